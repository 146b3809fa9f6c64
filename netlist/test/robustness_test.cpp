// Bad input never crashes or hangs: junk, unbalanced delimiters, runaway continuations, deep
// nesting, exponential subcircuit expansion. Every failure is a NetlistError.
#include <chrono>
#include <random>
#include <string>

#include <filesystem>
#include <fstream>
#include <unistd.h>
#include <gtest/gtest.h>

#include "netlist/netlist.h"
#include "netlist/test/parse_helpers.h"

namespace lcs {
namespace {

// Parses; returns "" on success, the message of the NetlistError otherwise. Any other exception
// fails the test.
std::string outcome(const std::string& text) {
  try {
    parse_netlist_string(text, "fuzz.cir");
    return "";
  } catch (const NetlistError& e) {
    EXPECT_FALSE(e.message().empty());
    EXPECT_GT(e.location().line, 0) << e.formatted();
    return e.message();
  }
}

TEST(ParseRobustness, EmptyAndTrivialInputs) {
  for (const char* text : {"", "\n", "\n\n\n", "title only", "t\n* only comments\n; and this\n", " \t \r\n",
                           "t\n.end\n", "t\n\n\n.END"})
    EXPECT_EQ(outcome(text), "") << text;
  EXPECT_EQ(outcome(std::string("t\n\0\n", 4)), "unknown element type '\\x00'");
  EXPECT_EQ(outcome("t\n+\n"), "continuation line without a card to continue");
}

TEST(ParseRobustness, UnbalancedDelimiters) {
  EXPECT_EQ(outcome("t\nV1 a 0 SIN((0 1 2\n"), "missing ')'");
  EXPECT_EQ(outcome("t\nV1 a 0 SIN(0 1 2))\n"), "unexpected extra token ')'");
  EXPECT_EQ(outcome("t\nR1 a 0 {{1}\n"), "missing '}'");  // braces nest
  EXPECT_EQ(outcome("t\nR1 a 0 {{1}}\n"), "unexpected '{' in expression");
  EXPECT_EQ(outcome("t\nR1 a 0 {1}}\n"), "unmatched '}'");
  EXPECT_EQ(outcome("t\nR1 a 0 )\n"), "expected a number, got ')'");
  EXPECT_EQ(outcome("t\n.model d D((von=1))\n"), "unexpected extra token ')'");
  EXPECT_EQ(outcome("t\n.param a=((1)\n"), "missing ')'");
  EXPECT_EQ(outcome("t\n.print tran v(a\n"), "missing ')'");
  EXPECT_EQ(outcome("t\n.include 'x\n"), "missing closing quote");
  EXPECT_EQ(outcome("t\nR1 a 0 '1+2\n"), "missing closing quote");
}

TEST(ParseRobustness, RunawayContinuationIsFastAndReportsTheFirstExtraToken) {
  std::string text = "t\nR1 a b 1k\n";
  for (int i = 0; i < 200000; ++i) text += "+ x\n";
  auto start = std::chrono::steady_clock::now();
  EXPECT_EQ(test::diag(text), "t.cir:3:3: error: unexpected extra token 'x'\n+ x\n  ^");
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(10));
}

TEST(ParseRobustness, LongLinesAndManyElements) {
  std::string text = "t\n";
  for (int i = 0; i < 200000; ++i) text += "R" + std::to_string(i) + " n" + std::to_string(i) + " n" + std::to_string(i + 1) + " 1k\n";
  Netlist n = parse_netlist_string(text, "big.cir");
  EXPECT_EQ(n.elements.size(), 200000u);  // the limit itself is admitted
  EXPECT_EQ(outcome(text + "R200000 n200000 n200001 1k\n"),
            "netlist too large (more than 200000 elements after subcircuit expansion)");
  std::string line = "t\nR1 a 0 1 " + std::string(1 << 20, 'x') + "\n";
  EXPECT_EQ(outcome(line), "unexpected extra token '" + std::string(40, 'x') + "...'");
}

TEST(ParseRobustness, ExponentialSubcircuitExpansionIsCapped) {
  // Ten levels of ten instances each would be 10^10 resistors.
  std::string text = "t\n.subckt s0 a\nR1 a 0 1\n.ends\n";
  for (int k = 1; k <= 10; ++k) {
    text += ".subckt s" + std::to_string(k) + " a\n";
    for (int j = 0; j < 10; ++j) text += "X" + std::to_string(j) + " a s" + std::to_string(k - 1) + "\n";
    text += ".ends\n";
  }
  text += "Xtop n s10\n";
  auto start = std::chrono::steady_clock::now();
  EXPECT_EQ(outcome(text), "netlist too large (more than 200000 elements after subcircuit expansion)");
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(20));
}

