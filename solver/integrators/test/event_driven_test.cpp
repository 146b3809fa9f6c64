// Closed-form checks of the event-driven method (8.3): exact inside modes, events where a
// complementarity variable reaches zero, jumps for inconsistent states, output grid (SPEC §3).
#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "solver/integrators/transient.h"
#include "tests/support/netlist_builder.h"

namespace lcs {
namespace {

using testing::NetlistBuilder;
constexpr double kPi = 3.141592653589793238462643;

struct EventRun {
  MemorySink sink;
  TransientSummary summary;
  std::vector<double> event_times;  // rows that are not multiples of the output step
};

EventRun run_event(const Netlist& netlist, const std::vector<Probe>& probes, double tstep,
                   double tstop, bool uic, double rtol = 0, std::size_t mode_cache_bytes = 0) {
  ModelOptions mo;
  mo.t1 = tstop;
  CircuitModel model = CircuitModel::build(netlist, mo);
  TransientOptions o;
  o.method = "event";
  o.method_options.rtol = rtol;
  o.method_options.event_mode_cache_bytes = mode_cache_bytes;
  o.step = tstep;
  o.tstop = tstop;
  o.uic = uic;
  EventRun r;
  r.summary = run_transient(model, model.output_map(probes), o, r.sink);
  for (double t : r.sink.times) {
    const double k = std::round(t / tstep);
    if (std::abs(t - k * tstep) > 1e-9 * tstep) r.event_times.push_back(t);
  }
  return r;
}

Probe v(const std::string& node) { return {Probe::Kind::NodeVoltage, node, "", {}}; }
Probe i(const std::string& element) { return {Probe::Kind::ElementCurrent, element, "", {}}; }

// Every multiple of the output step is a row, rows strictly increase (SPEC §3).
void expect_grid_rows(const EventRun& r, double tstep, double tstop) {
  const long n = std::lround(tstop / tstep);
  long found = 0;
  for (size_t k = 0; k < r.sink.times.size(); ++k) {
    if (k > 0) {
      ASSERT_GT(r.sink.times[k], r.sink.times[k - 1]) << "row " << k;
    }
    const double t = r.sink.times[k];
    if (std::abs(t - std::round(t / tstep) * tstep) <= 1e-9 * tstep) ++found;
  }
  EXPECT_EQ(found, n + 1);
  EXPECT_EQ(r.sink.times.back(), tstop);
}

// Siconos' diode bridge on a charged LC tank (circuits/lc_tank_bridge.cir): whatever pair of
// diodes conducts, the tank sees R, so v'' + v'/(RC) + v/(LC) = 0 exactly. Acceptance: within
// 1e-9 relative of the closed form (measured 1.05e-13), with an event at every zero crossing.
TEST(EventDriven, LcTankBridgeMatchesTheClosedFormTo1e9) {
  NetlistBuilder b;
  b.tran(1e-6, 5e-3, true);
  b.l("l1", "a", "0", 10e-3, 0.0).c("c1", "a", "0", 1e-6, 10.0);
  b.d("d1", "a", "p").d("d2", "n", "a").d("d3", "0", "p").d("d4", "n", "0");
  b.r("r1", "p", "n", 1e3);
  EventRun r = run_event(b.build(), {v("a"), i("d1"), i("d2")}, 1e-6, 5e-3, true);
  const double R = 1e3, L = 10e-3, C = 1e-6, v0 = 10;
  const double alpha = 1 / (2 * R * C), wd = std::sqrt(1 / (L * C) - alpha * alpha);
  auto exact = [&](double t) {
    return std::exp(-alpha * t) * (v0 * std::cos(wd * t) - alpha * v0 / wd * std::sin(wd * t));
  };
  double worst = 0;
  for (size_t k = 0; k < r.sink.times.size(); ++k)
    worst = std::max(worst, std::abs(r.sink.rows[k](0) - exact(r.sink.times[k])) / v0);
  EXPECT_LT(worst, 1e-9);
  expect_grid_rows(r, 1e-6, 5e-3);
  // Zero crossings of v: tan(wd t) = wd/alpha, t_k = (atan(wd/alpha) + k pi)/wd.
  std::vector<double> crossings;
  for (int k = 0;; ++k) {
    const double t = (std::atan(wd / alpha) + k * kPi) / wd;
    if (t > 5e-3) break;
    crossings.push_back(t);
  }
  ASSERT_EQ(r.event_times.size(), crossings.size());
  for (size_t k = 0; k < crossings.size(); ++k)
    EXPECT_NEAR(r.event_times[k], crossings[k], 1e-15) << "crossing " << k;
  EXPECT_EQ(r.summary.stepper.events, static_cast<long>(crossings.size()));
}

// An RC charged through a diode from a DC source (capacitor empty, UIC): the diode stays on and
// v(t) = (V - VON)(1 - exp(-t/tau)), tau = (R + RON) C, at every row to rounding.
TEST(EventDriven, RcThroughDiodeIsExact) {
  const double V = 10, VON = 0.7, RON = 10, R = 1e3, C = 1e-6, tau = (R + RON) * C;
  NetlistBuilder b;
  b.tran(2e-5, 5e-3, true);
  b.v("v1", "in", "0", NetlistBuilder::dc(V)).d("d1", "in", "a", VON, RON);
  b.r("r1", "a", "out", R).c("c1", "out", "0", C, 0.0);
  EventRun r = run_event(b.build(), {v("out"), i("d1")}, 2e-5, 5e-3, true);
  ASSERT_EQ(r.sink.times.size(), 251u);
  for (size_t k = 0; k < r.sink.times.size(); ++k) {
    const double t = r.sink.times[k], ex = (V - VON) * (1 - std::exp(-t / tau));
    EXPECT_NEAR(r.sink.rows[k](0), ex, 1e-12 * V) << "t = " << t;
    EXPECT_NEAR(r.sink.rows[k](1), (V - VON - ex) / (R + RON), 1e-12 * V / R) << "t = " << t;
  }
  EXPECT_EQ(r.summary.stepper.events, 0);
}

// Half-wave rectifier into a resistor (no states): v_out = R max(0, v_in - VON)/(R + RON). The
// diode switches where 10 sin(wt) = VON; the events must sit there to near machine precision.
TEST(EventDriven, ResistiveRectifierSwitchesWhereTheSourceCrossesTheThreshold) {
  const double VA = 10, f = 50, VON = 0.7, RON = 0.5, R = 100, tstop = 40e-3, tstep = 1e-4;
  NetlistBuilder b;
  b.tran(tstep, tstop, false);
  b.v("v1", "in", "0", NetlistBuilder::sin(0, VA, f)).d("d1", "in", "out", VON, RON);
  b.r("r1", "out", "0", R);
  EventRun r = run_event(b.build(), {v("out"), i("d1")}, tstep, tstop, false);
  const double w = 2 * kPi * f, t_on = std::asin(VON / VA) / w, t_off = (kPi - std::asin(VON / VA)) / w;
  const std::vector<double> expected = {t_on, t_off, t_on + 1 / f, t_off + 1 / f};
  ASSERT_EQ(r.event_times.size(), expected.size());
  for (size_t k = 0; k < expected.size(); ++k)
    EXPECT_NEAR(r.event_times[k], expected[k], 1e-15) << "event " << k;
  for (size_t k = 0; k < r.sink.times.size(); ++k) {
    const double vin = VA * std::sin(w * r.sink.times[k]);
    const double ex = R * std::max(0.0, vin - VON) / (R + RON);
    EXPECT_NEAR(r.sink.rows[k](0), ex, 1e-11 * VA) << "t = " << r.sink.times[k];
    EXPECT_GE(r.sink.rows[k](1), -1e-15);  // complementarity: the diode current never reverses
  }
  expect_grid_rows(r, tstep, tstop);
}

// A PULSE with zero-length edges (jumps) charges a capacitor through a diode; while the pulse is
// low the diode blocks and the capacitor holds. Breakpoints restart the mode at the jumps.
TEST(EventDriven, PulseJumpsChargeAndHold) {
  const double V = 5, VON = 0.7, R = 1e3, C = 1e-6, tau = R * C;
  NetlistBuilder b;
  b.tran(1e-5, 8e-3, true);
  b.v("v1", "in", "0", NetlistBuilder::pulse({0, V, 1e-3, 0, 0, 2e-3, 4e-3}));
  b.d("d1", "in", "a", VON, 0).r("r1", "a", "out", R).c("c1", "out", "0", C, 0.0);
  EventRun r = run_event(b.build(), {v("out")}, 1e-5, 8e-3, true);
  const double v1 = (V - VON) * (1 - std::exp(-2e-3 / tau));  // held from 3 ms to 5 ms
  auto exact = [&](double t) {
    if (t <= 1e-3) return 0.0;
    if (t <= 3e-3) return (V - VON) * (1 - std::exp(-(t - 1e-3) / tau));
    if (t <= 5e-3) return v1;
    if (t <= 7e-3) return (V - VON) - (V - VON - v1) * std::exp(-(t - 5e-3) / tau);
    return (V - VON) - (V - VON - v1) * std::exp(-2e-3 / tau);
  };
  for (size_t k = 0; k < r.sink.times.size(); ++k)
    EXPECT_NEAR(r.sink.rows[k](0), exact(r.sink.times[k]), 1e-12 * V) << "t = " << r.sink.times[k];
  expect_grid_rows(r, 1e-5, 8e-3);
}

// An inconsistent initial state (UIC): a capacitor at 5 V across an ideal diode with VON = 0.7
// and RON = 0 discharges impulsively to 0.7 V at t = 0 (the impulse LCP of 4.5), then the diode
// blocks and the capacitor decays through R: v = 0.7 exp(-t/RC).
TEST(EventDriven, InconsistentInitialStateJumps) {
  const double VON = 0.7, R = 1e3, C = 1e-6;
  NetlistBuilder b;
  b.tran(1e-5, 3e-3, true);
  b.c("c1", "a", "0", C, 5.0).d("d1", "a", "0", VON, 0).r("r1", "a", "0", R);
  EventRun r = run_event(b.build(), {v("a"), i("d1")}, 1e-5, 3e-3, true);
  ASSERT_FALSE(r.sink.times.empty());
  EXPECT_NEAR(r.sink.rows[0](0), VON, 1e-14);
  for (size_t k = 0; k < r.sink.times.size(); ++k) {
    EXPECT_NEAR(r.sink.rows[k](0), VON * std::exp(-r.sink.times[k] / (R * C)), 1e-13)
        << "t = " << r.sink.times[k];
    EXPECT_NEAR(r.sink.rows[k](1), 0.0, 1e-15);
  }
}

// A capacitor on an RON = 0 diode (the index-one constraint v(a) = u - VON holds while it
// conducts) and a PWL source that jumps at a grid time tb = k TSTEP that rounding puts on either
// side: 161e-6 / 7e-6 is just above 23 while 23 * 7e-6 == 161e-6, and 5 * 1e-6 is just below
// 5e-6. A grid time read the source on the wrong side of the jump for the mode it was in, and the
// projection onto that mode's constraint moved the capacitor to the other side's u - VON: after
// a fall from 5 V to 0 (the capacitor must hold 4.3 V and discharge through R) it went to
// -0.7 V and stayed there; at a step from 5 V to 6 V (the capacitor jumps to 5.3 V) the row at
// tb showed the old 4.3 V.
TEST(EventDriven, SourceJumpAtAGridTimeThatRoundsEitherWayKeepsTheCapacitor) {
  const double R = 10e3, C = 1e-6, VON = 0.7, tstop = 350e-6;
  struct Case {
    double tstep, tb;  // tb as a netlist gives it (one decimal conversion)
    int k;
    double before, after;
  };
  for (const Case& c : {Case{7e-6, 161e-6, 23, 5, 0}, Case{1e-6, 5e-6, 5, 5, 6}}) {
    SCOPED_TRACE("jump at " + std::to_string(c.tb) + " to " + std::to_string(c.after));
    ASSERT_TRUE(c.tb / c.tstep > c.k || c.k * c.tstep < c.tb);  // the rounding this is about
    NetlistBuilder b;
    b.tran(c.tstep, tstop, false);
    Waveform pwl;
    pwl.kind = Waveform::Kind::Pwl;
    pwl.params = {0, c.before, c.tb, c.before, c.tb, c.after};
    b.v("v1", "in", "0", pwl).d("d1", "in", "a", VON, 0).c("c1", "a", "0", C).r("r1", "a", "0", R);
    EventRun r = run_event(b.build(), {v("in"), v("a"), i("d1")}, c.tstep, tstop, false);
    expect_grid_rows(r, c.tstep, tstop);
    for (size_t n = 0; n < r.sink.times.size(); ++n) {
      const double t = r.sink.times[n];
      const bool before = t < c.tb && std::abs(t - c.tb) > 1e-9 * c.tstep;
      const double held = c.before - VON;
      double va = held;
      if (!before) va = c.after - VON >= held ? c.after - VON : held * std::exp(-(t - c.tb) / (R * C));
      const bool on = before || c.after - VON >= held;
      EXPECT_EQ(r.sink.rows[n](0), before ? c.before : c.after) << "t = " << t;
      EXPECT_NEAR(r.sink.rows[n](1), va, 1e-12 * 5) << "t = " << t;
      EXPECT_NEAR(r.sink.rows[n](2), on ? va / R : 0.0, 1e-15) << "t = " << t;
    }
  }
}

// The same circuit with a PULSE whose fall is at TSTOP: the jump belongs to the last row (values
// are right-continuous), where the diode blocks and the capacitor still holds 4.3 V. The corner
// at TSTOP was not a breakpoint, so the last grid time read the source after the fall in the
// conducting mode and printed v(a) = -0.7 V with a diode current of -70 uA.
TEST(EventDriven, SourceJumpAtTstopIsInTheLastRow) {
  const double VON = 0.7;
  NetlistBuilder b;
  b.tran(1e-5, 6e-3, true);
  b.v("v1", "in", "0", NetlistBuilder::pulse({0, 5, 1e-3, 0, 0, 1e-3, 2e-3}));
  b.d("d1", "in", "a", VON, 0).c("c1", "a", "0", 1e-6, 0.0).r("r1", "a", "0", 10e3);
  EventRun r = run_event(b.build(), {v("a"), i("d1")}, 1e-5, 6e-3, true);
  expect_grid_rows(r, 1e-5, 6e-3);
  for (size_t k = 0; k < r.sink.times.size(); ++k) {
    EXPECT_GE(r.sink.rows[k](0), 0.0) << "t = " << r.sink.times[k];
    EXPECT_GE(r.sink.rows[k](1), -1e-15) << "t = " << r.sink.times[k];
  }
  EXPECT_NEAR(r.sink.rows.back()(0), 5 - VON, 1e-12 * 5);
  EXPECT_NEAR(r.sink.rows.back()(1), 0.0, 1e-15);
}

// The last row is at TSTOP exactly (SPEC §3: TSTOP included), also when TSTOP / TSTEP is a
// whole number that k * TSTEP misses in the last bits: 650 * 1e-5 > 6.5e-3.
TEST(EventDriven, LastRowIsAtTstopExactly) {
  for (double tstop : {6.5e-3, 6e-3, 5.5e-3, 2.9e-3}) {
    SCOPED_TRACE("TSTOP " + std::to_string(tstop));
    const double tstep = 1e-5;
    NetlistBuilder b;
    b.tran(tstep, tstop, true);
    b.v("v1", "in", "0", NetlistBuilder::dc(10)).d("d1", "in", "a", 0.7, 10);
    b.r("r1", "a", "out", 1e3).c("c1", "out", "0", 1e-6, 0.0);
    EventRun r = run_event(b.build(), {v("out")}, tstep, tstop, true);
    expect_grid_rows(r, tstep, tstop);
  }
}

// A long run whose switches all fall on grid times: VON = 0 and a 50 Hz sine crossing zero every
// 10 ms with TSTEP = 1 ms, for 20 s (1000 periods). At the grid time the sources are read from
// the waveform again, which differs from the propagated sine by rounding; a diode current found
// slightly negative there was excused as "starting just below zero" although it was falling, so
// the turn-off was never seen: from 8.05 s on, the diode conducted with a negative current for
// whole half periods (at 8.051 s, i(d1) = -31 mA).
TEST(EventDriven, LongRunWithSwitchesOnGridTimesMissesNone) {
  const double R = 100, tstep = 1e-3, tstop = 20;
  NetlistBuilder b;
  b.tran(tstep, tstop, false);
  b.v("v1", "in", "0", NetlistBuilder::sin(0, 10, 50)).d("d1", "in", "out", 0, 0).r("r1", "out", "0", R);
  EventRun r = run_event(b.build(), {v("in"), i("d1")}, tstep, tstop, false);
  EXPECT_EQ(r.sink.times.back(), tstop);  // (the events sit within rounding of grid times)
  long bad = 0;
  for (size_t k = 0; k < r.sink.times.size(); ++k) {
    const double u = r.sink.rows[k](0), id = r.sink.rows[k](1);
    if (std::abs(id - std::max(0.0, u) / R) > 1e-12) {
      if (bad++ < 5) ADD_FAILURE() << "t = " << r.sink.times[k] << ": u = " << u << ", i(d1) = " << id;
    }
  }
  EXPECT_EQ(bad, 0);
  // A switch at every zero crossing, t = 10 ms ... 20 s (the last one at TSTOP may or may not
  // count, by rounding).
  EXPECT_GE(r.summary.stepper.mode_switches, 1999);
  EXPECT_LE(r.summary.stepper.events, 2000);
}

// A 10 kHz sine into an ideal diode and 1 ohm: i(d1) = max(0, u) at every row, events included,
// and each event a switch. The sine's companion matrix was [0 1; -ω² 0]: its exponentials over
// a step carried errors of 1e-16 ω² h relative to their small entries, so between grid times the
// propagated source was off by 4e-9 of its amplitude (i(d1) 4.2e-8 A off at an event row with
// TSTEP = 1 us), and every switch cost an extra event: the first located where the propagated
// source crossed zero, the restart (reading the waveform) finding nothing there.
TEST(EventDriven, FastSineIsPropagatedToRoundingBetweenGridTimes) {
  const double A = 9;
  for (double tstep : {10e-6, 1e-6}) {
    SCOPED_TRACE("TSTEP " + std::to_string(tstep));
    NetlistBuilder b;
    b.tran(tstep, 1e-3, false);
    b.v("v1", "in", "0", NetlistBuilder::sin(0, A, 10e3)).d("d1", "in", "out", 0, 0);
    b.r("r1", "out", "0", 1);
    EventRun r = run_event(b.build(), {v("in"), i("d1")}, tstep, 1e-3, false);
    for (size_t n = 0; n < r.sink.times.size(); ++n)
      EXPECT_NEAR(r.sink.rows[n](1), std::max(0.0, r.sink.rows[n](0)), 1e-12 * A)
          << "t = " << r.sink.times[n];
    EXPECT_EQ(r.summary.stepper.events, r.summary.stepper.mode_switches);
    EXPECT_GE(r.summary.stepper.mode_switches, 19);  // a zero crossing every 50 us
    EXPECT_LE(r.summary.stepper.mode_switches, 20);
  }
}

// A DC restorer with an ideal clamp (RON = 0, VON = 0): the clamp charges C1 while the 10 kHz
// source rises and releases at its peak, where its current reaches zero with the voltage w
// across it at zero and w' = 0 too (w'' > 0 decides, 8.3.3). The state the release leaves
// has w a rounding below zero and falling within the mode check's slope tolerance; refusing to
// excuse it (as for a plainly falling constraint) made every step an event at the same
// instant: "event chattering" at 25 us.
TEST(EventDriven, ClampReleasingAtTheSourcePeakDoesNotChatter) {
  NetlistBuilder b;
  b.tran(1e-5, 1e-3, true);
  b.v("v1", "n1", "0", NetlistBuilder::sin(0, 9, 10e3)).c("c1", "n1", "n3", 1e-6);
  b.c("c2", "n3", "n2", 0.01e-6).r("r4", "n2", "0", 10).d("d6", "n3", "0", 0, 0);
  EventRun r = run_event(b.build(), {v("n3"), i("d6")}, 1e-5, 1e-3, true);
  expect_grid_rows(r, 1e-5, 1e-3);
  for (size_t n = 0; n < r.sink.times.size(); ++n) {
    EXPECT_LE(r.sink.rows[n](0), 1e-12 * 9) << "t = " << r.sink.times[n];
    EXPECT_GE(r.sink.rows[n](1), -1e-12) << "t = " << r.sink.times[n];
  }
  // The release at 25 us, and later re-engagements near the peaks as C2 and R4 bleed C1.
  EXPECT_LE(r.summary.stepper.events, 2 * 10);
}

// Steep source edges: a PULSE with 1 ps edges (u' = 5e12 V/s) charges a capacitor through an
// RON = 0 diode. At the start of the rise (1 ms) the diode still blocks (u = 0 < VON + v(a))
// for another 0.14 ps. The rounding floor of the consistency check was 1e-13 |[x; σ]| with the
// slope u' in it, so it accepted the conducting mode off by 0.7 V and projected the capacitor to
// u - VON = -0.7 V: the row at 1 ms read v(a) = -0.7 V, i(d1) = 5e6 A.
TEST(EventDriven, SteepEdgeDoesNotSwampTheConsistencyCheck) {
  const double VON = 0.7, R = 10e3, C = 1e-6;
  NetlistBuilder b;
  b.tran(1e-5, 6.5e-3, false);
  b.v("v1", "in", "0", NetlistBuilder::pulse({0, 5, 1e-3, 1e-12, 1e-12, 1e-3, 2e-3}));
  b.d("d1", "in", "a", VON, 0).c("c1", "a", "0", C).r("r1", "a", "0", R);
  EventRun r = run_event(b.build(), {v("a"), i("d1")}, 1e-5, 6.5e-3, false);
  expect_grid_rows(r, 1e-5, 6.5e-3);
  const double held = 5 - VON, fall = 2e-3 + 1e-12;  // the fall starts 1 ms + TR later
  for (size_t n = 0; n < r.sink.times.size(); ++n) {
    const double t = r.sink.times[n];
    const double tau = std::fmod(t - 1e-3, 2e-3);  // phase in the period
    if (t <= 1e-3) {  // before the first rise, and its first instant
      EXPECT_EQ(r.sink.rows[n](0), 0.0) << "t = " << t;
      EXPECT_EQ(r.sink.rows[n](1), 0.0) << "t = " << t;
    } else if (tau > 2e-12 && tau < 1e-3 - 1e-9) {  // on the plateau: held at 5 V - VON
      EXPECT_NEAR(r.sink.rows[n](0), held, 1e-12 * 5) << "t = " << t;
      EXPECT_NEAR(r.sink.rows[n](1), held / R, 1e-15) << "t = " << t;
    } else if (tau > 1e-3 + 2e-12) {  // low: the diode blocks, the capacitor discharges
      const double after = std::fmod(t - fall, 2e-3);
      EXPECT_NEAR(r.sink.rows[n](0), held * std::exp(-after / (R * C)), 1e-12 * 5) << "t = " << t;
      EXPECT_EQ(r.sink.rows[n](1), 0.0) << "t = " << t;
    }
    EXPECT_GE(r.sink.rows[n](0), 0.0) << "t = " << t;
    EXPECT_GE(r.sink.rows[n](1), 0.0) << "t = " << t;
  }
}

// A node reached only through diodes that never conduct (n2: anode of three diodes, nothing
// feeds it), next to a high-pass C-R driven by PULSE jumps. At the jumps the switching LCP
// names a mode with the RON = 0 diode d0 blocking and the others off, which leaves n2 floating
// (not well posed), and its other solution is degenerate (d4 at z = w = 0). The fallback only
// tried pairs at zero in the previous mode, so the run stopped at the second rise (0.3 ms) with
// "no consistent mode after a switching event (pairs at zero: d0)".
TEST(EventDriven, FloatingNodeBehindDiodesSurvivesSourceJumps) {
  const double R = 10e3, C = 10e-6, lo = -1.5, hi = 4.8;
  NetlistBuilder b;
  b.tran(1e-5, 1e-3, false);
  b.v("v1", "n1", "0", NetlistBuilder::pulse({lo, hi, 0, 0, 0, 100e-6, 300e-6}));
  b.c("c1", "n1", "n4", C).r("r2", "n4", "0", R);
  b.d("d0", "n2", "n4", 0.7, 0).d("d4", "n2", "0", 0.5, 1).d("d5", "n2", "n1", 0.5, 1);
  EventRun r = run_event(b.build(), {v("n1"), v("n4"), v("n2"), i("d0"), i("d4"), i("d5")}, 1e-5,
                         1e-3, false);
  expect_grid_rows(r, 1e-5, 1e-3);
  // The diodes never conduct; v(n4) is the high-pass response to the jumps (the operating point
  // has the capacitor charged to u(0) = hi).
  const std::vector<std::pair<double, double>> jumps = {
      {100e-6, lo - hi}, {300e-6, hi - lo}, {400e-6, lo - hi}, {600e-6, hi - lo},
      {700e-6, lo - hi}, {900e-6, hi - lo}, {1000e-6, lo - hi}};
  for (size_t n = 0; n < r.sink.times.size(); ++n) {
    const double t = r.sink.times[n];
    double v4 = 0;
    for (auto [tk, du] : jumps)
      if (t >= tk - 1e-9 * 1e-5) v4 += du * std::exp(-(t - tk) / (R * C));
    EXPECT_NEAR(r.sink.rows[n](1), v4, 1e-12 * hi) << "t = " << t;
    for (int k = 3; k < 6; ++k) EXPECT_EQ(r.sink.rows[n](k), 0.0) << "t = " << t;
    // n2 below every diode's threshold
    const double u = r.sink.rows[n](0), v2 = r.sink.rows[n](2);
    EXPECT_LE(v2, std::min({v4 + 0.7, 0.5, u + 0.5}) + 1e-12) << "t = " << t;
  }
}

// A capacitive divider (a capacitor/voltage-source loop: the LCS state is x = x_phys - Gamma u)
// driven by PULSE jumps, off the grid and on it: at a jump the charge on the middle node is
// conserved, so v(n2) jumps by du C1/(C1 + C2) = du/2 and decays with tau = R (C1 + C2). The
// breakpoint kept x_phys continuous instead of x: v(n2) jumped by the whole du (0.9975 V five
// microseconds after a 1 V step, implicit Euler 0.496 V).
TEST(EventDriven, CapacitiveDividerConservesChargeAtSourceJumps) {
  const double C1 = 1e-6, C2 = 1e-6, R = 1e3, tau = R * (C1 + C2), tstep = 1e-5, tstop = 400e-6;
  for (double td : {15e-6, 20e-6}) {
    SCOPED_TRACE("TD = " + std::to_string(td));
    NetlistBuilder b;
    b.tran(tstep, tstop, false);
    b.v("v1", "n1", "0", NetlistBuilder::pulse({0, 1, td, 0, 0, 50e-6, 100e-6}));
    b.c("c1", "n1", "n2", C1).c("c2", "n2", "0", C2).r("r2", "n2", "0", R);
    EventRun r = run_event(b.build(), {v("n2")}, tstep, tstop, false);
    expect_grid_rows(r, tstep, tstop);
    for (size_t n = 0; n < r.sink.times.size(); ++n) {
      const double t = r.sink.times[n];
      double v2 = 0;
      for (int k = 0; td + 50e-6 * k <= t + 1e-9 * tstep; ++k)
        v2 += (k % 2 == 0 ? 1 : -1) * C1 / (C1 + C2) * std::exp(-(t - td - 50e-6 * k) / tau);
      EXPECT_NEAR(r.sink.rows[n](0), v2, 1e-12) << "t = " << t;
    }
  }
}

// A 1 us PULSE edge (2.6e6 V/s) crossing zero into an RON = 0 diode (found by a random-circuit
// comparison with implicit Euler; d2 hangs off a node with nothing else). The event is located
// to a bracket of 2^-43 TSTEP, in which the edge moves u by 3e-12 V, so the restart sees the
// diode's w at -1.4e-12 V: beyond the mode check's rounding tolerance (1e-13 V) once a ramp's
// slope no longer inflated it, and not among the pairs "at zero" that the mode search flips:
// "no consistent mode after a switching event (pairs at zero: d2)" at 0.79 us. The tolerance
// now includes |g'| times the bracket.
TEST(EventDriven, SteepRampCrossingIsAtZeroWithinTheEventBracket) {
  NetlistBuilder b;
  b.tran(1e-5, 1e-3, true);
  b.v("v1", "n1", "0", NetlistBuilder::pulse({-2.09639, 0.542138, 0, 1e-6, 1e-6, 100e-6, 300e-6}));
  b.d("d0", "n1", "n4", 0, 0).d("d1", "n2", "n1", 0.7, 0).d("d2", "n3", "n4", 0.5, 1);
  b.c("c3", "n1", "n2", 1e-6).r("rgn2", "n2", "0", 1000).r("rgn4", "n4", "0", 100);
  EventRun r = run_event(b.build(), {v("n1"), v("n4"), i("d0"), i("d1")}, 1e-5, 1e-3, true);
  expect_grid_rows(r, 1e-5, 1e-3);
  for (size_t n = 0; n < r.sink.times.size(); ++n) {
    // d0 into 100 ohm: v(n4) = max(0, u) (d2 carries nothing: n3 is a dead end).
    EXPECT_NEAR(r.sink.rows[n](1), std::max(0.0, r.sink.rows[n](0)), 1e-12 * 3) << "t = " << r.sink.times[n];
    EXPECT_GE(r.sink.rows[n](2), -1e-15) << "t = " << r.sink.times[n];
    EXPECT_GE(r.sink.rows[n](3), -1e-15) << "t = " << r.sink.times[n];
  }
}

// An inductor current reversing through two antiparallel RON = 0 diodes (found by a
// random-circuit comparison with implicit Euler). d0 (VON 0.7) carries the initial -4 mA; when
// the current reaches zero, d0 opens and its voltage jumps (an L diode), so d3 (VON 0) must close
// at the same instant. The switching LCP's deciding entry is O(eta) and sat at its tolerance, so
// it named a mode with neither changed, and d3 was not "at zero" in it: "no consistent mode after
// a switching event (pairs at zero: d0)" at 0.53 us. The mode search now falls back to every pair
// (circuits with at most 10 diodes).
TEST(EventDriven, InductorCurrentReversesThroughAntiparallelIdealDiodes) {
  const double V = 5, L = 1e-3, R = 1e3, i0 = -4e-3, VON = 0.7, tau = L / R;
  NetlistBuilder b;
  b.tran(1e-5, 1e-4, true);
  b.v("v1", "n1", "0", NetlistBuilder::dc(V)).l("l1", "n1", "n3", L, i0);
  b.d("d0", "n2", "n3", VON, 0).d("d3", "n3", "n2", 0, 0).r("rg", "n2", "0", R);
  EventRun r = run_event(b.build(), {i("l1"), i("d0"), i("d3")}, 1e-5, 1e-4, true);
  // d0 conducts: L i' = V + VON - R i; then d3: L i' = V - R i.
  const double t1 = tau * std::log((i0 - (V + VON) / R) / -((V + VON) / R));
  ASSERT_EQ(r.event_times.size(), 1u);
  EXPECT_NEAR(r.event_times[0], t1, 1e-15);
  for (size_t n = 0; n < r.sink.times.size(); ++n) {
    const double t = r.sink.times[n];
    const double il = t < t1 ? (V + VON) / R + (i0 - (V + VON) / R) * std::exp(-t / tau)
                             : V / R * (1 - std::exp(-(t - t1) / tau));
    EXPECT_NEAR(r.sink.rows[n](0), il, 1e-14) << "t = " << t;
    EXPECT_NEAR(r.sink.rows[n](1), t < t1 ? -il : 0.0, 1e-14) << "t = " << t;
    EXPECT_NEAR(r.sink.rows[n](2), t < t1 ? 0.0 : il, 1e-14) << "t = " << t;
  }
}

// Random circuit 92 of tests/random, reduced. When d2 turns off (0.40000598 s) the switching
// LCP is degenerate (d2 at zero) and d3's row, whose only other path is the 3.9 kH inductor, has
// all its entries O(eta): Lemke's final basis missed feas_tol ("numerical failure") and the run
// ended there with exit 3, while implicit Euler ran through. The LCP's best point is now only
// the first guess of the mode search; d3 then starts conducting at 0.4132 s.
TEST(EventDriven, IllConditionedSwitchingLcpFallsBackToTheModeSearch) {
  const double tstep = 1e-3, tstop = 0.8;
  NetlistBuilder b;
  b.tran(tstep, tstop, false);
  Waveform pwl;
  pwl.kind = Waveform::Kind::Pwl;
  pwl.params = {0, -1.2, 0.4, 6.3, 0.8, -3.5};
  b.v("v1", "in", "0", pwl).c("c1", "a", "in", 2.7e-6).r("r3", "b", "a", 12e3).r("r4", "k", "b", 22e3);
  b.i("i1", "0", "k", NetlistBuilder::dc(-4.6e-3)).l("l2", "m", "b", 3.9e3);
  b.d("d1", "0", "k", 0.159, 3.9).d("d2", "a", "k", 0.102, 0.33).d("d3", "0", "m", 0.314, 100);
  const Netlist net = b.build();
  const std::vector<Probe> probes = {v("k"), v("m"), v("b"), i("d2"), i("d3")};
  EventRun r = run_event(net, probes, tstep, tstop, false);
  expect_grid_rows(r, tstep, tstop);
  ASSERT_EQ(r.event_times.size(), 3u);  // d2 on, d2 off, d3 on
  EXPECT_NEAR(r.event_times[1], 0.400006, 1e-6);
  EXPECT_NEAR(r.event_times[2], 0.413158, 1e-6);

  // Implicit Euler at h = 10 us agrees within 1e-3 of each probe's range (measured: at most
  // 1.8e-4, v(m) at d3's turn-on; 2.3e-4 at 20 us).
  ModelOptions mo;
  mo.t1 = tstop;
  const CircuitModel model = CircuitModel::build(net, mo);
  TransientOptions o;
  o.method = "euler";
  o.step = 1e-5;
  o.tstop = tstop;
  MemorySink euler;
  run_transient(model, model.output_map(probes), o, euler);
  for (int p = 0; p < static_cast<int>(probes.size()); ++p) {
    double lo = INFINITY, hi = -INFINITY;
    for (const Eigen::VectorXd& row : r.sink.rows) lo = std::min(lo, row(p)), hi = std::max(hi, row(p));
    for (size_t n = 0; n < r.sink.times.size(); ++n) {
      const double t = r.sink.times[n];
      const long k = std::lround(t / o.step);
      if (std::abs(t - k * o.step) > 1e-9 * o.step) continue;  // an event between Euler's steps
      EXPECT_NEAR(r.sink.rows[n](p), euler.rows[static_cast<size_t>(k)](p), 1e-3 * (hi - lo))
          << probes[static_cast<size_t>(p)].name() << " at t = " << t;
    }
  }
}

// An ideal diode (VON = 0, RON = 0) in series with an inductor, driven by a PULSE whose 10 ns
// edges (3e8 V/s) cross zero between grid times: at a rising crossing the diode closes with its
// current i = 0 and i' = u/L = 0, so i'' = u'/L > 0 decides (8.3.3). The restart read the
// sources at the event time rounded to a double, up to ulp(t) from the instant the bisection
// located, which is more than the bracket (2^-43 TSTEP) once t is some hundreds of steps: where
// that put u before the crossing, i' was negative beyond rounding and the open diode's voltage
// falling, so no mode fitted: "no consistent mode after a switching event (pairs at zero: d1)"
// at 21 us at the 50 ns step (issue 9, circuits/flyback_converter.cir, whose transformer is
// irrelevant to it). Closed form: i = (U(t) - min U over [0, t]) / L with
// U = the integral of u (the diode reflects the current at zero); two events per period.
TEST(EventDriven, DiodeClosingOntoAnInductorAtARampZeroCrossing) {
  const double lo = -2, hi = 1, td = 1e-6, tr = 10e-9, pw = 5e-6, per = 10e-6, L = 1e-3;
  const double tstop = 200e-6;
  const int periods = 20;
  // Corners of u and U = integral of u at each (u is linear between them).
  std::vector<double> kt = {0}, ku = {lo};
  for (int k = 0; k < periods; ++k)
    for (auto [dt, u] : std::vector<std::pair<double, double>>{{0, lo}, {tr, hi}, {tr + pw, hi}, {2 * tr + pw, lo}}) {
      kt.push_back(td + k * per + dt);
      ku.push_back(u);
    }
  kt.push_back(tstop);
  ku.push_back(lo);
  std::vector<double> kU = {0};
  for (size_t c = 1; c < kt.size(); ++c) kU.push_back(kU.back() + (kt[c] - kt[c - 1]) * (ku[c] + ku[c - 1]) / 2);
  auto U = [&](double t) {
    size_t c = std::upper_bound(kt.begin(), kt.end(), t) - kt.begin();
    c = std::min(c, kt.size() - 1);
    const double s = (ku[c] - ku[c - 1]) / (kt[c] - kt[c - 1]), dt = t - kt[c - 1];
    return kU[c - 1] + dt * (ku[c - 1] + s * dt / 2);
  };
  std::vector<double> on, off;  // the rising zero crossings and the current's returns to zero
  for (int k = 0; k < periods; ++k) {
    on.push_back(td + k * per + tr * (-lo) / (hi - lo));
    const double fall_end = td + k * per + 2 * tr + pw;
    off.push_back(fall_end + (U(fall_end) - U(on.back())) / -lo);
  }
  auto current = [&](double t) {
    double low = std::min(0.0, U(t));
    for (double tc : on)
      if (tc <= t) low = std::min(low, U(tc));
    return (U(t) - low) / L;
  };
  for (double tstep : {5e-8, 1e-7, 2e-7}) {
    SCOPED_TRACE("step " + std::to_string(tstep));
    NetlistBuilder b;
    b.tran(tstep, tstop, true);
    b.v("v1", "in", "0", NetlistBuilder::pulse({lo, hi, td, tr, tr, pw, per}));
    b.d("d1", "in", "p", 0, 0).l("l1", "p", "0", L, 0.0);
    EventRun r = run_event(b.build(), {v("in"), i("d1")}, tstep, tstop, true);
    expect_grid_rows(r, tstep, tstop);
    // One event per switch, none repeated (a restart that read u on the wrong side of the
    // crossing could also accept the open mode and meet the same crossing again a step later).
    ASSERT_EQ(r.event_times.size(), 2u * periods);
    EXPECT_EQ(r.summary.stepper.events, 2 * periods);
    EXPECT_EQ(r.summary.stepper.mode_switches, 2 * periods);
    for (int k = 0; k < periods; ++k) {
      EXPECT_NEAR(r.event_times[2 * k], on[k], 1e-15) << "crossing " << k;
      EXPECT_NEAR(r.event_times[2 * k + 1], off[k], 1e-15) << "turn-off " << k;
    }
    // Peak 5 mA; measured: at most 8e-17 A off, events within 2e-19 s of the closed form.
    for (size_t n = 0; n < r.sink.times.size(); ++n) {
      const double t = r.sink.times[n];
      EXPECT_NEAR(r.sink.rows[n](1), current(t), 1e-14) << "t = " << t;
      EXPECT_GE(r.sink.rows[n](1), 0.0) << "t = " << t;
    }
  }
}

// Exponentials are cached per mode and dyadic step: a periodic circuit computes no new ones
// once every mode has been visited (bridge rectifier: the third and sixth period cost nothing).
TEST(EventDriven, PeriodicCircuitPaysSetupOncePerMode) {
  auto bridge = [](double tstop) {
    NetlistBuilder b;
    b.tran(2e-5, tstop, false);
    b.v("v1", "a", "0", NetlistBuilder::sin(0, 10, 50));
    b.d("d1", "a", "p", 0.7, 0.05).d("d2", "n", "a", 0.7, 0.05);
    b.d("d3", "0", "p", 0.7, 0.05).d("d4", "n", "0", 0.7, 0.05);
    b.c("cl", "p", "n", 100e-6).r("rl", "p", "n", 100);
    return b.build();
  };
  EventRun three = run_event(bridge(60e-3), {v("p")}, 2e-5, 60e-3, false);
  EventRun six = run_event(bridge(120e-3), {v("p")}, 2e-5, 120e-3, false);
  EXPECT_EQ(three.summary.stepper.factorisations, six.summary.stepper.factorisations);
  EXPECT_EQ(three.summary.stepper.modes, six.summary.stepper.modes);
  EXPECT_EQ(six.summary.stepper.events, 2 * three.summary.stepper.events + 1);
}

// The modes' budget (Impl::trim_modes): a run that keeps one mode at a time builds the others
// again when it comes back to them, to the same matrices, so the rows are the same to the bit.
TEST(EventDriven, ModesDroppedForTheBudgetAreBuiltAgainToTheSameRows) {
  NetlistBuilder b;
  b.tran(2e-5, 60e-3, false);
  b.v("v1", "a", "0", NetlistBuilder::sin(0, 10, 50));
  b.d("d1", "a", "p", 0.7, 0.05).d("d2", "n", "a", 0.7, 0.05);
  b.d("d3", "0", "p", 0.7, 0.05).d("d4", "n", "0", 0.7, 0.05);
  b.c("cl", "p", "n", 100e-6).r("rl", "p", "n", 100);
  const Netlist bridge = b.build();
  const EventRun kept = run_event(bridge, {v("p"), i("d1")}, 2e-5, 60e-3, false);
  const EventRun dropped = run_event(bridge, {v("p"), i("d1")}, 2e-5, 60e-3, false, 0, /*mode_cache_bytes=*/1);
  EXPECT_EQ(kept.summary.stepper.mode_evictions, 0);
  EXPECT_EQ(kept.summary.stepper.mode_rebuilds, 0);
  EXPECT_GT(kept.summary.stepper.mode_cache_budget_bytes, 1L << 20);
  EXPECT_EQ(dropped.summary.stepper.mode_cache_budget_bytes, 1);
  // Every switching leaves the last mode behind; each later visit builds it again.
  EXPECT_GE(dropped.summary.stepper.mode_evictions, dropped.summary.stepper.mode_switches - 1);
  EXPECT_GT(dropped.summary.stepper.mode_rebuilds, 0);
  EXPECT_EQ(dropped.summary.stepper.modes, kept.summary.stepper.modes);  // distinct modes
  EXPECT_LT(dropped.summary.stepper.mode_cache_peak_bytes, kept.summary.stepper.mode_cache_peak_bytes);
  ASSERT_EQ(dropped.sink.times, kept.sink.times);
  for (size_t k = 0; k < kept.sink.rows.size(); ++k) ASSERT_EQ(dropped.sink.rows[k], kept.sink.rows[k]) << k;
}

}  // namespace
}  // namespace lcs
