#include "solver/model/initial_state.h"

#include <gtest/gtest.h>

#include "tests/support/netlist_builder.h"

namespace lcs {
namespace {

using testing::NetlistBuilder;

// v1 -> r1 -> out, c1 from out to ground; r2 from out to ground. Operating point:
// v(out) = 10 * r2/(r1 + r2) = 5 V.
Netlist divider_with_capacitor(std::optional<double> ic_element, std::optional<double> ic_node) {
  NetlistBuilder b;
  b.v("v1", "in", "0", NetlistBuilder::dc(10)).r("r1", "in", "out", 1e3).r("r2", "out", "0", 1e3);
  b.c("c1", "out", "0", 1e-6, ic_element);
  Netlist n = b.build();
  if (ic_node) n.node_ics.push_back({"out", *ic_node, {}});
  return n;
}

double initial_v_out(const Netlist& n, bool uic) {
  CircuitModel m = CircuitModel::build(n, {});
  InitialState init = initial_state(m, uic, 0.0);
  return m.physical_state(init.x, 0.0)(0);
}

TEST(InitialState, OperatingPointWithoutUic) {
  EXPECT_NEAR(initial_v_out(divider_with_capacitor({}, {}), false), 5.0, 1e-12);
}

TEST(InitialState, UicStartsFromZero) {
  EXPECT_EQ(initial_v_out(divider_with_capacitor({}, {}), true), 0.0);
}

TEST(InitialState, NodeIcOverridesTheOperatingPointAndZero) {
  EXPECT_NEAR(initial_v_out(divider_with_capacitor({}, 2.0), false), 2.0, 1e-12);
  EXPECT_NEAR(initial_v_out(divider_with_capacitor({}, 2.0), true), 2.0, 1e-12);
}

TEST(InitialState, ElementIcTakesPrecedenceOverNodeIc) {
  EXPECT_NEAR(initial_v_out(divider_with_capacitor(3.0, 2.0), false), 3.0, 1e-12);
  EXPECT_NEAR(initial_v_out(divider_with_capacitor(3.0, {}), true), 3.0, 1e-12);
}

TEST(InitialState, InductorIcAndDependentCapacitorWarning) {
  NetlistBuilder b;
  b.v("v1", "a", "0", NetlistBuilder::dc(1)).c("c1", "a", "0", 1e-6, 7.0);  // forced: across v1
  b.r("r1", "a", "b", 10).l("l1", "b", "0", 1e-3, 0.25);
  CircuitModel m = CircuitModel::build(b.build(), {});
  InitialState init = initial_state(m, true, 0.0);
  ASSERT_EQ(m.states().size(), 1u);
  EXPECT_EQ(m.states()[0].label, "i(l1)");
  EXPECT_NEAR(m.physical_state(init.x, 0.0)(0), 0.25, 1e-15);
  ASSERT_EQ(init.warnings.size(), 1u);
  EXPECT_EQ(init.warnings[0],
            "IC= on c1 ignored: its voltage is fixed by a loop of capacitors and voltage sources");
}

}  // namespace
}  // namespace lcs

namespace lcs {
namespace {

TEST(InitialState, IcOnANodeWithoutAStateCapacitorIsReported) {
  NetlistBuilder b;
  b.v("v1", "in", "0", NetlistBuilder::dc(5)).r("r1", "in", "a", 1e3).r("r2", "a", "b", 1e3);
  b.c("c1", "b", "0", 1e-6);
  Netlist n = b.build();
  n.node_ics.push_back({"a", 2.0, {}});
  CircuitModel m = CircuitModel::build(n, {});
  InitialState init = initial_state(m, true, 0.0);
  ASSERT_EQ(init.warnings.size(), 1u);
  EXPECT_EQ(init.warnings[0], ".ic v(a) ignored: no capacitor whose voltage is a state of the "
                              "circuit connects to node 'a'");
}

// A capacitor with IC= on the node: its IC= wins (SPICE3), and the warning says so. Before, it
// said no capacitor connects to the node.
TEST(InitialState, IcOnANodeWhoseCapacitorHasItsOwnIcNamesThatCapacitor) {
  NetlistBuilder b;
  b.r("r1", "a", "0", 1e3);
  b.c("c1", "a", "0", 1e-6, 2.0);
  Netlist n = b.build();
  n.node_ics.push_back({"a", 5.0, {}});
  CircuitModel m = CircuitModel::build(n, {});
  for (bool uic : {true, false}) {
    InitialState init = initial_state(m, uic, 0.0);
    ASSERT_EQ(init.warnings.size(), 1u) << uic;
    EXPECT_EQ(init.warnings[0], ".ic v(a) ignored: IC= on c1 sets the voltage of the capacitor at node 'a' (a "
                                "device's IC= takes precedence over .ic)");
    EXPECT_DOUBLE_EQ(m.physical_state(init.x, 0.0)(0), 2.0) << uic;
  }
}

}  // namespace
}  // namespace lcs

