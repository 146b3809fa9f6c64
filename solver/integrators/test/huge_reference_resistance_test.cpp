// Circuits referenced to ground by a huge resistance (a floating source or load tied down by
// 1 TOhm, as decks do to give every node a DC path). The loop through the reference resistors
// puts 2e12 beside the diodes' 0.05 Ohm in the step LCP's M (M = 2e12 u u^T + S), and Lemke's
// method ended on a ray at the first conduction: every fixed-step method stopped with exit 3
// while the event method ran. Principal pivoting answers those steps (warm_solver.cpp); the
// answer is the one the same bridge gives with well-conditioned 1 GOhm references.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "solver/integrators/transient.h"
#include "solver/model/numerical_failure.h"
#include "tests/support/netlist_builder.h"

namespace lcs {
namespace {

using testing::NetlistBuilder;

// A bridge with no load but its 1 uF capacitor, from a floating 10 V, 1 kHz source.
Netlist referenced_bridge(double reference) {
  NetlistBuilder b;
  b.tran(0.1e-6, 2e-3, true);
  b.v("v1", "a", "b", NetlistBuilder::sin(0, 10, 1e3)).r("rg", "b", "0", reference);
  b.d("d1", "a", "p", 0.7, 0.05).d("d2", "b", "p", 0.7, 0.05).d("d3", "n", "a", 0.7, 0.05).d("d4", "n", "b", 0.7, 0.05);
  b.c("c1", "p", "n", 1e-6, 0.0).r("rc", "n", "0", reference);
  return b.build();
}

struct BridgeRun {
  MemorySink sink;
  std::vector<double> column(const std::string& name) const {
    const int c = sink.column(name);
    EXPECT_GE(c, 0) << name;
    std::vector<double> y;
    for (const Eigen::VectorXd& row : sink.rows) y.push_back(c >= 0 ? row(c) : NAN);
    return y;
  }
};

BridgeRun simulate(double reference, const std::string& method) {
  const Netlist netlist = referenced_bridge(reference);
  ModelOptions mo;
  mo.t1 = 2e-3;
  CircuitModel model = CircuitModel::build(netlist, mo);
  TransientOptions o;
  o.method = method;
  o.step = 0.1e-6;
  o.tstop = 2e-3;
  o.uic = true;
  const std::vector<Probe> probes = {{Probe::Kind::NodeVoltage, "p", "", {}},
                                     {Probe::Kind::NodeVoltage, "n", "", {}},
                                     {Probe::Kind::ElementCurrent, "d1", "", {}}};
  BridgeRun r;
  run_transient(model, model.output_map(probes), o, r.sink);
  return r;
}

double max_abs(const std::vector<double>& y) {
  double m = 0;
  for (double v : y) m = std::max(m, std::abs(v));
  return m;
}

// Each fixed-step method runs the 1 TOhm bridge through, and its waveform is its own on the
// 1 GOhm bridge (the references carry nanoamperes either way). Tolerances: D1's current to
// 5e-3 of its peak, the bound from M's small part being stored beside 2e12 to 2.4e-4 (0.5 % of
// RON = 0.05; measured 1.6e-4 / 3.9e-4 / 9.7e-4 of the peak for euler / theta / radau5); the
// capacitor's voltage to 1 mV (measured 2e-5 V, of 8.6 V).
TEST(HugeReferenceResistance, FixedStepMethodsRunTheBridgeAsWithSmallerReferences) {
  for (const std::string method : {"euler", "theta", "radau5"}) {
    SCOPED_TRACE(method);
    const BridgeRun tera = simulate(1e12, method), giga = simulate(1e9, method);
    ASSERT_EQ(tera.sink.times.size(), 20001u);
    ASSERT_EQ(giga.sink.times.size(), tera.sink.times.size());
    const std::vector<double> i1 = tera.column("i(d1)"), i0 = giga.column("i(d1)");
    const std::vector<double> p1 = tera.column("v(p)"), n1 = tera.column("v(n)");
    const std::vector<double> p0 = giga.column("v(p)"), n0 = giga.column("v(n)");
    const double peak = max_abs(i0);
    EXPECT_GT(peak, 0.06);  // the first charging pulse
    double current_gap = 0, voltage_gap = 0, charged = 0;
    for (std::size_t k = 0; k < i1.size(); ++k) {
      current_gap = std::max(current_gap, std::abs(i1[k] - i0[k]));
      voltage_gap = std::max(voltage_gap, std::abs((p1[k] - n1[k]) - (p0[k] - n0[k])));
      charged = std::max(charged, p1[k] - n1[k]);
    }
    EXPECT_LT(current_gap, 5e-3 * peak);
    EXPECT_LT(voltage_gap, 1e-3);
    EXPECT_NEAR(charged, 10 - 2 * 0.7, 0.01);  // the peak less two diodes' VON
  }
}

// A floating source charging a capacitor through D1 and D4, its low side referenced by a
// resistor across D4. In the mode with both diodes on, D's singular values are 2 R and RON: at
// R = 1 TOhm, 0.05 beside 2e12 (113 eps of it), which the event method counted as zero, so
// the loop ran as RON = 0 and charged the 2200 uF capacitor in an impulse: i(d1) = 8.24 A at
// turn-on where implicit Euler ramps up from 0.28 A (a prober's deck). Now that mode stops the
// event method with its reason; at 1 GOhm (5e-11) the method runs and agrees with Euler.
Netlist floating_source_charger(double reference) {
  NetlistBuilder b;
  b.tran(10e-6, 2e-3, false);
  b.v("v1", "a", "b", NetlistBuilder::sin(0, 12, 50)).d("d1", "a", "p", 0.7, 0.05).d("d4", "0", "b", 0.7, 0.05);
  b.c("c1", "p", "0", 2200e-6, 0.0).r("rref", "b", "0", reference);
  return b.build();
}

TEST(HugeReferenceResistance, EventMethodStopsWhereItCannotResolveTheLoop) {
  const Netlist netlist = floating_source_charger(1e12);
  ModelOptions mo;
  mo.t1 = 2e-3;
  CircuitModel model = CircuitModel::build(netlist, mo);
  TransientOptions o;
  o.method = "event";
  o.step = 10e-6;
  o.tstop = 2e-3;
  o.uic = true;
  MemorySink sink;
  try {
    run_transient(model, model.output_map({{Probe::Kind::ElementCurrent, "d1", "", {}}}), o, sink);
    ADD_FAILURE() << "the event method ran the unresolved loop";
  } catch (const NumericalFailure& e) {
    EXPECT_NEAR(e.time(), 3.722e-4, 1e-7);  // the turn-on
    EXPECT_NE(std::string(e.what()).find("d1, d4 conducting holds a resistance of 0.05"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("beside 2e+12 ohm"), std::string::npos) << e.what();
  }
  for (const Eigen::VectorXd& row : sink.rows) EXPECT_LT(std::abs(row(0)), 1.0);  // no impulse written
}

TEST(HugeReferenceResistance, EventMethodRunsTheResolvedLoop) {
  const Netlist netlist = floating_source_charger(1e9);
  ModelOptions mo;
  mo.t1 = 2e-3;
  CircuitModel model = CircuitModel::build(netlist, mo);
  auto run = [&](const std::string& method) {
    TransientOptions o;
    o.method = method;
    o.step = method == "event" ? 10e-6 : 0.1e-6;
    o.tstop = 2e-3;
    o.uic = true;
    MemorySink sink;
    run_transient(model, model.output_map({{Probe::Kind::ElementCurrent, "d1", "", {}}}), o, sink);
    return sink;
  };
  const MemorySink event = run("event"), euler = run("euler");
  // At 0.5, 1 and 2 ms (rows of both): the ramp after turn-on, within Euler's first-order error
  // at 0.1 us (the current is ~1 A and moves over RON C = 220 us: measured below 1e-3 A).
  for (double t : {0.5e-3, 1e-3, 2e-3}) {
    double a = NAN, b = NAN;
    for (std::size_t k = 0; k < event.times.size(); ++k)
      if (std::abs(event.times[k] - t) < 1e-12) a = event.rows[k](0);
    for (std::size_t k = 0; k < euler.times.size(); ++k)
      if (std::abs(euler.times[k] - t) < 1e-12) b = euler.rows[k](0);
    EXPECT_NEAR(a, b, 1e-3) << t;
    EXPECT_GT(a, 0.1) << t;
  }
}

}  // namespace
}  // namespace lcs
