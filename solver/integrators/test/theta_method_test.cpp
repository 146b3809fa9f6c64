// Closed-form checks of the theta-method time-stepping on diode circuits.
#include <cmath>

#include <gtest/gtest.h>

#include "solver/integrators/transient.h"
#include "tests/support/lc_tank_bridge.h"
#include "tests/support/netlist_builder.h"

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
             double h, double tstop, bool uic, double theta = 0.5) {
  ModelOptions mo;
  mo.t1 = tstop;
  CircuitModel model = CircuitModel::build(netlist, mo);
  TransientOptions o;
  o.method = method;
  o.method_options.theta = theta;
  o.step = h;
  o.tstop = tstop;
  o.uic = uic;
  RunResult r;
  r.summary = run_transient(model, model.output_map(probes), o, r.sink);
  return r;
}

Probe v(const std::string& node) { return {Probe::Kind::NodeVoltage, node, "", {}}; }
Probe i(const std::string& element) { return {Probe::Kind::ElementCurrent, element, "", {}}; }

// RC charged through a diode from a DC source, capacitor initially empty (UIC): the diode stays
// on, v(t) = (V - VON)(1 - exp(-t/tau)) with tau = (R + RON) C. Implicit Euler reproduces the
// exact discrete recursion v_n = (V - VON)(1 - (1 + h/tau)^-n).
class RcThroughDiode : public ::testing::TestWithParam<std::pair<double, double>> {};

Netlist rc_through_diode(double V, double VON, double RON, double R, double C) {
  NetlistBuilder b;
  b.v("v1", "in", "0", NetlistBuilder::dc(V)).d("d1", "in", "a", VON, RON);
  b.r("r1", "a", "out", R).c("c1", "out", "0", C, 0.0);
  return b.build();
}

TEST_P(RcThroughDiode, ImplicitEulerMatchesItsDiscreteClosedForm) {
  const auto [VON, RON] = GetParam();
  const double V = 10, R = 1e3, C = 1e-6, tau = (R + RON) * C, h = 2e-5;
  RunResult r = simulate(rc_through_diode(V, VON, RON, R, C), {v("out"), i("d1")}, "euler", h, 5e-3, true);
  ASSERT_EQ(r.sink.times.size(), 251u);
  for (size_t n = 0; n < r.sink.times.size(); ++n) {
    const double exact = (V - VON) * (1 - std::pow(1 + h / tau, -static_cast<double>(n)));
    EXPECT_NEAR(r.sink.rows[n](0), exact, 1e-12 * V) << "step " << n;
    // diode current = capacitor current = (V - VON - v)/(R + RON); at t = 0 it comes from the
    // start-up LCP (a step of 1e-8/|A|), hence the looser bound there.
    EXPECT_NEAR(r.sink.rows[n](1), (V - VON - exact) / (R + RON), (n > 0 ? 1e-14 : 1e-7) * V / R)
        << "step " << n;
  }
}

TEST_P(RcThroughDiode, ImplicitEulerIsFirstOrder) {
  // Plain variables, not a structured binding: the lambda below captures VON, which C++17
  // (and clang 14) does not allow for bindings.
  const double VON = GetParam().first, RON = GetParam().second;
  const double V = 10, R = 1e3, C = 1e-6, tau = (R + RON) * C, T = 2e-3;
  const Netlist netlist = rc_through_diode(V, VON, RON, R, C);
  auto error = [&](double h) {
    RunResult r = simulate(netlist, {v("out")}, "euler", h, T, true);
    double e = 0;
    for (size_t n = 0; n < r.sink.times.size(); ++n)
      e = std::max(e, std::abs(r.sink.rows[n](0) - (V - VON) * (1 - std::exp(-r.sink.times[n] / tau))));
    return e;
  };
  const double e1 = error(4e-5), e2 = error(2e-5), e3 = error(1e-5);
  EXPECT_NEAR(e1 / e2, 2.0, 0.1);
  EXPECT_NEAR(e2 / e3, 2.0, 0.05);
}

