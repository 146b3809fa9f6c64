// One suite for every registered method (Drake's generic_integrator_test.h is the model): each
// entry of method_registry() runs the same circuits against their closed forms, with its
// tolerances stated in one table below. A method added to the registry gets these tests for free;
// it only has to state its row (a missing row is a failure that says so).
//
// Methods that integrate the smoothed circuit (MethodEntry::smooth_model: Shockley junctions in
// place of the ideal law, solver/model/smooth_netlist.h) are compared with the same closed forms
// of the ideal circuit; their tolerance adds the model gap N Vt ln(1 + I/IS) of each conducting
// junction, computed from the circuit, to the numerical tolerance in the table.
#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "solver/integrators/method_registry.h"
#include "solver/integrators/shockley_dae.h"
#include "solver/integrators/transient.h"
#include "solver/model/pair_law.h"
#include "solver/model/smooth_netlist.h"
#include "tests/support/lc_tank_bridge.h"
#include "tests/support/netlist_builder.h"

namespace lcs {
namespace {

using testing::lc_tank_bridge;
using testing::lc_tank_closed_form;
using testing::NetlistBuilder;

constexpr double kPi = 3.14159265358979323846;

// Per-method tolerances. Errors are maxima over the output rows; the step of a fixed-step method
// is the case's h, an adaptive method uses h as its output spacing at its default tolerances.
struct Tolerances {
  const char* method;
  int order;          // classical order on a smooth stretch (fixed-step methods); 0: adaptive
  double rc;          // V: RC charged through a diode (5 time constants, h = tau/50, 10 V)
  double switching;   // s: the half-wave rectifier's turn-on and turn-off instants (h = 20 us)
  double no_states;   // A: diode and resistor on a sine (no states: every method is exact)
  double no_diodes;   // V: series RLC step response (h = T/100 of its ringing, 5 V)
  double lc_tank;     // V: the LC-tank bridge over 2 ms (h = 2 us), 10 V initial charge
  // Not L-stable: after a diode turns off, an index-one pair's z rings without damping and can
  // let the diode conduct spuriously before its true turn-on (README, docs/stability.md).
  bool rings_after_switching;
};

// The errors measured on 2026-11-25 are in brackets; each bound is 2-5 times its measurement.
// The switching instants are read off the rows by linear extrapolation, which itself errs by
// about 1e-8 s here. The smoothed circuit's model gap is added per case, not stated here.
const Tolerances kTable[] = {
    // euler [rc 3.4e-2, switching 1.1e-6, no states 1.8e-16, rlc 0.19, tank 0.67]
    {"euler", 1, 5e-2, 3e-6, 1e-12, 0.3, 1.0, false},
    // event: exact inside each mode [rc 4.3e-14, switching 1.1e-8, rlc 9.8e-15, tank 6.9e-13]
    {"event", 0, 1e-11, 5e-8, 1e-12, 1e-11, 1e-10, false},
    // radau3 [rc 3.8e-7, switching 1.1e-8, rlc 2.4e-5, tank 8.2e-6]
    {"radau3", 3, 1e-6, 5e-8, 1e-12, 5e-5, 2e-5, false},
    // radau5 [rc 1.5e-12, switching 1.1e-8, rlc 9.7e-10, tank 3.3e-11]
    {"radau5", 5, 1e-10, 5e-8, 1e-12, 3e-9, 1e-10, false},
    // smooth: IDA at rtol 1e-6, atol 1e-9 [rlc 8.0e-6]; with diodes, every measured error was
    // below the model gap alone (rc 0.031 of 0.036, tank 0.054 of 0.071)
    {"smooth", 0, 5e-5, 2e-6, 1e-7, 2e-5, 1e-3, false},
    // theta at its default 0.5, trapezoidal [rc 1.1e-4, switching 1.1e-8, rlc 2.1e-3, tank 2.4e-3]
    {"theta", 2, 3e-4, 5e-8, 1e-12, 5e-3, 5e-3, true},
};

const Tolerances* tolerances_of(const MethodEntry& entry) {
  for (const Tolerances& t : kTable)
    if (entry.name == t.method) return &t;
  return nullptr;
}

// The smoothed junction's extra voltage at current i (solver/devices/diode.h: smooth_equivalent).
double model_gap(double current) {
  const SmoothingOptions s;
  return s.emission * kThermalVoltage * std::log1p(current / s.saturation_current);
}

struct MethodRun {
  MemorySink sink;
  TransientSummary summary;
  std::vector<double> column(const std::string& probe) const {
    const int c = sink.column(probe);
    EXPECT_GE(c, 0) << probe;
    std::vector<double> out;
    for (const Eigen::VectorXd& row : sink.rows) out.push_back(row(std::max(c, 0)));
    return out;
  }
};

class Conformance : public ::testing::TestWithParam<const MethodEntry*> {
 protected:
  const MethodEntry& entry() const { return *GetParam(); }
  const Tolerances& tol() const {
    static const Tolerances strict{"", 0, 0, 0, 0, 0, 0, false};
    const Tolerances* t = tolerances_of(entry());
    if (!t) {
      ADD_FAILURE() << "method " << entry().name
                    << " has no row in the conformance table (conformance_test.cpp: kTable); "
                       "state its tolerances there";
      return strict;
    }
    return *t;
  }
  bool smooth() const { return entry().smooth_model; }

