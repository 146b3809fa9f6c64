// The smooth method (8.2, SUNDIALS IDA) against closed forms: Shockley diodes with a resistor
// (Lambert W), an RC charged through one (Lambert W and a quadrature), the approach to the ideal
// diode as N -> 0, switching events, and circuits without states or without diodes.
#include <algorithm>
#include <cmath>
#include <functional>

#include <gtest/gtest.h>

#include "solver/integrators/smooth_method.h"
#include "solver/integrators/transient.h"
#include "solver/devices/diode.h"
#include "solver/model/smooth_netlist.h"
#include "tests/support/netlist_builder.h"

namespace lcs {
namespace {

using testing::NetlistBuilder;

constexpr double kPi = 3.14159265358979323846;

struct SmoothRun {
  MemorySink sink;
  TransientSummary summary;
  std::vector<double> column(const std::string& probe) const {
    const int c = sink.column(probe);
    std::vector<double> out;
    for (const Eigen::VectorXd& row : sink.rows) out.push_back(row(c));
    return out;
  }
};

// The circuit smooth integrates: every diode card's VON/RON with a Shockley diode of emission N.
Netlist shockley(const Netlist& netlist, double emission, double is = 1e-14) {
  SmoothingOptions o;
  o.emission = emission;
  o.saturation_current = is;
  return smooth_netlist(netlist, o);
}

SmoothRun simulate(const Netlist& netlist, const std::vector<std::string>& probes, double tstep,
             double tstop, bool uic, double rtol = 0, std::vector<double> extra = {}) {
  ModelOptions mo;
  mo.t1 = tstop;
  CircuitModel model = CircuitModel::build(netlist, mo);
  std::vector<Probe> ps;
  for (const std::string& p : probes) ps.push_back(parse_probe(p, {}));
  TransientOptions o;
  o.method = "smooth";
  o.method_options.rtol = rtol;
  o.step = tstep;
  o.tstop = tstop;
  o.uic = uic;
  o.extra_output_times = std::move(extra);
  SmoothRun r;
  r.summary = run_transient(model, model.output_map(ps), o, r.sink);
  return r;
}

// Principal branch of Lambert W for large arguments given as L = ln(x): w + ln(w) = L by Newton.
double lambert_w_of_exp(double L) {
  double w = L > 1 ? L - std::log(L) : std::exp(L);
  for (int it = 0; it < 100; ++it) {
    const double f = w + std::log(w) - L, step = f / (1 + 1 / w);
    w -= step;
    if (std::abs(step) <= 1e-16 * w) break;
  }
  return w;
}

// Current of a Shockley diode (IS, N Vt) in series with R across a voltage V (GMIN left out):
// i + IS = (N Vt / R) W((R IS / N Vt) exp((V + R IS) / N Vt)).
double series_current(double V, double R, double is, double nvt) {
  const double L = std::log(R * is / nvt) + (V + R * is) / nvt;
  return nvt / R * lambert_w_of_exp(L) - is;
}

// (a) DC source, resistor and Shockley diode: no states, one Newton solve per output time.
class ResistorAndDiode : public ::testing::TestWithParam<double> {};

TEST_P(ResistorAndDiode, CurrentIsTheLambertWClosedForm) {
  const double N = GetParam(), V = 5, R = 1e3, IS = 1e-14;
  NetlistBuilder b;
  b.v("v1", "in", "0", NetlistBuilder::dc(V)).r("r1", "in", "a", R).d("d1", "a", "0");
  SmoothRun r = simulate(shockley(b.build(), N, IS), {"i(d1)", "v(a)"}, 1e-4, 1e-3, false);
  const double exact = series_current(V, R, IS, N * kThermalVoltage);
  ASSERT_EQ(r.sink.times.size(), 11u);
  // GMIN (1e-12 S across the junction, left out of the closed form) moves the current by about
  // GMIN v(a) / (R i / N Vt): 1e-12 relative at N = 1 (measured 2e-15, 1e-12, 5e-12 for N =
  // 0.05, 1, 2).
  for (size_t k = 0; k < r.sink.times.size(); ++k) {
    EXPECT_NEAR(r.sink.rows[k](0), exact, 1e-10 * exact) << "N = " << N << ", row " << k;
    EXPECT_NEAR(r.sink.rows[k](1), V - R * exact, 1e-10 * V) << "N = " << N;
  }
}

INSTANTIATE_TEST_SUITE_P(Emission, ResistorAndDiode, ::testing::Values(0.05, 1.0, 2.0));

// (b) A capacitor charged from a DC source through R and a Shockley diode (N = 1, VON = 0.3 in
// series). For capacitor voltage v the current is the Lambert W form with V - VON - v, so the
// exact time to reach v is T(v) = C ∫_0^v du / i(u), integrated here by 8-point Gauss-Legendre
// between consecutive output voltages. A row (t, v) is off the solution by |T(v) - t| i(v) / C volts.
double rc_diode_error(double rtol) {
  const double V = 5, VON = 0.3, R = 1e3, C = 1e-6, IS = 1e-14, nvt = kThermalVoltage;
  NetlistBuilder b;
  b.v("v1", "in", "0", NetlistBuilder::dc(V)).r("r1", "in", "a", R).d("d1", "a", "out", VON, 0);
  b.c("c1", "out", "0", C, 0.0);
  SmoothRun r = simulate(shockley(b.build(), 1.0, IS), {"v(out)"}, 2e-5, 3e-3, true, rtol);
  auto current = [&](double v) { return series_current(V - VON - v, R, IS, nvt); };
  static const double x[8] = {-0.9602898564975363, -0.7966664774136267, -0.5255324099163290,
                              -0.1834346424956498, 0.1834346424956498,  0.5255324099163290,
                              0.7966664774136267,  0.9602898564975363};
  static const double w[8] = {0.1012285362903763, 0.2223810344533745, 0.3137066458778873,
                              0.3626837833783620, 0.3626837833783620, 0.3137066458778873,
                              0.2223810344533745, 0.1012285362903763};
  double T = 0, v_prev = 0, worst = 0;
  for (size_t k = 0; k < r.sink.times.size(); ++k) {
    const double v = r.sink.rows[k](0);
    const double mid = 0.5 * (v + v_prev), half = 0.5 * (v - v_prev);
    for (int j = 0; j < 8; ++j) T += w[j] * half * C / current(mid + half * x[j]);
    v_prev = v;
    worst = std::max(worst, std::abs(T - r.sink.times[k]) * current(v) / C);
  }
  EXPECT_GT(r.sink.rows.back()(0), 0.9 * (V - VON - 0.7));  // charged most of the way
  return worst;
}

TEST(RcThroughShockleyDiode, ErrorScalesWithTheTolerance) {
  // Measured: 1.6e-4 V at rtol 1e-4, 1.5e-6 V at 1e-6 (a factor 106 for 100 in rtol); below
  // rtol 1e-6 it falls more slowly (4.3e-7 at 1e-7, 7.7e-8 at 1e-8).
  const double coarse = rc_diode_error(1e-4), fine = rc_diode_error(1e-6);
  EXPECT_LT(coarse, 2 * 1e-4 * 5);  // within twice rtol of the 5 V scale
  EXPECT_LT(fine, 2 * 1e-6 * 5);
  EXPECT_GT(coarse / fine, 50.0) << coarse << " " << fine;
}

// (b2) Without UIC the run starts at the smoothed circuit's own operating point, not the ideal
// diodes' (VON = 0.7, RON = 0 would put v(a) at 0.7 V, and the capacitor would relax from there):
// the DC current through R and VON + Shockley is the Lambert W form, and every row stays at it.
// A capacitor voltage set by IC= is held at its value.
TEST(RestPoint, TheRunStartsAtTheSmoothCircuitsOwnOperatingPoint) {
  const double V = 5, VON = 0.7, R = 1e3, C = 1e-6, IS = 1e-14;
  NetlistBuilder b;
  b.v("v1", "in", "0", NetlistBuilder::dc(V)).r("r1", "in", "a", R).d("d1", "a", "0", VON, 0);
  b.c("c1", "a", "0", C);
  SmoothRun r = simulate(shockley(b.build(), 1.0, IS), {"v(a)"}, 1e-4, 1e-3, false);
  const double exact = V - R * series_current(V - VON, R, IS, kThermalVoltage);
  ASSERT_GT(exact, VON + 0.5);  // far from the ideal operating point
  ASSERT_EQ(r.sink.times.size(), 11u);
  for (size_t k = 0; k < r.sink.times.size(); ++k)
    EXPECT_NEAR(r.sink.rows[k](0), exact, 1e-8 * V) << "row " << k;
  EXPECT_TRUE(r.summary.warnings.empty());

  NetlistBuilder held;
  held.v("v1", "in", "0", NetlistBuilder::dc(V)).r("r1", "in", "a", R).d("d1", "a", "0", VON, 0);
  held.c("c1", "a", "0", C, 1.0);
  SmoothRun h = simulate(shockley(held.build(), 1.0, IS), {"v(a)"}, 1e-4, 1e-3, false);
  EXPECT_NEAR(h.sink.rows[0](0), 1.0, 1e-12);
  EXPECT_NEAR(h.sink.rows.back()(0), exact, 1e-6 * V);  // and charges to the operating point
}

// (b3) The rest point's pull (which makes a state with no DC equation unique) moves the determined
// states too: a 1 pF capacitor on the diode's node (A's entries 2e9 s^-1) beside a 100 uF one
// behind 1 kohm (10 s^-1). The pull, 1e-9 of A's largest entry, held v(b) 0.115 V toward the
// ideal diodes' operating point (a sixth of the 0.69 V between them); the polish without it takes
// that out. The slow capacitor carries no DC current, so every row is the fast node's Lambert W
// value.
TEST(RestPoint, ASlowCapacitorBesideAFastOneStartsAtTheOperatingPoint) {
  const double V = 5, VON = 0.7, R = 1e3, IS = 1e-14;
  NetlistBuilder b;
  b.v("v1", "in", "0", NetlistBuilder::dc(V)).r("r1", "in", "a", R).d("d1", "a", "0", VON, 0);
  b.c("c1", "a", "0", 1e-12).r("r2", "a", "b", 1e3).c("c2", "b", "0", 100e-6);
  SmoothRun r = simulate(shockley(b.build(), 1.0, IS), {"v(b)"}, 1e-4, 1e-3, false);
  const double exact = V - R * series_current(V - VON, R, IS, kThermalVoltage);
  ASSERT_GT(exact, VON + 0.5);
  ASSERT_EQ(r.sink.times.size(), 11u);
  for (size_t k = 0; k < r.sink.times.size(); ++k)
    EXPECT_NEAR(r.sink.rows[k](0), exact, 1e-8 * V) << "row " << k;
}

// (b4) Two series capacitors with no DC path (1 nF from the diode's node a to b, 100 nF from b to
// ground): DC leaves their split free, and the start takes least energy, v(b) = v(a) C1/(C1 + C2),
// as the ideal operating point does. A pull capped per row of A (tried) split them as
// 1/(C pull): v(b) 9.2 times too high, for the whole run.
TEST(RestPoint, SeriesCapacitorsWithoutADcPathTakeTheSplitOfLeastEnergy) {
  const double V = 5, R = 1e3, IS = 1e-14, C1 = 1e-9, C2 = 100e-9;
  NetlistBuilder b;
  b.v("v1", "in", "0", NetlistBuilder::dc(V)).r("r1", "in", "a", R).d("d1", "a", "0", 0.7, 0);
  b.c("c1", "a", "b", C1).c("c2", "b", "0", C2);
  SmoothRun r = simulate(shockley(b.build(), 1.0, IS), {"v(a)", "v(b)"}, 1e-6, 1e-5, false);
  ASSERT_EQ(r.sink.times.size(), 11u);
  const double va = V - R * series_current(V - 0.7, R, IS, kThermalVoltage);
  for (size_t k = 0; k < r.sink.times.size(); ++k) {
    EXPECT_NEAR(r.sink.rows[k](0), va, 1e-8 * V) << "row " << k;
    EXPECT_NEAR(r.sink.rows[k](1), va * C1 / (C1 + C2), 1e-6 * va * C1 / (C1 + C2)) << "row " << k;
  }
}

// (c) As N -> 0 the smooth diode tends to the ideal one. Half-wave rectifier into R (no states):
// ideal v(out) = max(0, v_in - VON) R / (R + RON). The smooth diode needs N Vt ln(1 + i/IS) more,
// so the error is proportional to N, largest at the peak current.
double rectifier_gap(double N, double* predicted) {
  const double A = 10, f = 50, VON = 0.7, RON = 0.1, R = 1e3, IS = 1e-14;
  NetlistBuilder b;
  b.v("v1", "in", "0", NetlistBuilder::sin(0, A, f)).d("d1", "in", "out", VON, RON);
  b.r("r1", "out", "0", R);
  SmoothRun r = simulate(shockley(b.build(), N, IS), {"v(in)", "v(out)", "i(d1)"}, 1e-4, 1 / f, false);
  double worst = 0, peak = 0;
  for (size_t k = 0; k < r.sink.times.size(); ++k) {
    const double vin = A * std::sin(2 * kPi * f * r.sink.times[k]);
    EXPECT_NEAR(r.sink.rows[k](0), vin, 1e-12 * A);
    const double ideal = std::max(0.0, vin - VON) * R / (R + RON);
    worst = std::max(worst, std::abs(r.sink.rows[k](1) - ideal));
    peak = std::max(peak, r.sink.rows[k](2));
  }
  *predicted = N * kThermalVoltage * std::log(1 + peak / IS) * R / (R + RON);
  return worst;
}

TEST(EmissionToZero, SmoothRectifierApproachesTheIdealOneLinearlyInN) {
  double p1 = 0, p2 = 0, p3 = 0;
  const double e1 = rectifier_gap(0.08, &p1), e2 = rectifier_gap(0.04, &p2),
               e3 = rectifier_gap(0.02, &p3);
  // Measured 57.0, 28.5 and 14.3 mV: ratios 0.50006 and 0.50003 (ln(i/IS) at the peak barely
  // moves as the gap shrinks).
  EXPECT_NEAR(e2 / e1, 0.5, 0.005) << e1 << " " << e2;
  EXPECT_NEAR(e3 / e2, 0.5, 0.005) << e2 << " " << e3;
  // And the gap is the one the Shockley law predicts at the peak current.
  EXPECT_NEAR(e1, p1, 1e-3 * p1);
  EXPECT_NEAR(e3, p3, 1e-3 * p3);
}

// (d) Events are the zero crossings of the diode current. Into a resistor the smooth diode's
// current is zero exactly when v_in = VON, so the crossings are known in closed form.
TEST(Events, AtTheCurrentZeroCrossingsOfAResistiveRectifier) {
  const double A = 10, f = 50, VON = 0.7;
  NetlistBuilder b;
  b.v("v1", "in", "0", NetlistBuilder::sin(0, A, f)).d("d1", "in", "out", VON, 0.1);
  b.r("r1", "out", "0", 1e3);
  SmoothRun r = simulate(shockley(b.build(), 0.05), {"i(d1)"}, 1e-4, 2 / f, false);
  const double on = std::asin(VON / A) / (2 * kPi * f);
  const std::vector<double> expected = {on, 0.5 / f - on, 1 / f + on, 1.5 / f - on};
  std::vector<double> events;
  for (size_t k = 0; k < r.sink.times.size(); ++k) {
    const double t = r.sink.times[k];
    if (t == std::round(t / 1e-4) * 1e-4) continue;  // a grid row
    events.push_back(t);
    EXPECT_LT(std::abs(r.sink.rows[k](0)), 1e-12) << "current at the event at t = " << t;
  }
  ASSERT_EQ(events.size(), expected.size());
  // Measured within 4e-16 s: the root finder's resolution.
  for (size_t k = 0; k < events.size(); ++k) EXPECT_NEAR(events[k], expected[k], 1e-14) << k;
  EXPECT_EQ(r.summary.stepper.events, 4);
}

// The half-wave rectifier with an L-C filter (states, IDA's root finder): every sign change of the
// diode current between output rows holds an event, and the current at each event is ~0.
TEST(Events, EveryCurrentSignChangeOfAnLcRectifierIsAnEvent) {
  NetlistBuilder b;
  b.v("v1", "in", "0", NetlistBuilder::sin(0, 10, 50)).d("d1", "in", "n1", 0.7, 0.1);
  b.l("l1", "n1", "out", 10e-3).c("c1", "out", "0", 470e-6).r("r1", "out", "0", 22);
  SmoothRun r = simulate(shockley(b.build(), 0.05), {"i(d1)"}, 20e-6, 60e-3, false);
  const std::vector<double> i = r.column("i(d1)");
  double peak = 0;
  for (double v : i) peak = std::max(peak, std::abs(v));
  ASSERT_GT(peak, 1.0);
  auto on_grid = [](double t) { return t == std::round(t / 20e-6) * 20e-6; };
  long crossings = 0, events = 0;
  for (size_t k = 0; k < i.size(); ++k) {
    const double t = r.sink.times[k];
    if (!on_grid(t)) {
      ++events;
      EXPECT_LT(std::abs(i[k]), 1e-9 * peak) << "t = " << t;
      continue;
    }
    // The previous grid row, and whether an event lies between the two.
    size_t p = k;
    bool event_between = false;
    while (p > 0) {
      --p;
      if (on_grid(r.sink.times[p])) break;
      event_between = true;
    }
    if (p == k || k == 0) continue;
    // Blocking, the current is -IS - GMIN m (about -1e-11 A); conducting, amperes. At t = 0 the
    // ideal operating point leaves it at zero (to rounding): leaving zero is not a crossing.
    if (std::abs(i[p]) > 1e-15 * peak && (i[p] > 0) != (i[k] > 0)) {
      ++crossings;
      EXPECT_TRUE(event_between) << "no event between t = " << r.sink.times[p] << " and " << t;
    }
  }
  EXPECT_EQ(crossings, 6);  // three conduction intervals
  EXPECT_GE(events, crossings);
  EXPECT_EQ(events, r.summary.stepper.events);
}

// A PULSE square wave into a capacitor through a diode: every edge is a jump, and every jump
// switches the diode, so the events are the edges themselves (emitted with event = true), and a
// step that lands on a jump must not see it (it would be rejected: measured 160 rejected steps
// when the sources were not taken as their left limits there, 0 now).
TEST(Events, SourceJumpsThatSwitchADiodeAreEventsAtTheJumps) {
  NetlistBuilder b;
  b.v("v1", "in", "0", NetlistBuilder::pulse({0, 5, 1e-3, 0, 0, 1e-3, 2e-3}));
  b.r("r1", "in", "a", 1e3).d("d1", "a", "out", 0.6, 1.0).c("c1", "out", "0", 1e-6, 0.0);
  b.r("r2", "out", "0", 1e4);
  ModelOptions mo;
  mo.t1 = 10e-3;
  CircuitModel model = CircuitModel::build(shockley(b.build(), 0.05), mo);
  SmoothMethod method(model, MethodOptions{});
  OutputGrid grid;
  grid.tstep = 1e-5;
  grid.tstop = 10e-3;
  std::vector<double> event_times, times;
  method.Run(Eigen::VectorXd::Zero(model.lcs().states()), grid,
             [&](double t, const Eigen::VectorXd&, const Eigen::VectorXd&, bool event) {
               times.push_back(t);
               if (event) event_times.push_back(t);
             });
  const std::vector<double> edges = {1e-3, 2e-3, 3e-3, 4e-3, 5e-3, 6e-3, 7e-3, 8e-3, 9e-3};
  ASSERT_EQ(event_times.size(), edges.size());
  for (size_t k = 0; k < edges.size(); ++k) EXPECT_NEAR(event_times[k], edges[k], 1e-15);
  EXPECT_EQ(times.size(), 1001u);  // the edges are grid times: one row each
  EXPECT_EQ(method.stats().events, 9);
  EXPECT_EQ(method.stats().rejected_steps, 0);
}

// (e) No states and no diodes: a divider, exact at every output time (every multiple of TSTEP
// and the extra times asked for).
TEST(Degenerate, DividerWithoutStatesOrDiodes) {
  NetlistBuilder b;
  b.v("v1", "in", "0", NetlistBuilder::sin(1, 2, 1e3)).r("r1", "in", "out", 3e3).r("r2", "out", "0", 1e3);
  SmoothRun r = simulate(b.build(), {"v(out)"}, 1e-4, 1e-3, false, 0, {2.5e-4, 7.77e-4});
  ASSERT_EQ(r.sink.times.size(), 13u);
  for (size_t k = 0; k < r.sink.times.size(); ++k) {
    const double t = r.sink.times[k];
    EXPECT_NEAR(r.sink.rows[k](0), (1 + 2 * std::sin(2 * kPi * 1e3 * t)) / 4, 1e-14);
  }
  EXPECT_EQ(r.sink.times[3], 2.5e-4);
  EXPECT_EQ(r.sink.times[9], 7.77e-4);
  EXPECT_EQ(r.sink.times[10], 8 * 1e-4);  // k * TSTEP, not accumulated
}

// No diodes, with states: a series RLC switched on by a PULSE that jumps from 0 to 1 V at 1 ms
// (a breakpoint: IDA stops, restarts after the jump). Underdamped closed form after the jump.
TEST(Degenerate, RlcWithoutDiodesFollowsTheClosedFormThroughAJump) {
  const double R = 20, L = 10e-3, C = 1e-6, td = 1e-3;
  NetlistBuilder b;
  b.v("v1", "in", "0", NetlistBuilder::pulse({0, 1, td, 0, 0, 1, 2}));
  b.r("r1", "in", "a", R).l("l1", "a", "b", L, 0.0).c("c1", "b", "0", C, 0.0);
  SmoothRun r = simulate(b.build(), {"v(b)", "i(l1)"}, 1e-5, 3e-3, true, 1e-8);
  const double alpha = R / (2 * L), w0 = 1 / std::sqrt(L * C), wd = std::sqrt(w0 * w0 - alpha * alpha);
  double worst = 0;
  for (size_t k = 0; k < r.sink.times.size(); ++k) {
    const double t = r.sink.times[k] - td;
    const double v = t < 0 ? 0 : 1 - std::exp(-alpha * t) * (std::cos(wd * t) + alpha / wd * std::sin(wd * t));
    const double i = t < 0 ? 0 : C * std::exp(-alpha * t) * (w0 * w0 / wd) * std::sin(wd * t);
    worst = std::max({worst, std::abs(r.sink.rows[k](0) - v), 100 * std::abs(r.sink.rows[k](1) - i)});
  }
  EXPECT_LT(worst, 1e-6);  // measured 9e-8 at rtol 1e-8
  EXPECT_EQ(r.summary.stepper.events, 0);
  EXPECT_GT(r.summary.stepper.steps, 0);
  EXPECT_GT(r.summary.stepper.jacobian_evals, 0);
}

// Issue 9, defect 2: smooth integrates Shockley junctions, so the ideal law's loop check does
// not apply to its rewrite. An RON = 0, VON = 0 diode antiparallel to a user's Shockley diode
// (IS, N, no VON/RON: RS = 0 in the rewrite) is an impedance-free ideal loop; smooth runs it.
// At the source's negative peak the user's junction carries I = (5 V + v(a)) / R with
// v(a) = -Vt ln(1 + I / IS), the other junction only its leakage.
TEST(Degenerate, ShockleyDiodeAntiparallelToAZeroImpedanceDiodeRuns) {
  const double R = 100, IS = 1e-14;
  NetlistBuilder b;
  b.v("v1", "in", "0", NetlistBuilder::sin(0, 5, 1e3)).r("r1", "in", "a", R).d("d1", "a", "0");
  Netlist n = b.build();
  Element d2 = n.elements.back();
  d2.name = "d2";
  d2.nodes = {"0", "a"};
  d2.model = "m_user";
  DiodeModel user;
  user.name = "m_user";
  user.is = IS;
  user.n = 1;
  user.has_is = user.has_n = true;
  n.diode_models["m_user"] = user;
  n.elements.push_back(d2);
  SmoothRun r = simulate(shockley(n, 0.05), {"v(a)"}, 2.5e-5, 1e-3, true, 1e-9);
  double va = -0.6;
  for (int it = 0; it < 100; ++it) va = -kThermalVoltage * std::log1p((5 + va) / R / IS);
  const auto peak = std::find(r.sink.times.begin(), r.sink.times.end(), 30 * 2.5e-5);
  ASSERT_NE(peak, r.sink.times.end());
  EXPECT_NEAR(r.column("v(a)")[peak - r.sink.times.begin()], va, 1e-4);
}

}  // namespace
}  // namespace lcs
