// Radau IIA time-stepping (8.4.1): exact tableaux, classical order 2s - 1 on circuits that stay in
// one mode (closed forms), complementarity at every step of a switching circuit, circuits
// without states or without diodes, an LCP of 3 * 30 pairs, and no heap allocation per step.
#include "tests/support/sanitizers.h"
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "solver/integrators/radau_iia.h"
#include "solver/integrators/transient.h"
#include "solver/model/initial_state.h"
#include "tests/support/lc_tank_bridge.h"
#include "tests/support/netlist_builder.h"

// Count heap allocations by interposing malloc/calloc/realloc, as warm_solver_test.cpp does
// (forwarded to glibc's allocator, so glibc's free stays valid).
#if defined(__GLIBC__) && !LCS_UNDER_ASAN
#define LCS_COUNT_ALLOCS 1
extern "C" void* __libc_malloc(std::size_t);
extern "C" void* __libc_calloc(std::size_t, std::size_t);
extern "C" void* __libc_realloc(void*, std::size_t);
namespace {
std::atomic<long> g_allocs{0};
std::atomic<bool> g_counting{false};
}  // namespace
extern "C" void* malloc(std::size_t n) {
  if (g_counting.load(std::memory_order_relaxed)) g_allocs.fetch_add(1, std::memory_order_relaxed);
  return __libc_malloc(n);
}
extern "C" void* calloc(std::size_t a, std::size_t b) {
  if (g_counting.load(std::memory_order_relaxed)) g_allocs.fetch_add(1, std::memory_order_relaxed);
  return __libc_calloc(a, b);
}
extern "C" void* realloc(void* p, std::size_t n) {
  if (g_counting.load(std::memory_order_relaxed)) g_allocs.fetch_add(1, std::memory_order_relaxed);
  return __libc_realloc(p, n);
}
#endif

