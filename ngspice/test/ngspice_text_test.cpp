// The bridge's text handling without ngspice: deck preparation and reading ngspice's messages.
// The message samples are verbatim ngspice 39 output (see ngspice/README.md).
#include <gtest/gtest.h>

#include "ngspice/ngspice_deck.h"
#include "ngspice/ngspice_messages.h"

namespace lcs {
namespace {

using ngspice_messages::Line;
using ngspice_messages::Stream;

std::vector<Line> lines(std::initializer_list<const char*> raw) {
  std::vector<Line> out;
  for (const char* r : raw) out.push_back(ngspice_messages::parse(r));
  return out;
}

TEST(NgspiceDeck, EndCardIsDetectedLikeNgspice) {
  EXPECT_TRUE(ngspice_deck::is_end_card(".end"));
  EXPECT_TRUE(ngspice_deck::is_end_card("  .END"));
  EXPECT_TRUE(ngspice_deck::is_end_card(".end  * trailing"));
  EXPECT_FALSE(ngspice_deck::is_end_card(".ends"));
  EXPECT_FALSE(ngspice_deck::is_end_card(".endc"));
  EXPECT_FALSE(ngspice_deck::is_end_card(".endl"));
  EXPECT_FALSE(ngspice_deck::is_end_card("* .end"));
  EXPECT_FALSE(ngspice_deck::is_end_card(""));
}

TEST(NgspiceDeck, AppendsMissingEndAndDropsWhatFollowsIt) {
  auto a = ngspice_deck::prepare({"t", "R1 a 0 1k"});
  ASSERT_TRUE(a.error.empty());
  EXPECT_EQ(a.lines, (std::vector<std::string>{"t", "R1 a 0 1k", ".end"}));

  auto b = ngspice_deck::prepare({"t", "R1 a 0 1k", ".END", "R2 b 0 1k", ".end"});
  ASSERT_TRUE(b.error.empty());
  EXPECT_EQ(b.lines, (std::vector<std::string>{"t", "R1 a 0 1k", ".END"}));
}

TEST(NgspiceDeck, SplitsMultiLineEntries) {
  auto d = ngspice_deck::prepare({"title\r\nR1 a 0 1k\n.tran 1u 1m\r\n.end\n"});
  ASSERT_TRUE(d.error.empty());
  // The trailing newline yields an empty line after .end, which is dropped with everything else.
  EXPECT_EQ(d.lines, (std::vector<std::string>{"title", "R1 a 0 1k", ".tran 1u 1m", ".end"}));
}

TEST(NgspiceDeck, BlankOrEndTitleIsReplaced) {
  EXPECT_EQ(ngspice_deck::prepare({"", "R1 a 0 1k", ".end"}).lines.front(), "untitled");
  EXPECT_EQ(ngspice_deck::prepare({"   ", "R1 a 0 1k", ".end"}).lines.front(), "untitled");
  auto d = ngspice_deck::prepare({".end", "R1 a 0 1k", ".end"});
  EXPECT_EQ(d.lines, (std::vector<std::string>{"untitled", "R1 a 0 1k", ".end"}));
}

TEST(NgspiceDeck, RejectsEmptyDecksAndControlBlocks) {
  EXPECT_FALSE(ngspice_deck::prepare({}).error.empty());
  EXPECT_FALSE(ngspice_deck::prepare({""}).error.empty());
  auto d = ngspice_deck::prepare({"t", "R1 a 0 1k", ".control", "quit", ".endc", ".end"});
  EXPECT_NE(d.error.find("line 3"), std::string::npos) << d.error;
  EXPECT_NE(d.error.find(".control"), std::string::npos) << d.error;
  EXPECT_TRUE(d.lines.empty());
  EXPECT_FALSE(ngspice_deck::prepare({"t", "  .ENDC", ".end"}).error.empty());
  // A comment that mentions .control is fine.
  EXPECT_TRUE(ngspice_deck::prepare({"t", "* no .control here", ".end"}).error.empty());
}

TEST(NgspiceMessages, ParseStripsStreamPrefixes) {
  Line out = ngspice_messages::parse("stdout Circuit: rc");
  EXPECT_EQ(out.stream, Stream::Out);
  EXPECT_EQ(out.text, "Circuit: rc");
  Line err = ngspice_messages::parse("stderr Error: circuit not parsed.\n");
  EXPECT_EQ(err.stream, Stream::Err);
  EXPECT_EQ(err.text, "Error: circuit not parsed.");
  Line progress = ngspice_messages::parse(" Reference value :  8.79083e-05\r");
  EXPECT_EQ(progress.stream, Stream::Other);
  EXPECT_EQ(progress.text, " Reference value :  8.79083e-05");
  EXPECT_EQ(ngspice_messages::parse("stdout ").text, "");
  EXPECT_EQ(ngspice_messages::parse("stdoutx").text, "stdoutx");
}

TEST(NgspiceMessages, LogKeepsHeadAndTail) {
  ngspice_messages::Log log(2, 3);
  for (int i = 0; i < 10; ++i) log.add({Stream::Out, std::to_string(i)});
  EXPECT_EQ(log.size(), 10u);
  EXPECT_EQ(log.texts(), (std::vector<std::string>{"0", "1", "[lcspice: 5 ngspice lines not kept]",
                                                   "7", "8", "9"}));
  auto recent = log.since(8);
  ASSERT_EQ(recent.size(), 2u);
  EXPECT_EQ(recent[0].text, "8");
  EXPECT_EQ(log.since(1).size(), 4u);  // "1" and the kept tail
  log.clear();
  EXPECT_EQ(log.size(), 0u);
  EXPECT_TRUE(log.texts().empty());
}

TEST(NgspiceMessages, LoadFailuresAsNgspicePrintsThem) {
  std::vector<std::string> evidence;
  EXPECT_TRUE(ngspice_messages::load_failed(
      lines({"stdout Note: No compatibility mode selected!",
             "stderr warning, can't find model 'nomodel' from line", "stderr d1 out 0 nomodel",
             "stdout Circuit: bad", "stderr Error on line 4 or its substitute:",
             "stderr d1 out 0 nomodel", "stderr could not find a valid modelname"}),
      evidence));
  ASSERT_FALSE(evidence.empty());
  EXPECT_EQ(evidence.back(), "could not find a valid modelname");

  evidence.clear();
  EXPECT_TRUE(ngspice_messages::load_failed(
      lines({"stderr Error: not enough parameters in line", "stderr foo bar baz",
             "stderr No circuit loaded!"}),
      evidence));
  EXPECT_TRUE(ngspice_messages::load_failed(
      lines({"stderr Error: Could not find include file /nonexistent/x.lib"}), evidence));

  evidence.clear();
  EXPECT_FALSE(ngspice_messages::load_failed(
      lines({"stdout Note: No compatibility mode selected!", "stdout Circuit: rc"}), evidence));
  EXPECT_TRUE(evidence.empty());
}

TEST(NgspiceMessages, DetachAnnouncements) {
  EXPECT_TRUE(ngspice_messages::announces_detach(
      lines({"stderr Please check your input netlist.",
             "stderr Error: ngspice.dll cannot recover and awaits to be detached"})));
  EXPECT_TRUE(ngspice_messages::announces_detach(
      lines({"stdout ngspice-39 done", "stdout ", "stdout Note: 'quit' asks for detaching ngspice.dll."})));
  EXPECT_FALSE(ngspice_messages::announces_detach(lines({"stdout Circuit: rc"})));
}

TEST(NgspiceMessages, RunVerdicts) {
  using ngspice_messages::RunVerdict;
  std::vector<std::string> evidence;
  EXPECT_EQ(ngspice_messages::classify_run(
                lines({"stdout Doing analysis at TEMP = 27.000000 and TNOM = 27.000000",
                       "stdout No. of Data Rows : 5022"}),
                evidence),
            RunVerdict::Completed);

  evidence.clear();
  EXPECT_EQ(ngspice_messages::classify_run(
                lines({"stderr Warning: singular matrix:  check node a",
                       "stderr doAnalyses: TRAN:  Timestep too small; time = 1e-06, timestep = "
                       "2.5e-19: trouble with dd-instance d1",
                       "stderr run simulation(s) aborted"}),
                evidence),
            RunVerdict::Convergence);
  ASSERT_FALSE(evidence.empty());
  EXPECT_NE(evidence.front().find("Timestep too small"), std::string::npos);

  evidence.clear();
  EXPECT_EQ(ngspice_messages::classify_run(
                lines({"stderr Error: Transient op failed, timestep too small"}), evidence),
            RunVerdict::Convergence);
  EXPECT_EQ(ngspice_messages::classify_run(lines({"stderr Error: circuit not parsed."}), evidence),
            RunVerdict::NotLoaded);
  EXPECT_EQ(ngspice_messages::classify_run(
                lines({"stderr Error: there aren't any circuits loaded."}), evidence),
            RunVerdict::NotLoaded);
  EXPECT_EQ(ngspice_messages::classify_run(lines({"stderr doAnalyses: pause requested",
                                                  "stderr run simulation interrupted"}),
                                           evidence),
            RunVerdict::Interrupted);
  // gmin/source stepping failures alone are warnings: ngspice may still find the op point.
  EXPECT_EQ(ngspice_messages::classify_run(lines({"stderr Warning: Dynamic gmin stepping failed",
                                                  "stderr Warning: source stepping failed",
                                                  "stdout Note: Transient op finished successfully"}),
                                           evidence),
            RunVerdict::Completed);
}

}  // namespace
}  // namespace lcs