namespace lcs {
namespace {

// A loop of inductors only: the warning names the states DC leaves free and the rule used.
TEST(InitialState, AnInductorLoopIsChosenOnceAndSaidSo) {
  testing::NetlistBuilder b;
  b.v("v1", "in", "0", testing::NetlistBuilder::dc(5)).r("r1", "in", "a", 10);
  b.l("l1", "a", "0", 1e-3).l("l2", "a", "0", 3e-3);
  CircuitModel m = CircuitModel::build(b.build(), {});
  InitialState init = initial_state(m, false, 0.0);
  ASSERT_EQ(init.warnings.size(), 1u);
  EXPECT_EQ(init.warnings[0],
            "the operating point does not determine i(l1), i(l2) (a loop of inductors, or "
            "capacitors with no DC path): they start at the values of least stored energy (set "
            "IC= with UIC, or .ic, to choose them)");
  const Eigen::VectorXd x = m.physical_state(init.x, 0.0);
  EXPECT_NEAR(x(0), 0.375, 1e-15);  // 0.5 A split 3 : 1, inversely to L
  EXPECT_NEAR(x(1), 0.125, 1e-15);
}

}  // namespace
}  // namespace lcs

namespace lcs {
namespace {

using testing::NetlistBuilder;

// A 1:2 perfectly coupled transformer (k = 1) whose secondary feeds a diode: only the magnetising
// current imag(l1) = i(l1) + 2 i(l2) is a state. IC= on the windings set it as the flux they
// carry together; the winding currents at the start are then the circuit's.
CircuitModel transformer_with_diode(std::optional<double> ic1, std::optional<double> ic2) {
  NetlistBuilder b;
  b.v("v1", "p", "0", NetlistBuilder::sin(0, 10, 1000)).r("r1", "p", "a", 1).l("l1", "a", "0", 1e-3, ic1);
  b.l("l2", "s", "0", 4e-3, ic2).k("k1", "l1", "l2", 1.0).d("d1", "s", "out", 0.7, 0.5).r("rl", "out", "0", 50);
  return CircuitModel::build(b.build(), {});
}

// IC= 1 A on the primary alone: the secondary diode blocks at the start (v(s) = -2 V), so the
// primary does carry 1 A: the flux is 1 A referred to l1 and nothing is reported.
TEST(InitialState, PerfectlyCoupledPrimaryIcHolds) {
  CircuitModel m = transformer_with_diode(1.0, {});
  ASSERT_EQ(m.states().size(), 1u);
  InitialState init = initial_state(m, true, 0.0);
  EXPECT_NEAR(m.physical_state(init.x, 0.0)(0), 1.0, 1e-15);
  EXPECT_TRUE(init.warnings.empty()) << init.warnings.front();
}

// IC= 1 A and 0.5 A: the flux is 1 + 2 x 0.5 = 2 A referred to l1, but the blocking diode leaves
// the secondary no current: the primary starts with all 2 A, and the warning says so.
TEST(InitialState, PerfectlyCoupledIcsThatDisagreeWithTheCircuitAreReported) {
  CircuitModel m = transformer_with_diode(1.0, 0.5);
  InitialState init = initial_state(m, true, 0.0);
  EXPECT_NEAR(m.physical_state(init.x, 0.0)(0), 2.0, 1e-15);
  ASSERT_EQ(init.warnings.size(), 1u);
  EXPECT_EQ(init.warnings[0],
            "IC= on l1 and l2: perfectly coupled windings (k = 1) share one state, imag(l1) = "
            "i(l1) + 2*i(l2), set to 2 A by the IC=s; the circuit starts with i(l1) = 2 A, "
            "i(l2) = 0 A");
}

// Without UIC a winding without IC= brings its operating-point current: 5 V through 2 ohm gives
// i(l1) = 2.5 A, i(l2) = 0; IC= 0.25 A on l2 makes the flux 2.5 + 2 x 0.25 = 3 A. With the
// secondary's 10 ohm the circuit then starts with i(l2) = 1/9 A and i(l1) = 3 - 2/9 A.
TEST(InitialState, PerfectlyCoupledIcWithTheOperatingPoint) {
  NetlistBuilder b;
  b.v("v1", "p", "0", NetlistBuilder::dc(5)).r("r1", "p", "a", 2).l("l1", "a", "0", 1e-3);
  b.l("l2", "s", "0", 4e-3, 0.25).k("k1", "l1", "l2", 1.0).r("r2", "s", "0", 10);
  CircuitModel m = CircuitModel::build(b.build(), {});
  InitialState init = initial_state(m, false, 0.0);
  EXPECT_NEAR(m.physical_state(init.x, 0.0)(0), 3.0, 1e-12);
  ASSERT_EQ(init.warnings.size(), 1u);
  EXPECT_EQ(init.warnings[0],
            "IC= on l2: perfectly coupled windings (k = 1) share one state, imag(l1) = i(l1) + "
            "2*i(l2), set to 3 A by the IC=s; the circuit starts with i(l1) = 2.77778 A, "
            "i(l2) = 0.111111 A");
}

}  // namespace
}  // namespace lcs
