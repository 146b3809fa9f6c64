// `.control` ... `.endc`: its `tran` command runs when the deck has no `.tran`; the other commands
// are named in one warning; a deck with no transient analysis at all is refused (SPEC §2).
#include <gtest/gtest.h>

#include <fstream>

#include "netlist/netlist.h"
#include "netlist/test/parse_helpers.h"

namespace lcs {
namespace {

ReadOptions transient_required() {
  ReadOptions o;
  o.require_transient = true;
  return o;
}

std::string run_diag(const std::string& text) {
  try {
    parse_netlist_string(text, "t.cir", transient_required());
  } catch (const NetlistError& e) {
    return e.formatted();
  }
  return "<no error>";
}

TEST(ControlBlock, TranCommandRunsWhenTheDeckHasNoTranCard) {
  Netlist n = test::parse("t\n.param h=2u\nR1 a 0 1\nV1 a 0 1\n.control\nset x=1\nrun\n  tran {h} 1m 0.5m uic ; c\n"
                          "plot v(a)\nplot v(a)\n.endc\n");
  ASSERT_TRUE(n.tran);
  EXPECT_EQ(n.tran->tstep, 2e-6);
  EXPECT_EQ(n.tran->tstop, 1e-3);
  EXPECT_EQ(n.tran->tstart, 0.5e-3);
  EXPECT_TRUE(n.tran->uic);
  EXPECT_EQ(n.tran->loc.line, 8);
  EXPECT_EQ(n.tran->loc.column, 3);
  ASSERT_EQ(n.warnings.size(), 1u);
  EXPECT_EQ(n.warnings[0], "t.cir:5:1: warning: '.control' block: its 'tran' command is run; ignored: 'set', 'run', 'plot'");
}

TEST(ControlBlock, TranCardWinsOverTheControlBlock) {
  Netlist n = test::parse("t\nR1 a 0 1\n.tran 1u 2m\n.control\ntran 5u 1m\nrun\n.endc\n");
  ASSERT_TRUE(n.tran);
  EXPECT_EQ(n.tran->tstep, 1e-6);
  EXPECT_EQ(n.tran->tstop, 2e-3);
  ASSERT_EQ(n.warnings.size(), 1u);
  EXPECT_EQ(n.warnings[0], "t.cir:4:1: warning: '.control' block is not run (the deck's '.tran' card is); its commands: 'tran', 'run'");
}

TEST(ControlBlock, BadTranCommandIsLocatedInTheBlock) {
  EXPECT_EQ(test::diag("t\nR1 a 0 1\n.control\n tran 1u\n.endc\n"),
            "t.cir:4:9: error: '.tran' needs TSTEP and TSTOP\n tran 1u\n        ^");
}

TEST(ControlBlock, DeckWithoutTransientIsRefusedWhereItAsksForAnotherAnalysis) {
  // Refused at the `dc` command, before the model card's unknown parameter is looked at.
  EXPECT_EQ(run_diag("t\nD1 a 0 dx\n.model dx d(roff=1)\nV1 a 0 1\n.control\nset x\ndc v1 0 1 0.1\nplot i(v1)\n.endc\n"),
            "t.cir:7:1: error: the deck has no transient analysis (no '.tran' card and no 'tran' command in "
            "'.control'; lcspice runs transient analyses only): the '.control' block runs 'dc'\n"
            "dc v1 0 1 0.1\n^~");
  EXPECT_EQ(run_diag("t\nR1 a 0 1\n.op\n"),
            "t.cir:3:1: error: the deck has no transient analysis (no '.tran' card and no 'tran' command in "
            "'.control'; lcspice runs transient analyses only): it asks for '.op'\n.op\n^~~");
  // Without the requirement (op, analyze) the deck reads; with no analysis at all, the caller says so.
  EXPECT_NO_THROW(test::parse("t\nR1 a 0 1\n.op\n"));
  EXPECT_EQ(run_diag("t\nR1 a 0 1\n"), "<no error>");
}

TEST(ControlBlock, RealDcOnlyDecksAreRefusedForTheirAnalysisNotTheirModels) {
  const std::string dir = std::string(LCSPICE_REALWORLD_DIR) + "/ngspice/examples";
  if (!std::ifstream(dir + "/soa/diode-soa-simple.cir")) GTEST_SKIP() << "real-world decks not found in " << dir;
  for (const char* deck : {"/xspice/various/simple-diode.cir", "/soa/diode-soa-simple.cir"}) {
    try {
      parse_netlist_file(dir + deck, transient_required());
      ADD_FAILURE() << deck << " was accepted";
    } catch (const NetlistError& e) {
      EXPECT_NE(e.message().find("no transient analysis"), std::string::npos) << e.formatted();
      EXPECT_NE(e.message().find("runs 'dc'"), std::string::npos) << e.formatted();
      EXPECT_EQ(e.location().line_text.substr(0, 3), "dc ") << e.formatted();
    }
  }
}

}  // namespace
}  // namespace lcs
