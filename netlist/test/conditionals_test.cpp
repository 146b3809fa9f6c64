// ngspice's `.if (expr)` / `.elseif (expr)` / `.else` / `.endif`, on `.param` values.
#include <gtest/gtest.h>

#include "netlist/netlist.h"
#include "netlist/test/parse_helpers.h"

namespace lcs {
namespace {

std::string chosen(int a, int b) {
  Netlist n = test::parse("t\n.param a=" + std::to_string(a) + " b=" + std::to_string(b) +
                          "\n"
                          ".if (a)\nI1 0 1 1m\nRI 1 0 1\n"
                          ".elseif (b)\nV1 1 0 2\n"
                          ".else\nV1 1 0 3\n"
                          ".endif\nR1 1 0 1k\n");
  std::string out;
  for (const Element& e : n.elements)
    out += e.name + (e.kind == ElementKind::VoltageSource ? "=" + std::to_string(int(e.waveform.dc)) : "") + " ";
  return out;
}

TEST(Conditionals, TakesTheFirstTrueBranch) {
  EXPECT_EQ(chosen(1, 0), "i1 ri r1 ");
  EXPECT_EQ(chosen(1, 1), "i1 ri r1 ");
  EXPECT_EQ(chosen(0, 1), "v1=2 r1 ");
  EXPECT_EQ(chosen(0, 0), "v1=3 r1 ");
}

TEST(Conditionals, NestedWithParamsDefinedInATakenBranch) {
  Netlist n = test::parse(
      "t\n.param outer=1\n"
      ".if (outer)\n  .param inner=0\n"
      "  .if (inner)\n    R1 a 0 1\n  .else\n    R2 a 0 2\n  .endif\n"
      ".else\n  .param inner=1\n  R3 a 0 3\n"
      "  .if (inner)\n    R4 a 0 4\n  .endif\n"
      ".endif\n"
      ".if (inner * 2 - 1 + 1)\nR5 a 0 5\n.endif\n");  // inner = 0 from the taken branch
  std::string names;
  for (const Element& e : n.elements) names += e.name + " ";
  EXPECT_EQ(names, "r2 ");
}

TEST(Conditionals, ComparisonConditions) {
  Netlist n = test::parse("t\n.param mode=2\n.if (mode == 1)\nR1 a 0 1\n.elseif (mode == 2 && 1 < 2)\nR2 a 0 2\n.endif\n");
  ASSERT_EQ(n.elements.size(), 1u);
  EXPECT_EQ(n.elements[0].name, "r2");
}

TEST(Conditionals, ErrorsAreLocated) {
  EXPECT_EQ(test::diag("t\nR1 a 0 1\n.else\n"), "t.cir:3:1: error: '.else' without '.if'\n.else\n^~~~~");
  EXPECT_EQ(test::diag("t\n.if (1)\nR1 a 0 1\n.else\n.elseif (1)\n.endif\n"),
            "t.cir:5:1: error: '.elseif' after '.else'\n.elseif (1)\n^~~~~~~");
  EXPECT_EQ(test::diag("t\nR1 a 0 1\n  .if (1)\nR2 a 0 1\n"),
            "t.cir:3:3: error: missing '.endif' for '.if'\n  .if (1)\n  ^~~");
  EXPECT_EQ(test::diag("t\n.param a=1\n.if (a + nosuch)\n.endif\n"),
            "t.cir:3:10: error: undefined parameter 'nosuch'\n.if (a + nosuch)\n         ^~~~~~");
  EXPECT_EQ(test::diag("t\n.if\n.endif\n"), "t.cir:2:4: error: missing condition after '.if'\n.if\n   ^");
}

}  // namespace
}  // namespace lcs