namespace lcs {
namespace {

using testing::lc_tank_bridge;
using testing::lc_tank_closed_form;
using testing::NetlistBuilder;

struct RunResult {
  MemorySink sink;
  TransientSummary summary;
};

RunResult simulate(const Netlist& netlist, const std::vector<Probe>& probes, const std::string& method,
                   double h, double tstop, bool uic) {
  ModelOptions mo;
  mo.t1 = tstop;
  CircuitModel model = CircuitModel::build(netlist, mo);
  TransientOptions o;
  o.method = method;
  o.step = h;
  o.tstop = tstop;
  o.uic = uic;
  RunResult r;
  r.summary = run_transient(model, model.output_map(probes), o, r.sink);
  return r;
}

Probe v(const std::string& node) { return {Probe::Kind::NodeVoltage, node, "", {}}; }
Probe i(const std::string& element) { return {Probe::Kind::ElementCurrent, element, "", {}}; }

// ---------------------------------------------------------------------------------------------
// The tableaux

// Butcher's simplifying assumptions (8.4.1): B(2s-1) for the weights b (the last row of a),
// C(s) for every row; Radau IIA also ends at c_s = 1 (stiffly accurate, RK2).
TEST(RadauTableau, MeetsSimplifyingAssumptionsBAndC) {
  for (int s : {2, 3}) {
    const ButcherTableau t = radau_iia_tableau(s);
    ASSERT_EQ(t.c.size(), s);
    ASSERT_EQ(t.a.rows(), s);
    ASSERT_EQ(t.a.cols(), s);
    EXPECT_EQ(t.c(s - 1), 1.0);
    const Eigen::RowVectorXd b = t.a.row(s - 1);
    for (int k = 1; k <= 2 * s - 1; ++k) {
      double sum = 0;
      for (int j = 0; j < s; ++j) sum += k * b(j) * std::pow(t.c(j), k - 1);
      EXPECT_NEAR(sum, 1.0, 1e-15) << "B(" << k << "), s = " << s;
    }
    // B(2s) fails: 2s - 1 is the order, not more.
    double sum = 0;
    for (int j = 0; j < s; ++j) sum += 2 * s * b(j) * std::pow(t.c(j), 2 * s - 1);
    EXPECT_GT(std::abs(sum - 1.0), 1e-3) << "s = " << s;
    for (int i = 0; i < s; ++i)
      for (int k = 1; k <= s; ++k) {
        double row = 0;
        for (int j = 0; j < s; ++j) row += k * t.a(i, j) * std::pow(t.c(j), k - 1);
        EXPECT_NEAR(row, std::pow(t.c(i), k), 1e-15) << "C(" << k << "), row " << i << ", s = " << s;
      }
  }
  EXPECT_THROW(radau_iia_tableau(1), std::invalid_argument);
  EXPECT_THROW(radau_iia_tableau(4), std::invalid_argument);
}

// ---------------------------------------------------------------------------------------------
// Order on circuits that stay in one mode

// log2 of successive error ratios at h, h/2, h/4.
std::pair<double, double> observed_orders(double e1, double e2, double e3) {
  return {std::log2(e1 / e2), std::log2(e2 / e3)};
}

// The LC-tank bridge: its diodes switch every half period, but the tank voltage is smooth and
// each switch happens where the current through the pair is zero, so Radau keeps its order.
// Ideal diodes (RON = 0) make the pairs index one or two: an algebraic constraint per mode.
double lc_tank_end_error(const std::string& method, double h, double T) {
  RunResult r = simulate(lc_tank_bridge(), {v("a")}, method, h, T, true);
  EXPECT_NEAR(r.sink.times.back(), T, 1e-15);
  return std::abs(r.sink.rows.back()(0) - lc_tank_closed_form(T));
}

// Measured end-point errors: radau3 1.84e-5, 2.32e-6, 2.91e-7 V at h = 4, 2, 1 us (orders 2.985,
// 2.993); radau5 2.33e-7, 7.55e-9, 2.40e-10 V at h = 16, 8, 4 us (orders 4.949, 4.975). Rounding
// over the run is about 1e-12 V.
TEST(RadauLcTankBridge, Radau3IsThirdOrderAtTheEndPoint) {
  const double T = 4.8e-3;
  const double e1 = lc_tank_end_error("radau3", 4e-6, T), e2 = lc_tank_end_error("radau3", 2e-6, T),
               e3 = lc_tank_end_error("radau3", 1e-6, T);
  const auto [p1, p2] = observed_orders(e1, e2, e3);
  EXPECT_NEAR(p1, 3.0, 0.3) << e1 << " " << e2;
  EXPECT_NEAR(p2, 3.0, 0.3) << e2 << " " << e3;
  EXPECT_GT(e3, 1e-9);  // far above rounding
}

TEST(RadauLcTankBridge, Radau5IsFifthOrderAtTheEndPoint) {
  const double T = 4.8e-3;
  const double e1 = lc_tank_end_error("radau5", 16e-6, T), e2 = lc_tank_end_error("radau5", 8e-6, T),
               e3 = lc_tank_end_error("radau5", 4e-6, T);
  const auto [p1, p2] = observed_orders(e1, e2, e3);
  EXPECT_NEAR(p1, 5.0, 0.3) << e1 << " " << e2;
  EXPECT_NEAR(p2, 5.0, 0.3) << e2 << " " << e3;
  EXPECT_GT(e3, 1e-11);
}

// A SIN source charges C || RL through a diode (VON, RON) and R that never stops conducting (the
// load draws more than the ripple returns): v' = -a v + b g(t), g = VO - VON + VA sin(w t),
// a = (1/Rs + 1/RL)/C, b = 1/(Rs C), Rs = R + RON. The stage inputs u(t + c_j h) matter here.
struct SinChargedRc {
  double vo = 10, va = 2, freq = 500, von = 0.7, ron = 10, r = 990, c = 1e-6, rl = 1e3;

