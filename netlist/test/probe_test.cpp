// parse_probe: the three probe forms, canonical names, errors with columns.
#include <gtest/gtest.h>

#include "netlist/netlist.h"

namespace lcs {
namespace {

SourceLocation at(int line, int column) {
  SourceLocation loc;
  loc.file = "p.cir";
  loc.line = line;
  loc.column = column;
  loc.line_text = ".print tran   v(out)   bogus";
  return loc;
}

TEST(ParseProbe, Forms) {
  Probe p = parse_probe("v(out)", at(1, 1));
  EXPECT_EQ(p.kind, Probe::Kind::NodeVoltage);
  EXPECT_EQ(p.a, "out");
  EXPECT_EQ(p.name(), "v(out)");
  p = parse_probe("V(In, OUT)", at(1, 1));
  EXPECT_EQ(p.kind, Probe::Kind::NodePairVoltage);
  EXPECT_EQ(p.a, "in");
  EXPECT_EQ(p.b, "out");
  EXPECT_EQ(p.name(), "v(in,out)");
  p = parse_probe("I(D1)", at(1, 1));
  EXPECT_EQ(p.kind, Probe::Kind::ElementCurrent);
  EXPECT_EQ(p.a, "d1");
  EXPECT_EQ(p.name(), "i(d1)");
  EXPECT_EQ(parse_probe(" v ( x1.mid ) ", at(1, 1)).name(), "v(x1.mid)");
  EXPECT_EQ(parse_probe("v(gnd)", at(1, 1)).name(), "v(0)");
  EXPECT_EQ(parse_probe("v(a,GND)", at(1, 1)).name(), "v(a,0)");
}

TEST(ParseProbe, FromTheCommandLineHasNoLocation) {
  Probe p = parse_probe("i(l1)", SourceLocation());
  EXPECT_EQ(p.name(), "i(l1)");
  try {
    parse_probe("x(l1)", SourceLocation());
    FAIL();
  } catch (const NetlistError& e) {
    EXPECT_EQ(e.formatted(), "error: invalid probe 'x(l1)': expected v(node), v(node1,node2), i(element), ic/ib/ie(transistor) or i2(line)");
  }
}

TEST(ParseProbe, TransistorTerminalCurrents) {
  for (char t : {'c', 'b', 'e'}) {
    const Probe p = parse_probe(std::string("I") + t + " ( Q1 )", at(1, 1));
    EXPECT_EQ(p.kind, Probe::Kind::TerminalCurrent);
    EXPECT_EQ(p.a, "q1");
    EXPECT_EQ(p.terminal, t);
    EXPECT_EQ(p.name(), std::string("i") + t + "(q1)");
  }
}

TEST(ParseProbe, Errors) {
  for (const char* bad : {"", "v", "v()", "v(a", "va)", "v(a,b,c)", "i(a,b)", "x(a)", "vm(a)", "v(a)b", "ix(q1)", "ic(q1,q2)", "ic()",
                          "v(a b)", "@r1[i]", "v(,a)", "v(a,)", "all"}) {
    EXPECT_THROW(parse_probe(bad, at(1, 1)), NetlistError) << bad;
  }
}

TEST(ParseProbe, ErrorColumnSkipsLeadingBlanks) {
  try {
    parse_probe("  bogus", at(1, 22));
    FAIL();
  } catch (const NetlistError& e) {
    EXPECT_EQ(e.location().column, 24);
    EXPECT_EQ(e.location().length, 5);
    EXPECT_EQ(e.formatted(),
              "p.cir:1:24: error: invalid probe 'bogus': expected v(node), v(node1,node2), i(element), ic/ib/ie(transistor) or i2(line)\n"
              ".print tran   v(out)   bogus\n"
              "                       ^~~~~");
  }
}

}  // namespace
}  // namespace lcs
