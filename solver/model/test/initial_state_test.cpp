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
