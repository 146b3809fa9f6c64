// Subcircuit flattening: names, nodes, parameters, scoping.
#include <gtest/gtest.h>

#include "netlist/netlist.h"
#include "netlist/test/parse_helpers.h"

namespace lcs {
namespace {

using test::element;
using test::parse;

std::vector<std::string> names(const Netlist& n) {
  std::vector<std::string> out;
  for (const Element& e : n.elements) out.push_back(e.name);
  return out;
}

TEST(ParseSubcircuit, FlattensNamesAndNodes) {
  Netlist n = parse(
      "t\n"
      ".subckt divider top bot\n"
      "R1 top mid 1k\n"
      "R2 mid bot 1k\n"
      "C1 mid 0 1n\n"
      ".ends divider\n"
      "V1 in 0 1\n"
      "X1 in out divider\n"
      "X2 out GND divider\n");
  EXPECT_EQ(names(n), (std::vector<std::string>{"v1", "x1.r1", "x1.r2", "x1.c1", "x2.r1", "x2.r2", "x2.c1"}));
  EXPECT_EQ(element(n, "x1.r1").nodes, (std::vector<std::string>{"in", "x1.mid"}));
  EXPECT_EQ(element(n, "x1.r2").nodes, (std::vector<std::string>{"x1.mid", "out"}));
  EXPECT_EQ(element(n, "x1.c1").nodes, (std::vector<std::string>{"x1.mid", "0"}));  // ground stays ground
  EXPECT_EQ(element(n, "x2.r2").nodes, (std::vector<std::string>{"x2.mid", "0"}));   // port mapped to gnd
  // Elements inside a subcircuit point at their card inside the .subckt
  EXPECT_EQ(element(n, "x2.r2").loc.line, 4);
  EXPECT_EQ(element(n, "x2.r2").loc.line_text, "R2 mid bot 1k");
}

TEST(ParseSubcircuit, NestedInstances) {
  Netlist n = parse(
      "t\n"
      ".subckt leaf a b\n"
      "R1 a b 1\n"
      ".ends\n"
      ".subckt pair p q\n"
      "X1 p m leaf\n"
      "X2 m q leaf\n"
      ".ends pair\n"
      "Xtop in 0 pair\n"
      "Vin in 0 1\n");
  EXPECT_EQ(names(n), (std::vector<std::string>{"xtop.x1.r1", "xtop.x2.r1", "vin"}));
  EXPECT_EQ(element(n, "xtop.x1.r1").nodes, (std::vector<std::string>{"in", "xtop.m"}));
  EXPECT_EQ(element(n, "xtop.x2.r1").nodes, (std::vector<std::string>{"xtop.m", "0"}));
}

TEST(ParseSubcircuit, DefinitionAfterUseAndNestedDefinitions) {
  Netlist n = parse(
      "t\n"
      "X1 a 0 outer\n"
      ".subckt outer x y\n"
      ".subckt inner u v\n"
      "R1 u v 2\n"
      ".ends inner\n"
      "X5 x y inner\n"
      ".ends outer\n");
  EXPECT_EQ(names(n), (std::vector<std::string>{"x1.x5.r1"}));
  EXPECT_EQ(element(n, "x1.x5.r1").nodes, (std::vector<std::string>{"a", "0"}));
  // `inner` is local to `outer`
  EXPECT_EQ(test::diag("t\n.subckt outer x y\n.subckt inner u v\nR1 u v 2\n.ends\n.ends\nX1 a 0 inner\n"),
            "t.cir:7:8: error: subcircuit 'inner' is not defined\n"
            "X1 a 0 inner\n"
            "       ^~~~~");
}

TEST(ParseSubcircuit, ParametersDefaultsAndOverrides) {
  Netlist n = parse(
      "t\n"
      ".param scale=10\n"
      ".subckt rc in out params: r=1k c={1u*scale} tau={r*c}\n"
      "R1 in out {r}\n"
      "C1 out 0 {c}\n"
      "R2 out 0 {tau*1e6}\n"
      ".param local={r/10}\n"
      "R3 in 0 {local}\n"
      ".ends\n"
      "X1 a b rc\n"
      "X2 a b rc r=2k\n"
      "X3 a b rc params: r={scale*100} c=1n\n");
  EXPECT_EQ(element(n, "x1.r1").value, 1000);
  EXPECT_DOUBLE_EQ(element(n, "x1.c1").value, 1e-5);
  EXPECT_DOUBLE_EQ(element(n, "x1.r2").value, 1e4);
  EXPECT_EQ(element(n, "x1.r3").value, 100);
  EXPECT_EQ(element(n, "x2.r1").value, 2000);
  EXPECT_DOUBLE_EQ(element(n, "x2.r2").value, 2e4);  // tau follows the overridden r
  EXPECT_EQ(element(n, "x2.r3").value, 200);
  EXPECT_EQ(element(n, "x3.r1").value, 1000);
  EXPECT_EQ(element(n, "x3.c1").value, 1e-9);
  EXPECT_DOUBLE_EQ(element(n, "x3.r2").value, 1);
}

TEST(ParseSubcircuit, CouplingNamesAreScoped) {
  Netlist n = parse(
      "t\n"
      ".subckt xfmr p1 p2 s1 s2\n"
      "L1 p1 p2 1m\n"
      "L2 s1 s2 4m\n"
      "K1 L1 L2 0.95\n"
      ".ends\n"
      "X1 a 0 b 0 xfmr\n"
      "X2 c 0 d 0 xfmr\n"
      "K9 x1.l1 x2.l2 0.1\n");
  EXPECT_EQ(element(n, "x1.k1").coupled, (std::vector<std::string>{"x1.l1", "x1.l2"}));
  EXPECT_EQ(element(n, "x2.k1").coupled, (std::vector<std::string>{"x2.l1", "x2.l2"}));
  EXPECT_EQ(element(n, "k9").coupled, (std::vector<std::string>{"x1.l1", "x2.l2"}));
}

TEST(ParseSubcircuit, ModelsInsideASubcircuitAreLocal) {
  Netlist n = parse(
      "t\n"
      ".model dm D(von=0.7)\n"
      ".subckt clamp a k params: v=0.3\n"
      "D1 a k dm\n"
      "D2 k a dlocal\n"
      ".model dlocal D(von={v})\n"
      ".ends\n"
      "X1 n1 0 clamp\n"
      "X2 n2 0 clamp v=0.5\n"
      "D3 n1 n2 dm\n");
  EXPECT_EQ(element(n, "x1.d1").model, "dm");
  EXPECT_EQ(element(n, "x1.d2").model, "x1.dlocal");
  EXPECT_EQ(element(n, "x2.d2").model, "x2.dlocal");
  EXPECT_EQ(element(n, "d3").model, "dm");
  EXPECT_EQ(*n.diode_models.at("x1.dlocal").von, 0.3);
  EXPECT_EQ(*n.diode_models.at("x2.dlocal").von, 0.5);
  EXPECT_EQ(n.diode_models.at("x2.dlocal").name, "x2.dlocal");
}

TEST(ParseSubcircuit, UnusedDefinitionsAreNotExpanded) {
  Netlist n = parse("t\n.subckt unused a b\nR1 a b 1\n.ends\nR1 x 0 1\n");
  EXPECT_EQ(names(n), (std::vector<std::string>{"r1"}));
}

TEST(ParseSubcircuit, ProbesAndIcReachIntoInstances) {
  Netlist n = parse(
      "t\n.subckt s a\nR1 a m 1\nC1 m 0 1u\n.ends\nX1 in s\nV1 in 0 1\n"
      ".print tran v(x1.m) i(x1.r1)\n.ic v(x1.m)=0.5\n");
  ASSERT_EQ(n.probes.size(), 2u);
  EXPECT_EQ(n.probes[0].name(), "v(x1.m)");
  EXPECT_EQ(n.probes[1].name(), "i(x1.r1)");
  EXPECT_EQ(n.node_ics[0].node, "x1.m");
}

}  // namespace
}  // namespace lcs