  Netlist netlist(const std::string& suffix = "", NetlistBuilder* into = nullptr) const {
    NetlistBuilder local;
    NetlistBuilder& b = into ? *into : local;
    if (!into) b.v("v1", "in", "0", NetlistBuilder::sin(vo, va, freq));
    b.d("d" + suffix, "in", "a" + suffix, von, ron).r("r" + suffix, "a" + suffix, "b" + suffix, r);
    b.c("c" + suffix, "b" + suffix, "0", c, 0.0).r("rl" + suffix, "b" + suffix, "0", rl);
    return b.build();
  }
  double v(double t) const {  // v(b), from v(0) = 0
    const double rs = r + ron, a = (1 / rs + 1 / rl) / c, bb = 1 / (rs * c), w = 2 * M_PI * freq;
    const double g0 = vo - von, den = a * a + w * w;
    const double k = -bb * g0 / a + bb * va * w / den;
    return bb * g0 / a + bb * va * (a * std::sin(w * t) - w * std::cos(w * t)) / den +
           k * std::exp(-a * t);
  }
  double diode_current(double t, double vb) const {
    return (vo - von + va * std::sin(2 * M_PI * freq * t) - vb) / (r + ron);
  }
};

// Measured end-point errors: radau3 2.74e-6, 3.51e-7, 4.45e-8 V at h = 40, 20, 10 us (orders
// 2.963, 2.981); radau5 4.24e-8, 1.33e-9, 4.18e-11 V at h = 80, 40, 20 us (orders 4.991, 4.996).
double sin_rc_end_error(const std::string& method, double h, double T) {
  const SinChargedRc rc;
  RunResult r = simulate(rc.netlist(), {v("b"), i("d")}, method, h, T, true);
  double min_current = INFINITY;
  for (size_t n = 0; n < r.sink.times.size(); ++n) min_current = std::min(min_current, r.sink.rows[n](1));
  EXPECT_GT(min_current, 1e-3);  // one mode all along: the premise of the closed form
  EXPECT_NEAR(r.sink.rows.back()(1), rc.diode_current(T, rc.v(T)), 1e-3 * 1e-3);
  return std::abs(r.sink.rows.back()(0) - rc.v(T));
}

TEST(RadauSinChargedRc, Radau3IsThirdOrderAtTheEndPoint) {
  const double T = 2e-3;
  const double e1 = sin_rc_end_error("radau3", 40e-6, T), e2 = sin_rc_end_error("radau3", 20e-6, T),
               e3 = sin_rc_end_error("radau3", 10e-6, T);
  const auto [p1, p2] = observed_orders(e1, e2, e3);
  EXPECT_NEAR(p1, 3.0, 0.3) << e1 << " " << e2;
  EXPECT_NEAR(p2, 3.0, 0.3) << e2 << " " << e3;
  EXPECT_GT(e3, 1e-10);
}

TEST(RadauSinChargedRc, Radau5IsFifthOrderAtTheEndPoint) {
  const double T = 2e-3;
  const double e1 = sin_rc_end_error("radau5", 80e-6, T), e2 = sin_rc_end_error("radau5", 40e-6, T),
               e3 = sin_rc_end_error("radau5", 20e-6, T);
  const auto [p1, p2] = observed_orders(e1, e2, e3);
  EXPECT_NEAR(p1, 5.0, 0.3) << e1 << " " << e2;
  EXPECT_NEAR(p2, 5.0, 0.3) << e2 << " " << e3;
  EXPECT_GT(e3, 1e-11);
}

// No complementarity pairs (m = 0): an RC low-pass driven by a SIN source,
// v' = (u - v)/(RC), the same closed form with VON = RON = 0 and RL = infinity. Measured
// 3.21e-8, 1.00e-9, 3.14e-11 V at h = 80, 40, 20 us (orders 4.999, 4.999).
TEST(RadauWithoutDiodes, RcLowPassIsFifthOrder) {
  const double R = 1e3, C = 1e-6, f = 500, T = 2e-3;
  NetlistBuilder b;
  b.v("v1", "in", "0", NetlistBuilder::sin(0, 5, f)).r("r1", "in", "out", R).c("c1", "out", "0", C, 0.0);
  const Netlist netlist = b.build();
  auto exact = [&](double t) {
    const double a = 1 / (R * C), w = 2 * M_PI * f, den = a * a + w * w;
    return 5 * a * (a * std::sin(w * t) - w * std::cos(w * t)) / den + 5 * a * w / den * std::exp(-a * t);
  };
  auto end_error = [&](double h) {
    RunResult r = simulate(netlist, {v("out")}, "radau5", h, T, true);
    EXPECT_EQ(r.summary.stepper.lcp.lemke_calls, 0);
    return std::abs(r.sink.rows.back()(0) - exact(T));
  };
  const double e1 = end_error(80e-6), e2 = end_error(40e-6), e3 = end_error(20e-6);
  const auto [p1, p2] = observed_orders(e1, e2, e3);
  EXPECT_NEAR(p1, 5.0, 0.3) << e1 << " " << e2;
  EXPECT_NEAR(p2, 5.0, 0.3) << e2 << " " << e3;
  EXPECT_GT(e3, 1e-11);
}

// No states (n = 0): a half-wave rectifier into a resistor is a static LCP at t + h (c_s = 1),
// v(out) = max(0, u - VON) R/(R + RON) exactly at every step.
TEST(RadauWithoutStates, HalfWaveIntoResistorIsExact) {
  const double VON = 0.6, RON = 2, R = 50;
  NetlistBuilder b;
  b.tran(1e-4, 40e-3, false);
  b.v("v1", "in", "0", NetlistBuilder::sin(0, 10, 50)).d("d1", "in", "out", VON, RON);
  b.r("rl", "out", "0", R);
  for (const char* method : {"radau3", "radau5"}) {
    RunResult r = simulate(b.build(), {v("out"), i("d1")}, method, 1e-4, 40e-3, false);
    ASSERT_EQ(r.sink.times.size(), 401u);
    int conducting = 0;
    for (size_t n = 0; n < r.sink.times.size(); ++n) {
      const double u = 10 * std::sin(2 * M_PI * 50 * r.sink.times[n]);
      const double expected = std::max(0.0, u - VON) * R / (R + RON);
      EXPECT_NEAR(r.sink.rows[n](0), expected, 1e-12) << method << " step " << n;
      EXPECT_NEAR(r.sink.rows[n](1), expected / R, 1e-14) << method << " step " << n;
      conducting += expected > 0;
    }
    EXPECT_GT(conducting, 150);
    EXPECT_LT(conducting, 250);
  }
}

// ---------------------------------------------------------------------------------------------
// A switching circuit

// The half-wave rectifier of circuits/half_wave_rectifier.cir (Stewart Fig. 1.6): SIN(0 10 50)
// through a diode (VON 0.7, RON 0.1) into L = 10 mH, C = 470 uF, R = 22; the diode turns off when
// the inductor current reaches zero.
Netlist half_wave_rectifier() {
  NetlistBuilder b;
  b.tran(20e-6, 60e-3, false);
  b.v("v1", "in", "0", NetlistBuilder::sin(0, 10, 50)).d("d1", "in", "n1", 0.7, 0.1);
  b.l("l1", "n1", "out", 10e-3).c("c1", "out", "0", 470e-6).r("r1", "out", "0", 22);
  return b.build();
}

// Every step's end stage solves its complementarity problem: z >= 0, w = C x + D z + F u >= 0,
// z . w = 0 (to rounding), and both the conducting and the blocking mode occur.
TEST(RadauHalfWaveRectifier, ComplementarityHoldsAtEveryStep) {
  ModelOptions mo;
  mo.t1 = 60e-3;
  const CircuitModel model = CircuitModel::build(half_wave_rectifier(), mo);
  const Lcs& s = model.lcs();
  ASSERT_EQ(s.pairs(), 1);
  for (int stages : {2, 3}) {
    RadauIIA radau(model, stages);
    const double h = 20e-6;
    Eigen::VectorXd x = initial_state(model, false, 0.0).x, z(s.pairs());
    radau.Start(0.0, h, x, z);
    int on = 0, off = 0;
    for (int k = 1; k <= 3000; ++k) {
      radau.Step((k - 1) * h, h, x, z);
      const Eigen::VectorXd w = s.C * x + s.D * z + s.F * model.input_values(k * h);
      // w is a current (A) or a voltage margin (V), z the other: both of order 1 here.
      const double scale = 1 + x.cwiseAbs().maxCoeff() + z.cwiseAbs().maxCoeff();
      ASSERT_GE(z.minCoeff(), 0.0) << "step " << k;
      ASSERT_GE(w.minCoeff(), -1e-12 * scale) << "step " << k;
      ASSERT_LE(std::abs(z.dot(w)), 1e-12 * scale * scale) << "step " << k;
      on += z(0) > 0;
      off += w(0) > 1e-9;
    }
    EXPECT_GT(on, 300) << stages;
    EXPECT_GT(off, 300) << stages;
    EXPECT_EQ(radau.stats().steps, 3000);
  }
}

// radau3/radau5 at the netlist's step (20 us) against implicit Euler at 0.4 and 0.2 us,
// Richardson-extrapolated (2 E(h/2) - E(h)): Euler's own error is first order, 2.04e-3 and
// 1.02e-3 V on v(out) (against radau5 at 0.5 us), the extrapolation's 1.3e-7 V. Where the diode
// switches, a method that does not locate the instant is first order, so Radau's gap comes from
// the switching steps: measured 6.6e-6 V (radau3) and 8.2e-6 V (radau5) on v(out) (up to 8.3 V),
// 1.7e-6 and 1.6e-6 A on i(l1) (up to 0.6 A). Bounds: 2e-5 V and 5e-6 A.
TEST(RadauHalfWaveRectifier, AgreesWithExtrapolatedFineImplicitEuler) {
  const std::vector<Probe> probes = {v("out"), i("l1")};
  const RunResult coarse = simulate(half_wave_rectifier(), probes, "euler", 0.4e-6, 60e-3, false);
  const RunResult fine = simulate(half_wave_rectifier(), probes, "euler", 0.2e-6, 60e-3, false);
  for (const char* method : {"radau3", "radau5"}) {
    const RunResult r = simulate(half_wave_rectifier(), probes, method, 20e-6, 60e-3, false);
    ASSERT_EQ(r.sink.times.size(), 3001u);
    double dv = 0, di = 0;
    for (size_t n = 0; n < r.sink.times.size(); ++n) {
      const Eigen::VectorXd& e1 = coarse.sink.rows[50 * n];
      const Eigen::VectorXd& e2 = fine.sink.rows[100 * n];
      ASSERT_NEAR(fine.sink.times[100 * n], r.sink.times[n], 1e-12);
      ASSERT_NEAR(coarse.sink.times[50 * n], r.sink.times[n], 1e-12);
      const Eigen::VectorXd reference = 2 * e2 - e1;
      dv = std::max(dv, std::abs(r.sink.rows[n](0) - reference(0)));
      di = std::max(di, std::abs(r.sink.rows[n](1) - reference(1)));
    }
    EXPECT_LT(dv, 2e-5) << method;
    EXPECT_LT(di, 5e-6) << method;
  }
}

// A 1 nF capacitor at 5 V discharging through 1 kOhm into a diode (VON 0.7, RON 0), tau = 1 us,
// one radau3 step of h = 10 tau. With zeta_j = R Z_j and A = 0 the stage LCP is
// w = -4.3 + (I + 10 𝒜) zeta >= 0 ⟂ zeta >= 0; its unique solution (I + 10 𝒜 is a P-matrix) has
// stage 2 blocking: zeta_1 = 4.3 / (1 + 50/12), x+ = 5 - 10 * (3/4) zeta_1 = -77/62 V. Radau IIA is
// not monotone: the diode then holds the undershoot (implicit Euler ends at 0.7 V).
TEST(RadauDischargeWithHugeStep, EndsWhereTheStageSystemPutsIt) {
  NetlistBuilder b;
  b.c("c1", "b", "0", 1e-9, 5.0).r("r1", "b", "a", 1e3).d("d1", "a", "0", 0.7, 0.0);
  const RunResult r = simulate(b.build(), {v("b"), i("d1")}, "radau3", 10e-6, 30e-6, true);
  ASSERT_EQ(r.sink.times.size(), 4u);
  EXPECT_NEAR(r.sink.rows[1](0), -77.0 / 62, 1e-12);
  EXPECT_EQ(r.sink.rows[1](1), 0.0);  // Z_s = 0: the diode blocks at the end of the step
  EXPECT_NEAR(r.sink.rows[3](0), -77.0 / 62, 1e-12);
}

// ---------------------------------------------------------------------------------------------
// Many pairs

// 15 SinChargedRc branches (different C) on one source, each with a blocking diode (VON 0.5)
// across its capacitor: m = 30 pairs, so radau5 solves LCPs of size 90, beyond the 64 pairs the
// warm solver caches active sets for (it falls back to Lemke every step). Every branch must
// still follow its closed form.
TEST(RadauManyPairs, ThirtyPairsFollowTheirClosedForms) {
  NetlistBuilder b;
  const SinChargedRc proto;
  b.v("v1", "in", "0", NetlistBuilder::sin(proto.vo, proto.va, proto.freq));
  std::vector<SinChargedRc> branches;
  std::vector<Probe> probes;
  for (int k = 0; k < 15; ++k) {
    SinChargedRc rc;
    rc.c = (1 + 0.2 * k) * 1e-6;
    rc.netlist(std::to_string(k), &b);
    b.d("x" + std::to_string(k), "0", "b" + std::to_string(k), 0.5, 0.0);
    branches.push_back(rc);
    probes.push_back(v("b" + std::to_string(k)));
    probes.push_back(i("x" + std::to_string(k)));
  }
  const double T = 2e-3;
  for (const char* method : {"radau3", "radau5"}) {
    const RunResult r = simulate(b.build(), probes, method, 10e-6, T, true);
    ASSERT_EQ(r.sink.times.size(), 201u);
    double err = 0, blocked = 0;
    for (size_t n = 0; n < r.sink.times.size(); ++n)
      for (int k = 0; k < 15; ++k) {
        err = std::max(err, std::abs(r.sink.rows[n](2 * k) - branches[k].v(r.sink.times[n])));
        blocked = std::max(blocked, std::abs(r.sink.rows[n](2 * k + 1)));
      }
    // Measured 2.5e-7 V (radau3) and 1.3e-12 V (radau5) at h = 10 us, as their orders predict
    // from the single-branch tests; a wrong stage input or a lost pair would show at 1e-2 V.
    EXPECT_LT(err, std::string(method) == "radau3" ? 1e-6 : 1e-10) << method;
    EXPECT_EQ(blocked, 0.0) << method;
    EXPECT_EQ(r.summary.stepper.lcp.solves, 201) << method;
  }
}

// ---------------------------------------------------------------------------------------------
// Cost

// Steps within one mode (warm hits on cached factors) allocate nothing: the stage inputs, the
// LCP vector and the new state live in preallocated members.
TEST(RadauAllocation, SteadyStepsDoNotAllocate) {
#ifndef LCS_COUNT_ALLOCS
  GTEST_SKIP() << "allocation counting needs glibc and no sanitizer";
#else
  const SinChargedRc rc;
  ModelOptions mo;
  mo.t1 = 2e-3;
  const CircuitModel model = CircuitModel::build(rc.netlist(), mo);
  for (int stages : {2, 3}) {
    RadauIIA radau(model, stages);
    const double h = 10e-6;
    Eigen::VectorXd x = initial_state(model, true, 0.0).x, z(model.lcs().pairs());
    radau.Start(0.0, h, x, z);
    for (int k = 0; k < 5; ++k) radau.Step(k * h, h, x, z);  // factorise, find the mode
    const long hits_before = radau.stats().lcp.warm_hits;
    g_allocs = 0;
    g_counting = true;
    for (int k = 5; k < 105; ++k) radau.Step(k * h, h, x, z);
    g_counting = false;
    EXPECT_EQ(g_allocs.load(), 0) << stages;
    EXPECT_EQ(radau.stats().lcp.warm_hits - hits_before, 100) << stages;
    EXPECT_GT(z(0), 0.0);  // the diode conducted throughout
  }
#endif
}

// A bridge with no load, its capacitor (1 uF) referenced by 1 GOhm, RON = 0.05: once D1 and D4
// conduct, tau i' + i = C Vs'(t) with tau = 2 RON C = 0.1 us, so a few tau after turn-on
// i = C A w (cos wt + tau w sin wt) / (1 + (tau w)^2). The stage LCP of a collocation step is
// not a P-matrix here (the 1 GOhm loops make its diagonal blocks rank one): seven stage patterns
// solve it at h = 0.1 us. The turn-on step ends with its first stage blocking, and when that
// pattern was kept as the next steps' first guess it kept solving them: i(d1) sat at 0.088 A
// (C dv/dt of the rows 0.062 A) for the whole conduction. Each step now starts from the mode the
// last one ended in, in every stage (LcpWarmSolver::continue_last_block).
TEST(RadauNoLoadBridge, StagesContinueTheModeTheLastStepEndedIn) {
  const double amplitude = 10, freq = 1e3, C = 1e-6, ron = 0.05;
  NetlistBuilder b;
  b.tran(1e-7, 200e-6, true);
  b.v("v1", "a", "b", NetlistBuilder::sin(0, amplitude, freq)).r("rg", "b", "0", 1e9);
  b.d("d1", "a", "p", 0.7, ron).d("d2", "b", "p", 0.7, ron).d("d3", "n", "a", 0.7, ron);
  b.d("d4", "n", "b", 0.7, ron).c("c1", "p", "n", C, 0.0).r("rc", "n", "0", 1e9);
  const double w = 2 * M_PI * freq, tau = 2 * ron * C;
  for (const char* method : {"radau3", "radau5"}) {
    const RunResult r = simulate(b.build(), {i("d1")}, method, 1e-7, 200e-6, true);
    double worst = 0;
    int rows = 0;
    for (size_t n = 0; n < r.sink.times.size(); ++n) {
      const double t = r.sink.times[n];
      if (t < 30e-6) continue;  // turn-on at 22.4 us; its transient is e^-76 by 30 us
      const double closed = C * amplitude * w * (std::cos(w * t) + tau * w * std::sin(w * t)) /
                            (1 + tau * w * tau * w);
      worst = std::max(worst, std::abs(r.sink.rows[n](0) - closed));
      ++rows;
    }
    EXPECT_GT(rows, 1600) << method;
    EXPECT_LT(worst, 1e-6) << method;  // i(d1) up to 0.062 A
  }
}

}  // namespace
}  // namespace lcs
