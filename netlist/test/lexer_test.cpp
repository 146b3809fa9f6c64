// Title, comments, continuation lines, case, .end and .control: the card level of the reader.
#include "netlist/lexer.h"

#include <gtest/gtest.h>

#include "netlist/test/parse_helpers.h"

namespace lcs {
namespace {

using test::diag;
using test::element;
using test::parse;

TEST(ParseLexer, TokensKeepTheirPhysicalPositionAcrossContinuations) {
  std::vector<std::string> warnings;
  auto file = parse::make_source_file("f.cir", "title\nR1 a\n* a comment between\n\n+ b\n+   {2*k} ; tail\n");
  std::vector<parse::Card> cards = parse::split_cards(file, true, warnings);
  ASSERT_EQ(cards.size(), 1u);
  const parse::Card& c = cards[0];
  ASSERT_EQ(c.size(), 4u);
  EXPECT_EQ(c[0].lower, "r1");
  EXPECT_EQ(c[3].kind, parse::Token::Kind::Braced);
  EXPECT_EQ(c[3].text, "2*k");
  int want[4][2] = {{2, 1}, {2, 4}, {5, 3}, {6, 5}};
  for (int i = 0; i < 4; ++i) {
    SourceLocation loc = c.at(i);
    EXPECT_EQ(loc.line, want[i][0]) << i;
    EXPECT_EQ(loc.column, want[i][1]) << i;
    EXPECT_EQ(loc.file, "f.cir");
  }
  EXPECT_EQ(c.at(3).length, 5);
  EXPECT_EQ(c.at(3).line_text, "+   {2*k} ; tail");
}

TEST(ParseLexer, TokenKinds) {
  std::vector<std::string> warnings;
  auto file = parse::make_source_file("f.cir", "t\nV1 a 0 SIN(0, 1k) ic=\"x y\" 'a+b' {c}\n");
  std::vector<parse::Card> cards = parse::split_cards(file, true, warnings);
  ASSERT_EQ(cards.size(), 1u);
  using K = parse::Token::Kind;
  std::vector<K> kinds;
  std::vector<std::string> texts;
  for (const parse::Token& t : cards[0].tokens) {
    kinds.push_back(t.kind);
    texts.push_back(t.text);
  }
  EXPECT_EQ(kinds, (std::vector<K>{K::Word, K::Word, K::Word, K::Word, K::LParen, K::Word, K::Comma, K::Word,
                                   K::RParen, K::Word, K::Equals, K::Quoted, K::Quoted, K::Braced}));
  EXPECT_EQ(texts, (std::vector<std::string>{"V1", "a", "0", "SIN", "(", "0", ",", "1k", ")", "ic", "=", "x y",
                                             "a+b", "c"}));
}

TEST(ParseLexer, ErrorInsideAContinuationLinePointsAtItsColumn) {
  EXPECT_EQ(diag("t\nR1 a b\n+ {2 * undefined_p}\n"),
            "t.cir:3:8: error: undefined parameter 'undefined_p'\n"
            "+ {2 * undefined_p}\n"
            "       ^~~~~~~~~~~");
  EXPECT_EQ(diag("t\nL1 a\n+ a 1m\n"),
            "t.cir:3:3: error: l1 connects node 'a' to itself (the current of an inductor shorted by itself is not "
            "set by the circuit)\n"
            "+ a 1m\n"
            "  ^");
}

TEST(ParseLexer, TitleIsAlwaysTheFirstLine) {
  EXPECT_EQ(parse("R1 a 0 1k\nR2 a 0 1k\n").title, "R1 a 0 1k");
  Netlist n = parse("* My Circuit *\nR2 a 0 1k\n");
  EXPECT_EQ(n.title, "* My Circuit *");
  EXPECT_EQ(n.elements.size(), 1u);
  EXPECT_EQ(parse(".tran 1 2\n").title, ".tran 1 2");
  EXPECT_FALSE(parse(".tran 1 2\n").tran.has_value());
  EXPECT_EQ(parse("").title, "");
  EXPECT_EQ(parse("Title with CRLF\r\nR1 a 0 1\r\n").title, "Title with CRLF");
  EXPECT_EQ(parse("\xEF\xBB\xBFTitle after a byte order mark\nR1 a 0 1\n").title, "Title after a byte order mark");
}

TEST(ParseLexer, CommentsAndBlankLines) {
  Netlist n = parse(
      "title\n"
      "* full-line comment with R9 a b 1\n"
      "   * indented comment\n"
      "\n"
      "   \t\n"
      "R1 a 0 1k ; inline comment R2\n"
      "R2 a 0 2k $ dollar comment\n"
      "R3 n$1 0 3k\n"  // `$` not followed by a blank is part of a name
      "R4 a 0 4k;no space needed for semicolons\n"
      "R5 a 0 5k $comment: ngspice reads a word after a blank that starts with $ as one\n"
      "R6 $N_0001 $G_DPWR 6k $ PSpice's generated node names are not comments\n");
  ASSERT_EQ(n.elements.size(), 6u);
  EXPECT_EQ(element(n, "r5").value, 5e3);
  EXPECT_EQ(element(n, "r6").nodes, (std::vector<std::string>{"$n_0001", "$g_dpwr"}));
  EXPECT_EQ(element(n, "r1").value, 1e3);
  EXPECT_EQ(element(n, "r2").value, 2e3);
  EXPECT_EQ(element(n, "r3").nodes[0], "n$1");
  EXPECT_EQ(element(n, "r4").value, 4e3);
}

TEST(ParseLexer, CaseInsensitiveButLineTextKept) {
  Netlist n = parse("Title\nRLOAD OUT Gnd 1K\n");
  const Element& r = element(n, "rload");
  EXPECT_EQ(r.nodes, (std::vector<std::string>{"out", "0"}));
  EXPECT_EQ(r.loc.line_text, "RLOAD OUT Gnd 1K");
  EXPECT_EQ(r.loc.line, 2);
  EXPECT_EQ(r.loc.column, 1);
  EXPECT_EQ(r.loc.length, 5);
}

TEST(ParseLexer, EndStopsTheDeck) {
  Netlist n = parse("t\nR1 a 0 1\n.END\nR2 a 0 {unbalanced\n\x01\x02 junk\n");
  EXPECT_EQ(n.elements.size(), 1u);
  EXPECT_EQ(parse("t\nR1 a 0 1\n  .end extra words\nR2 b 0 1\n").elements.size(), 1u);
  // .ends and .endc are not .end
  EXPECT_EQ(parse("t\n.subckt s a\nR1 a 0 1\n.ends\nX1 n s\n").elements.size(), 1u);
}

TEST(ParseLexer, ControlBlocksAreTakenOutWithAWarning) {
  Netlist n = parse("t\nR1 a 0 1\n.control\nrun\nplot v(a) * junk {\n.endc\nR2 a 0 2\n");
  EXPECT_EQ(n.elements.size(), 2u);
  ASSERT_EQ(n.warnings.size(), 1u);
  EXPECT_EQ(n.warnings[0], "t.cir:3:1: warning: '.control' block is not run; its commands: 'run', 'plot'");
  EXPECT_EQ(diag("t\nR1 a 0 1\n  .control\nrun\n"),
            "t.cir:3:3: error: missing '.endc' for '.control'\n"
            "  .control\n"
            "  ^~~~~~~~");
}

TEST(ParseLexer, WarningLinesAreOneLine) {
  SourceLocation loc;
  loc.file = "a.cir";
  loc.line = 3;
  loc.column = 7;
  loc.line_text = "whatever";
  EXPECT_EQ(parse::warning_line(loc, "something"), "a.cir:3:7: warning: something");
}

TEST(ParseLexer, QuoteEscapesControlBytesAndCutsLongTokens) {
  EXPECT_EQ(parse::quote("r1"), "'r1'");
  EXPECT_EQ(parse::quote(std::string("a\x01" "b", 3)), "'a\\x01b'");
  EXPECT_EQ(parse::quote(std::string(50, 'x')), "'" + std::string(40, 'x') + "...'");
}

}  // namespace
}  // namespace lcs
