// LTspice's instance parasitics on L, C and V cards: each its own element beside the card's
// (instance_parasitics.h), series ones through internal nodes, parallel ones across the card.
#include <gtest/gtest.h>

#include "netlist/netlist.h"
#include "netlist/test/parse_helpers.h"

namespace lcs {
namespace {

std::string nodes(const Element& e) { return e.nodes.at(0) + " " + e.nodes.at(1); }

TEST(InstanceParasitics, InductorSeriesAndParallelOnes) {
  const Netlist n = test::parse("t\nV1 a 0 1\nL1 a b 10u Rser=0.05 Rpar=10k Cpar=2p\nR1 b 0 1\n");
  ASSERT_EQ(n.elements.size(), 6u);
  EXPECT_EQ(nodes(test::element(n, "l1")), "l1#rser b");
  EXPECT_DOUBLE_EQ(test::element(n, "l1").value, 10e-6);
  const Element& rser = test::element(n, "l1#rser");
  EXPECT_EQ(rser.kind, ElementKind::Resistor);
  EXPECT_EQ(nodes(rser), "a l1#rser");
  EXPECT_DOUBLE_EQ(rser.value, 0.05);
  EXPECT_EQ(test::element(n, "l1#rpar").kind, ElementKind::Resistor);
  EXPECT_EQ(nodes(test::element(n, "l1#rpar")), "a b");
  EXPECT_DOUBLE_EQ(test::element(n, "l1#rpar").value, 1e4);
  EXPECT_EQ(test::element(n, "l1#cpar").kind, ElementKind::Capacitor);
  EXPECT_EQ(nodes(test::element(n, "l1#cpar")), "a b");
  EXPECT_DOUBLE_EQ(test::element(n, "l1#cpar").value, 2e-12);
  EXPECT_TRUE(n.warnings.empty());
}

// Rser then Lser from the first node to the capacitor; IC= stays the capacitor's.
TEST(InstanceParasitics, CapacitorSeriesChainKeepsItsInitialCondition) {
  const Netlist n = test::parse("t\nV1 a 0 1\nC1 a 0 100u Rser=10m Lser=5n IC=2\n");
  EXPECT_EQ(nodes(test::element(n, "c1#rser")), "a c1#rser");
  EXPECT_EQ(test::element(n, "c1#lser").kind, ElementKind::Inductor);
  EXPECT_EQ(nodes(test::element(n, "c1#lser")), "c1#rser c1#lser");
  EXPECT_DOUBLE_EQ(test::element(n, "c1#lser").value, 5e-9);
  EXPECT_EQ(nodes(test::element(n, "c1")), "c1#lser 0");
  EXPECT_EQ(test::element(n, "c1").ic, 2.0);
}

TEST(InstanceParasitics, VoltageSourceRserAndCparAndZeroMeansNone) {
  const Netlist n = test::parse("t\nV1 a 0 SINE(0 5 1k) Rser=1 Cpar=1n\nR1 a 0 1k\nL1 a 0 1m Rser=0\n");
  EXPECT_EQ(nodes(test::element(n, "v1")), "v1#rser 0");
  EXPECT_EQ(test::element(n, "v1").waveform.kind, Waveform::Kind::Sin);
  EXPECT_EQ(nodes(test::element(n, "v1#rser")), "a v1#rser");
  EXPECT_EQ(nodes(test::element(n, "v1#cpar")), "a 0");
  EXPECT_EQ(nodes(test::element(n, "l1")), "a 0");  // Rser=0: none
  EXPECT_EQ(n.find_element("l1#rser"), nullptr);
}

// m copies in parallel: their parasitics in parallel too (R and L over m, C times m), on the card
// and on a subcircuit instance.
TEST(InstanceParasitics, MultipliersScaleTheParasitics) {
  const Netlist n = test::parse(
      "t\nV1 a 0 1\nL1 a 0 10u Rser=1 Cpar=1p m=2\n"
      ".subckt cap p\nC1 p 0 1u Rser=4 Lser=8n\n.ends\nX1 a cap m=4\n");
  EXPECT_DOUBLE_EQ(test::element(n, "l1").value, 5e-6);
  EXPECT_DOUBLE_EQ(test::element(n, "l1#rser").value, 0.5);
  EXPECT_DOUBLE_EQ(test::element(n, "l1#cpar").value, 2e-12);
  EXPECT_DOUBLE_EQ(test::element(n, "x1.c1").value, 4e-6);
  EXPECT_DOUBLE_EQ(test::element(n, "x1.c1#rser").value, 1.0);
  EXPECT_DOUBLE_EQ(test::element(n, "x1.c1#lser").value, 2e-9);
  EXPECT_EQ(nodes(test::element(n, "x1.c1")), "x1.c1#lser 0");
}

TEST(InstanceParasitics, BadValuesPointAtThem) {
  EXPECT_EQ(test::diag("t\nL1 a 0 1m Rpar=0\n"),
            "t.cir:2:16: error: Rpar of 'l1' must be positive\nL1 a 0 1m Rpar=0\n               ^");
  EXPECT_EQ(test::diag("t\nC1 a 0 1u Rser=-1\n"),
            "t.cir:2:16: error: Rser of 'c1' must be zero (none) or positive\nC1 a 0 1u Rser=-1\n               ^~");
  EXPECT_EQ(test::diag("t\nC1 a 0 1u Rser=1 rser=2\n"),
            "t.cir:2:18: error: 'rser' given twice for 'c1'\nC1 a 0 1u Rser=1 rser=2\n                 ^~~~");
}

// A node of the deck that has the name of an internal node would join the parasitic's chain.
TEST(InstanceParasitics, ADeckNodeNamedLikeAnInternalNodeIsRefused) {
  EXPECT_EQ(test::diag("t\nV1 in 0 DC 1 Rser=1\nR1 v1#rser 0 1\nR2 in 0 1\n"),
            "t.cir:3:1: error: 'r1' connects to node 'v1#rser', the internal node lcspice makes for an instance "
            "parasitic (Rser=, Lser=): rename the node\nR1 v1#rser 0 1\n^~");
}

}  // namespace
}  // namespace lcs
