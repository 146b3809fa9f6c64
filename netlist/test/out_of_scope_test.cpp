// What lcspice does not simulate: unused models of such types are skipped with a note; elements
// that need them are refused with the reason, at the card.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "netlist/netlist.h"
#include "netlist/test/parse_helpers.h"

namespace lcs {
namespace {

TEST(OutOfScope, UnusedModelsOfOtherTypesAreSkippedWithANote) {
  Netlist n = test::parse(
      "t\nR1 a 0 1\n.MODEL mn NMOS VTO=0.8 KP=48U\n.model m2 numd level=1\n+ options defa=1p\n"
      ".subckt s p\n.model c1 lcouple(num_turns=120)\nR1 p 0 1\n.ends\nX1 a s\nX2 a s\n");
  ASSERT_EQ(n.warnings.size(), 3u);
  EXPECT_EQ(n.warnings[0], "t.cir:3:11: warning: model 'mn' (MOSFET) is not simulated by lcspice; no element uses it: skipped");
  EXPECT_EQ(n.warnings[1],
            "t.cir:4:11: warning: model 'm2' (CIDER numerical device) is not simulated by lcspice; no element uses it: skipped");
  // One note for a model in a subcircuit however many times it is instantiated.
  EXPECT_EQ(n.warnings[2],
            "t.cir:7:11: warning: model 'x1.c1' (XSPICE code model) is not simulated by lcspice; no element uses it: skipped");
  EXPECT_EQ(n.elements.size(), 3u);
  // A type nobody knows is still an error.
  EXPECT_EQ(test::diag("t\n.model q1 nosuchtype\n"),
            "t.cir:2:11: error: unsupported model type 'nosuchtype'\n.model q1 nosuchtype\n          ^~~~~~~~~~");
}

TEST(OutOfScope, ElementsThatNeedThemAreRefusedWithTheReason) {
  EXPECT_EQ(test::diag("t\nR1 a 0 1\nm5 0 168 2 0 mn0p9 w=18u l=0.9u\n.model mn0p9 nmos vto=0.8 foo=\n"),
            "t.cir:3:1: error: MOSFETs are outside lcspice's scope (ideal diodes and bipolar transistors)\n"
            "m5 0 168 2 0 mn0p9 w=18u l=0.9u\n^~");
  EXPECT_EQ(test::diag("t\nA1 a b amod\n"),
            "t.cir:2:1: error: XSPICE code-model instances ('A' cards) are outside lcspice's scope (ideal diodes and "
            "bipolar transistors)\nA1 a b amod\n^~");
  EXPECT_EQ(test::diag("t\nB1 a 0 V=v(b)*2\n"),
            "t.cir:2:1: error: behavioural sources ('B' cards) are outside lcspice's scope (ideal diodes and "
            "bipolar transistors)\nB1 a 0 V=v(b)*2\n^~");
  // CIDER numerical diode: refused at the model name.
  EXPECT_EQ(test::diag("t\nD1 a 0 M_PN AREA=100\n.MODEL M_PN NUMD LEVEL=1\n"),
            "t.cir:2:8: error: CIDER numerical devices (model type numd) are outside lcspice's scope (ideal "
            "diodes and bipolar transistors)\nD1 a 0 M_PN AREA=100\n       ^~~~");
  EXPECT_EQ(test::diag("t\nDth1 1 0 tj dmod1 thermal\n.model dmod1 d(rth0=1)\n"),
            "t.cir:2:19: error: thermal diodes (self-heating, with a thermal node) are outside lcspice's scope "
            "(ideal diodes and bipolar transistors)\nDth1 1 0 tj dmod1 thermal\n                  ^~~~~~~");
}

TEST(OutOfScope, ExpressionsOfNodeVoltagesAreRefusedBeforeTheParametersAround) {
  // Nested braces read as one expression; the parameter the evaluator does not know (IF) is not
  // what is reported: the behavioural source is.
  EXPECT_EQ(test::diag("t\n.param td = {IF((d < 1e-9), 1e-9, d)}\n"
                       "EOUT OUT 0 VALUE= { IF ( (V(IN1+,IN1-) > {VTH}),\n+ VL + R*I(EOUT), VH ) }\n"),
            "t.cir:3:12: error: behavioural sources (VALUE=) are outside lcspice's scope (ideal diodes and bipolar "
            "transistors)\nEOUT OUT 0 VALUE= { IF ( (V(IN1+,IN1-) > {VTH}),\n           ^~~~~");
  EXPECT_EQ(test::diag("t\nR1 a 0 {1k + v(a)}\n"),
            "t.cir:2:8: error: expressions of node voltages or branch currents (behavioural sources) are outside "
            "lcspice's scope (ideal diodes and bipolar transistors)\nR1 a 0 {1k + v(a)}\n       ^~~~~~~~~~~");
}

// The TLC555 model the 555 deck includes is made of MOSFETs and behavioural sources (with nested
// braces); the first of them in deck order is what the refusal names, before the library's
// parameters (one uses VT, which nothing defines).
TEST(OutOfScope, RealDeckTlc555IsRefusedForItsFirstMosfet) {
  const std::string dir = std::string(LCSPICE_REALWORLD_DIR) + "/ngspice/examples/p-to-n-examples";
  if (!std::ifstream(dir + "/555-timer-2.cir")) GTEST_SKIP() << "real-world decks not found in " << dir;
  try {
    parse_netlist_file(dir + "/555-timer-2.cir");
    FAIL() << "accepted";
  } catch (const NetlistError& e) {
    EXPECT_EQ(e.message(), "MOSFETs are outside lcspice's scope (ideal diodes and bipolar transistors)");
    EXPECT_EQ(e.location().file, (std::filesystem::path(dir) / "TLC555.LIB").lexically_normal().string());
    EXPECT_EQ(e.location().line, 111);
    EXPECT_EQ(e.location().column, 1);
  }
}

}  // namespace
}  // namespace lcs