// Issue 9, defect 6: five files of 40 `.include` lines of the next would open 40^4 files.
TEST(ParseRobustness, IncludesThatRepeatEachOtherAreBounded) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("lcspice-inc-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  for (int level = 0; level < 5; ++level) {
    std::ofstream f(dir / ("l" + std::to_string(level) + ".inc"));
    if (level == 4) {
      f << "R1 a 0 1\n";
      continue;
    }
    for (int j = 0; j < 40; ++j) f << ".include l" << level + 1 << ".inc\n";
  }
  std::ofstream(dir / "top.cir") << "t\n.include l0.inc\n.end\n";
  auto start = std::chrono::steady_clock::now();
  try {
    parse_netlist_file((dir / "top.cir").string());
    ADD_FAILURE() << "parsed";
  } catch (const NetlistError& e) {
    EXPECT_EQ(e.message(), "more than 10000 .include files read for one netlist (includes that repeat each other?)");
  }
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(20));
  fs::remove_all(dir);
}

TEST(ParseRobustness, DeepNesting) {
  // A chain of 300 subcircuits, each instantiating the next.
  std::string chain = "t\n";
  for (int k = 0; k < 300; ++k)
    chain += ".subckt c" + std::to_string(k) + " a\nX1 a c" + std::to_string(k + 1) + "\n.ends\n";
  chain += ".subckt c300 a\nR1 a 0 1\n.ends\nX1 n c0\n";
  EXPECT_EQ(outcome(chain), "subcircuit instances nested too deeply");
  // 1000 nested definitions.
  std::string nested = "t\n";
  for (int k = 0; k < 1000; ++k) nested += ".subckt d" + std::to_string(k) + " a\n";
  for (int k = 0; k < 1000; ++k) nested += ".ends\n";
  EXPECT_EQ(outcome(nested), "subcircuit definitions nested too deeply");
  // Parameters defined in terms of later ones, 10000 deep.
  std::string params = "t\n";
  for (int k = 0; k < 10000; ++k) params += ".param p" + std::to_string(k) + "={p" + std::to_string(k + 1) + "+1}\n";
  params += ".param p10000=0\nR1 a 0 {p0+1}\n";
  EXPECT_EQ(outcome(params), "parameters nested too deeply");
  // The same chain the other way round is evaluated in order and is fine.
  std::string forward = "t\n.param p0=1\n";
  for (int k = 1; k <= 10000; ++k) forward += ".param p" + std::to_string(k) + "={p" + std::to_string(k - 1) + "+1}\n";
  forward += "R1 a 0 {p10000}\n";
  Netlist n = parse_netlist_string(forward, "f.cir");
  EXPECT_EQ(n.elements[0].value, 10001);
}

TEST(ParseRobustness, IncludeOfItself) {
  EXPECT_EQ(outcome("t\n.include fuzz.cir\n"), "include cycle: 'fuzz.cir' is already being included");
}

// Random bytes, and random sequences of SPICE-like fragments that reach deeper into the parser.
TEST(ParseRobustness, RandomInputOnlyEverThrowsNetlistError) {
  std::mt19937 rng(12345);
  const std::vector<std::string> fragments = {
      "R1", "L1", "C1", "K1", "V1", "I1", "D1", "X1", "Q1", "T1", "O1", "a", "b", "0", "gnd", "1k", "-1", "{",
      "}", "(", ")", "=", ",", "'", "\"", "{a*2}", "{1/0}", "SIN(", "PULSE", "PWL", "DC", "AC", "IC=", ".model",
      "D(", "von=", ".subckt", ".ends", ".param", "a=", ".tran", "1u", "1m", "uic", ".ic", "v(a)", ".print",
      "tran", "i(r1)", ".save", "all", ".options", ".include", ".control", ".endc", ".end", "\n", "\n+", "\n*",
      ";", "$ ", "\t", " ", "params:", "s", "dm", "1e999", "x1.r1", "\x01", "\xff", "\r\n"};
  int errors = 0, successes = 0;
  for (int iter = 0; iter < 20000; ++iter) {
    std::string text = "fuzz\n";
    int n = std::uniform_int_distribution<int>(0, 60)(rng);
    if (iter % 3 == 0) {
      for (int i = 0; i < n * 4; ++i) text += static_cast<char>(std::uniform_int_distribution<int>(0, 255)(rng));
    } else {
      for (int i = 0; i < n; ++i) {
        text += fragments[std::uniform_int_distribution<std::size_t>(0, fragments.size() - 1)(rng)];
        text += ' ';
      }
    }
    (outcome(text).empty() ? successes : errors)++;
  }
  EXPECT_GT(errors, 0);
  EXPECT_GT(successes, 0);
}

}  // namespace
}  // namespace lcs