// A charged capacitor discharging through R into an ideal diode, tau = 1 us, run with h = 1 s:
// the t = 0 row must still show the consistent start (diode current V/R, v(a) = 0), not a
// current averaged over a start-up step comparable to tau.
TEST(RcThroughDiode, StartRowIsConsistentWhenTheStepDwarfsTheTimeConstant) {
  NetlistBuilder b;
  b.c("c1", "b", "0", 1e-9, 5.0).r("r1", "b", "a", 1e3).d("d1", "a", "0");
  RunResult r = simulate(b.build(), {v("a"), i("d1")}, "euler", 1.0, 2.0, true);
  EXPECT_NEAR(r.sink.rows[0](0), 0.0, 1e-6);
  EXPECT_NEAR(r.sink.rows[0](1), 5e-3, 1e-10);
}

INSTANTIATE_TEST_SUITE_P(Laws, RcThroughDiode,
                         ::testing::Values(std::make_pair(0.0, 0.0), std::make_pair(0.7, 0.0),
                                           std::make_pair(0.7, 25.0)));

// Half-wave rectifier into a resistor: no states, v(out) = max(0, u - VON) R/(R + RON) exactly.
TEST(HalfWaveIntoResistor, EveryStepIsExact) {
  const double VON = 0.6, RON = 2, R = 50;
  NetlistBuilder b;
  b.tran(1e-4, 40e-3, false);
  b.v("v1", "in", "0", NetlistBuilder::sin(0, 10, 50)).d("d1", "in", "out", VON, RON);
  b.r("rl", "out", "0", R);
  RunResult r = simulate(b.build(), {v("out"), i("d1")}, "euler", 1e-4, 40e-3, false);
  int conducting = 0;
  for (size_t n = 0; n < r.sink.times.size(); ++n) {
    const double u = 10 * std::sin(2 * M_PI * 50 * r.sink.times[n]);
    const double expected = std::max(0.0, u - VON) * R / (R + RON);
    EXPECT_NEAR(r.sink.rows[n](0), expected, 1e-12);
    EXPECT_NEAR(r.sink.rows[n](1), expected / R, 1e-14);
    conducting += expected > 0;
  }
  EXPECT_GT(conducting, 150);  // both half-cycles were exercised
  EXPECT_LT(conducting, 250);
}

// The LC-tank bridge (tests/support/lc_tank_bridge.h): the tank voltage is a damped RLC solution.
double lc_tank_error(const std::string& method, double h, double theta = 0.5) {
  RunResult r = simulate(lc_tank_bridge(), {v("a")}, method, h, 5e-3, true, theta);
  double e = 0;
  for (size_t n = 0; n < r.sink.times.size(); ++n)
    e = std::max(e, std::abs(r.sink.rows[n](0) - lc_tank_closed_form(r.sink.times[n])));
  return e;
}

TEST(LcTankBridge, ImplicitEulerConvergesAtFirstOrder) {
  const double e1 = lc_tank_error("euler", 2e-6), e2 = lc_tank_error("euler", 1e-6),
               e3 = lc_tank_error("euler", 5e-7);
  // Implicit Euler damps the oscillation at the rate w0^2 h / 2, so its error grows like
  // v0 (w0^2 h / 2) t exp(-alpha t), largest at t = 1/alpha: v0 w0^2 h / (2 alpha e) = 0.184 V.
  const double predicted = 10 * 1e8 * 5e-7 / (2 * 500 * std::exp(1.0));
  EXPECT_NEAR(e3, predicted, 0.1 * predicted);
  EXPECT_NEAR(e1 / e2, 2.0, 0.15);
  EXPECT_NEAR(e2 / e3, 2.0, 0.1);
}

TEST(LcTankBridge, TrapezoidalConvergesAtSecondOrder) {
  const double e1 = lc_tank_error("theta", 4e-6), e2 = lc_tank_error("theta", 2e-6);
  EXPECT_NEAR(e1 / e2, 4.0, 0.4);
}

TEST(LcTankBridge, WarmStartAnswersMostSteps) {
  RunResult r = simulate(lc_tank_bridge(), {v("a")}, "euler", 1e-6, 5e-3, true);
  EXPECT_EQ(r.summary.stepper.steps, 5000);
  EXPECT_EQ(r.summary.stepper.lcp.solves, 5001);  // + the t0 consistency LCP
  EXPECT_GT(r.summary.stepper.lcp.warm_hits, 4900);
}

}  // namespace
}  // namespace lcs