  MethodRun simulate(Netlist netlist, const std::vector<std::string>& probes, double h, double tstop,
               bool uic) const {
    if (smooth()) netlist = smooth_netlist(netlist, SmoothingOptions{});
    ModelOptions mo;
    mo.t1 = tstop;
    const CircuitModel model = CircuitModel::build(netlist, mo);
    std::vector<Probe> ps;
    for (const std::string& p : probes) ps.push_back(parse_probe(p, {}));
    TransientOptions o;
    o.method = entry().name;
    o.step = h;
    o.tstop = tstop;
    o.uic = uic;
    MethodRun r;
    r.summary = run_transient(model, model.output_map(ps), o, r.sink);
    expect_well_formed(r, h, tstop);
    return r;
  }

  // SPEC §3: rows start at 0, strictly increase and end at TSTOP; a fixed-step method writes
  // exactly one row per step, an adaptive one at least every multiple of the output spacing.
  void expect_well_formed(const MethodRun& r, double h, double tstop) const {
    ASSERT_FALSE(r.sink.times.empty());
    EXPECT_TRUE(r.sink.finished);
    EXPECT_EQ(r.sink.times.front(), 0.0);
    EXPECT_DOUBLE_EQ(r.sink.times.back(), tstop);
    for (size_t k = 1; k < r.sink.times.size(); ++k)
      ASSERT_LT(r.sink.times[k - 1], r.sink.times[k]) << "row " << k;
    const size_t steps = static_cast<size_t>(std::lround(tstop / h));
    if (entry().fixed_step())
      EXPECT_EQ(r.sink.times.size(), steps + 1);
    else
      EXPECT_GE(r.sink.times.size(), steps + 1);
    for (const Eigen::VectorXd& row : r.sink.rows) ASSERT_TRUE(row.allFinite());
  }
};

// RC charged through a diode (UIC: the capacitor starts empty, the diode conducts throughout):
// v(t) = (V - VON)(1 - exp(-t/tau)), tau = (R + RON) C.
struct RcThroughDiode {
  double V = 10, VON = 0.7, RON = 5, R = 1e3, C = 1e-6;
  double tau() const { return (R + RON) * C; }
  Netlist netlist(const Waveform& source) const {
    NetlistBuilder b;
    b.v("v1", "in", "0", source).d("d1", "in", "a", VON, RON);
    b.r("r1", "a", "out", R).c("c1", "out", "0", C, 0.0);
    return b.build();
  }
  double v(double t) const { return (V - VON) * (1 - std::exp(-t / tau())); }
  // The smoothed junction conducts (V - VON)/(R + RON) at most; the gap divides between R + RON
  // and the capacitor's voltage follows the lower source, so v lags by at most the gap.
  double gap() const { return model_gap((V - VON) / (R + RON)); }
};

double max_error(const MethodRun& r, const std::string& probe, const std::function<double(double)>& exact) {
  const std::vector<double> x = r.column(probe);
  double e = 0;
  for (size_t k = 0; k < x.size(); ++k) e = std::max(e, std::abs(x[k] - exact(r.sink.times[k])));
  return e;
}

TEST_P(Conformance, RcThroughADiodeMatchesItsClosedForm) {
  const RcThroughDiode c;
  const double h = c.tau() / 50, T = 5 * c.tau();
  const MethodRun r = simulate(c.netlist(NetlistBuilder::dc(c.V)), {"v(out)"}, h, T, true);
  const double bound = tol().rc + (smooth() ? c.gap() : 0);
  EXPECT_LE(max_error(r, "v(out)", [&](double t) { return c.v(t); }), bound);
}

TEST_P(Conformance, RcThroughADiodeConvergesAtTheStatedOrder) {
  if (!entry().fixed_step()) GTEST_SKIP() << "adaptive: no step to halve";
  const RcThroughDiode c;
  const Netlist n = c.netlist(NetlistBuilder::dc(c.V));
  auto error = [&](double h) {
    return max_error(simulate(n, {"v(out)"}, h, 2 * c.tau(), true), "v(out)",
                     [&](double t) { return c.v(t); });
  };
  // radau5 reaches rounding at tau/50; its order shows on coarser steps.
  const double h = tol().order >= 5 ? c.tau() / 8 : c.tau() / 25;
  const double rate = std::log2(error(h) / error(h / 2));
  EXPECT_NEAR(rate, tol().order, 0.3);
}

// A source that jumps exactly at TSTOP: the run ends at TSTOP on the value before the jump
// (PULSE starts its edge at TD), with no row past it and nothing lost at the end.
TEST_P(Conformance, ASourceJumpAtTstopEndsTheRunOnTheValueBeforeIt) {
  const RcThroughDiode c;
  const double h = c.tau() / 50, T = 5 * c.tau();
  const Waveform pulse = NetlistBuilder::pulse({c.V, 0, T, 1e-7, 1e-7, 1, 2});
  const MethodRun r = simulate(c.netlist(pulse), {"v(out)", "v(in)"}, h, T, true);
  EXPECT_DOUBLE_EQ(r.column("v(in)").back(), c.V);
  const double bound = tol().rc + (smooth() ? c.gap() : 0);
  EXPECT_NEAR(r.column("v(out)").back(), c.v(T), bound);
}

// Diode and resistor on a sine, no states: i = max(0, V sin(wt) - VON) / (R + RON) at every row,
// exact for every time-stepping method (there is nothing to integrate).
TEST_P(Conformance, NoStatesIsExactAtEveryRow) {
  const double V = 10, f = 50, VON = 0.7, RON = 0.5, R = 100;
  NetlistBuilder b;
  b.tran(20e-6, 40e-3, false);
  b.v("v1", "in", "0", NetlistBuilder::sin(0, V, f)).d("d1", "in", "a", VON, RON).r("r1", "a", "0", R);
  const MethodRun r = simulate(b.build(), {"i(d1)"}, 20e-6, 40e-3, false);
  auto exact = [&](double t) { return std::max(0.0, V * std::sin(2 * kPi * f * t) - VON) / (R + RON); };
  // The smoothed junction takes up to the gap at the peak current: i is lower by gap / (R + RON).
  const double bound = tol().no_states + (smooth() ? model_gap((V - VON) / (R + RON)) / (R + RON) : 0);
  EXPECT_LE(max_error(r, "i(d1)", exact), bound);
}

// Series RLC step response (no diodes, UIC): underdamped, v_C = V (1 - e^{-at}(cos wt + a/w sin wt)).
TEST_P(Conformance, NoDiodesFollowsTheLinearClosedForm) {
  const double V = 5, R = 20, L = 1e-3, C = 1e-6;
  const double a = R / (2 * L), w0 = 1 / std::sqrt(L * C), w = std::sqrt(w0 * w0 - a * a);
  const double period = 2 * kPi / w, h = period / 100, T = 3 * period;
  NetlistBuilder b;
  b.v("v1", "in", "0", NetlistBuilder::dc(V)).r("r1", "in", "a", R).l("l1", "a", "b", L, 0.0);
  b.c("c1", "b", "0", C, 0.0);
  const MethodRun r = simulate(b.build(), {"v(b)"}, h, T, true);
  auto exact = [&](double t) {
    return V * (1 - std::exp(-a * t) * (std::cos(w * t) + a / w * std::sin(w * t)));
  };
  EXPECT_LE(max_error(r, "v(b)", exact), tol().no_diodes);
}

// Half-wave rectifier into a series L-R load (Stewart Fig. 1.6 without the filter capacitor):
// the diode turns on when V sin(wt) reaches VON (i = 0, so the load takes no voltage), then
// L i' + (R + RON) i = V sin(wt) - VON until i returns to 0 after the source reverses.
struct HalfWaveRL {
  double V = 10, f = 50, VON = 0.7, RON = 0.1, L = 10e-3, R = 10;
  double w() const { return 2 * kPi * f; }
  double rt() const { return R + RON; }
  double t_on() const { return std::asin(VON / V) / w(); }
  double i(double t) const {  // on [t_on, t_off]
    const double z = std::hypot(rt(), w() * L), phi = std::atan2(w() * L, rt());
    auto forced = [&](double s) { return V / z * std::sin(w() * s - phi) - VON / rt(); };
    return forced(t) - forced(t_on()) * std::exp(-(t - t_on()) * rt() / L);
  }
  double t_off() const {  // i > 0 from just after t_on through the source's peak
    double lo = t_on() + 0.25 / f, hi = t_on() + 1 / f;
    for (int k = 0; k < 200; ++k) (i(0.5 * (lo + hi)) > 0 ? lo : hi) = 0.5 * (lo + hi);
    return 0.5 * (lo + hi);
  }
  double peak() const { return V / std::hypot(rt(), w() * L); }
};

// The zero of a sampled signal that leaves (or reaches) 0 with a nonzero slope, extrapolated
// linearly from the two rows on the nonzero side next to it.
double extrapolated_zero(const std::vector<double>& t, const std::vector<double>& x, size_t k0,
                         size_t k1) {
  return t[k0] - x[k0] * (t[k1] - t[k0]) / (x[k1] - x[k0]);
}

TEST_P(Conformance, HalfWaveRectifierSwitchesAtTheClosedFormInstants) {
  const HalfWaveRL c;
  const double h = 20e-6, T = 1.5 / c.f;
  NetlistBuilder b;
  b.tran(h, T, false);
  b.v("v1", "in", "0", NetlistBuilder::sin(0, c.V, c.f)).d("d1", "in", "n1", c.VON, c.RON);
  b.l("l1", "n1", "x", c.L, 0.0).r("r1", "x", "0", c.R);
  const MethodRun r = simulate(b.build(), {"v(n1)", "i(d1)"}, h, T, true);
  const std::vector<double>& t = r.sink.times;
  const std::vector<double> v = r.column("v(n1)"), i = r.column("i(d1)");
  // On: v(n1) = V sin(wt) - VON - RON i rises from 0 at t_on; off: i falls to 0 at t_off.
  // The thresholds are far above a smoothed junction's reverse current and far below the signal.
  const double v_eps = 1e-6 * c.V, i_eps = 1e-6 * c.peak();
  size_t on = 1;
  while (on + 1 < t.size() && v[on] <= v_eps) ++on;
  size_t off = on + 1;
  while (off < t.size() && i[off] > i_eps) ++off;
  ASSERT_LT(off, t.size());
  const double t_on = extrapolated_zero(t, v, on, on + 1);
  const double t_off = extrapolated_zero(t, i, off - 1, off - 2);
  // A smoothed junction conducts once the source is within a gap of VON and stops a gap early:
  // the instants move by gap / slope of the driving voltage there.
  const double gap_on = smooth() ? model_gap(c.peak()) / (c.V * c.w() * std::cos(c.w() * c.t_on())) : 0;
  const double gap_off =
      smooth() ? model_gap(c.peak()) / std::abs(c.V * c.w() * std::cos(c.w() * c.t_off())) : 0;
  EXPECT_NEAR(t_on, c.t_on(), tol().switching + gap_on);
  EXPECT_NEAR(t_off, c.t_off(), tol().switching + gap_off);
  // Off for the rest of the period: no current until the next turn-on at t_on + 1/f.
  if (tol().rings_after_switching) return;
  for (size_t k = off + 1; k < t.size() && t[k] < c.t_on() + 1 / c.f - 2 * h; ++k)
    ASSERT_LE(i[k], i_eps) << "t = " << t[k];
}

// circuits/lc_tank_bridge.cir: the diodes switch at every zero of the tank voltage, which stays
// a damped sine; each method at its stated accuracy.
TEST_P(Conformance, LcTankBridgeFollowsTheDampedSine) {
  const double h = 2e-6, T = 2e-3;
  const MethodRun r = simulate(lc_tank_bridge(), {"v(a)"}, h, T, false);
  // The smoothed bridge puts two junctions in the load's path, at most 10 mA each.
  const double gap = smooth() ? 2 * model_gap(10.0 / 1e3) : 0;
  EXPECT_LE(max_error(r, "v(a)", lc_tank_closed_form), tol().lc_tank + gap);
}

// Two inductors in parallel (a loop of inductors only, issue 9 defect 5) fed through R from a
// source that steps from 5 V to -5 V; a diode to a load across them. DC fixes i1 + i2 = V/R but
// not the current circulating in the loop: the operating point takes the split of least energy,
// L1 i1 = L2 i2, and every method starts there. Both inductors then see the same voltage, so
// L1 i1 - L2 i2 is invariant; linear one-step methods and BDF keep linear invariants exactly.
Netlist parallel_inductors(std::optional<double> ic1, std::optional<double> ic2) {
  NetlistBuilder b;
  b.v("v1", "in", "0", NetlistBuilder::pulse({5, -5, 1e-3, 1e-6, 1e-6, 1e-3, 2e-3}));
  b.r("r1", "in", "a", 10).l("l1", "a", "0", 1e-3, ic1).l("l2", "a", "0", 2e-3, ic2);
  b.d("d1", "a", "k", 0.7, 0.1).r("r2", "k", "0", 5);
  return b.build();
}

TEST_P(Conformance, AnInductorLoopStartsAtTheLeastEnergySplitAndKeepsItsCirculation) {
  const double h = 10e-6, T = 3e-3;
  const MethodRun r = simulate(parallel_inductors({}, {}), {"i(l1)", "i(l2)"}, h, T, false);
  const std::vector<double> i1 = r.column("i(l1)"), i2 = r.column("i(l2)");
  // 0.5 A divided inversely to L; the smoothed circuit starts at its own operating point, where
  // the blocking junction (at -VON) adds its leakage IS + GMIN VON to the inductors' current.
  const SmoothingOptions so;
  const double leak = smooth() ? so.saturation_current + kGmin * 0.7 : 0;
  EXPECT_NEAR(i1.front(), (0.5 + leak) / 3 * 2, 1e-14);
  EXPECT_NEAR(i2.front(), (0.5 + leak) / 3, 1e-14);
  for (size_t k = 0; k < i1.size(); ++k)
    ASSERT_NEAR(1e-3 * i1[k] - 2e-3 * i2[k], 0.0, 1e-15) << "t = " << r.sink.times[k];
  // IC= with UIC chooses the circulation: L1 i1 - L2 i2 = 1 mH * 0.5 A stays.
  const MethodRun u = simulate(parallel_inductors(0.5, 0.0), {"i(l1)", "i(l2)"}, h, T, true);
  const std::vector<double> j1 = u.column("i(l1)"), j2 = u.column("i(l2)");
  EXPECT_EQ(j1.front(), 0.5);
  EXPECT_EQ(j2.front(), 0.0);
  for (size_t k = 0; k < j1.size(); ++k)
    ASSERT_NEAR(1e-3 * j1[k] - 2e-3 * j2[k], 0.5e-3, 1e-15) << "t = " << u.sink.times[k];
}

// Random circuit 3 of tests/random, reduced: two reverse-biased diodes feed an inductor that is
// their only other path, and nothing moves (v(m) = L di/dt = 0). The time-stepping start, one
// LCP with a tiny step, left d3 at its threshold, v(m) = -0.724 V in the row at t = 0: d3's
// current-type row couples to d2's voltage-type one by O(1) entries while everything the
// inductor brings is O(h) and sat below the LCP's tolerance. The trapezoidal rule carried that
// start as a +-0.724 V ringing for the whole run.
TEST_P(Conformance, ReverseBiasedDiodesFeedingAnInductorStayIdle) {
  if (smooth())  // the inductor first takes the junctions' leakage (1.6 pA within 6 ps, v(m) -0.72 V)
    GTEST_SKIP() << "Shockley junctions are not idle: their leakage flows through the inductor";
  NetlistBuilder b;
  b.tran(4e-6, 2e-3, false);
  b.v("v1", "a", "0", NetlistBuilder::dc(-0.56)).l("l3", "m", "0", 2.7);
  b.d("d2", "a", "m", 0.267, 2.7).d("d3", "a", "m", 0.164, 0.082);
  const MethodRun r = simulate(b.build(), {"v(m)", "i(l3)"}, 4e-6, 2e-3, false);
  const std::vector<double> vm = r.column("v(m)"), il = r.column("i(l3)");
  for (size_t k = 0; k < vm.size(); ++k) {
    EXPECT_LE(std::abs(vm[k]), 1e-9) << "v(m) at t = " << r.sink.times[k];
    EXPECT_LE(std::abs(il[k]), 1e-12) << "i(l3) at t = " << r.sink.times[k];
  }
}

// Random circuit 221 of tests/random, reduced: d4 is reverse biased and its only other path is
// the inductor, so v(m) = v(c) = 0 throughout. The operating point leaves 1.3e-15 A of rounding
// in i(l1); the start LCP, whose row for d4 is all O(h) (D_44 = 0), divided it by h/L and put
// d4's voltage 0.36 V off (v(m) = -0.36 V at t = 0; theta rang with +-0.36 V for the whole run).
// What remains is the 1e-15 A divided by the run's own step (implicit Euler's second row:
// 3.6e-9 V), which the trapezoidal rule keeps.
TEST_P(Conformance, RoundingInAnIdleInductorDoesNotMoveItsDiodesVoltage) {
  if (smooth())
    GTEST_SKIP() << "Shockley junctions are not idle: their leakage flows through the inductor";
  NetlistBuilder b;
  b.tran(1e-5, 2e-3, false);
  b.v("v1", "b", "0", NetlistBuilder::dc(-4.8)).r("r5", "a", "0", 39);
  b.d("d2", "a", "b", 0.459, 0.68).d("d3", "0", "a", 0.169, 0.27).d("d4", "a", "m", 0.789, 0.39);
  b.l("l1", "m", "c", 27).r("r3", "c", "0", 33).r("r4", "d", "c", 47e3);
  const MethodRun r = simulate(b.build(), {"v(m)"}, 1e-5, 2e-3, false);
  const std::vector<double> vm = r.column("v(m)");
  for (size_t k = 0; k < vm.size(); ++k) EXPECT_LE(std::abs(vm[k]), 1e-7) << "t = " << r.sink.times[k];
}

TEST(ConformanceTable, EveryRowNamesARegisteredMethod) {
  for (const Tolerances& t : kTable) EXPECT_NE(find_method(t.method), nullptr) << t.method;
}

std::vector<const MethodEntry*> every_method() {
  std::vector<const MethodEntry*> out;
  for (const MethodEntry& e : method_registry()) out.push_back(&e);
  return out;
}

INSTANTIATE_TEST_SUITE_P(EveryMethod, Conformance, ::testing::ValuesIn(every_method()),
                         [](const ::testing::TestParamInfo<const MethodEntry*>& info) {
                           return info.param->name;
                         });

}  // namespace
}  // namespace lcs
