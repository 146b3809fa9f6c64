// SPICE number syntax: scale suffixes and unit letters.
#include "netlist/number.h"

#include <gtest/gtest.h>

namespace lcs::parse {
namespace {

double num(const char* text) {
  std::optional<double> v = parse_number(text);
  EXPECT_TRUE(v.has_value()) << text;
  return v.value_or(-12345.0);
}

TEST(ParseNumber, PlainNumbers) {
  EXPECT_EQ(num("1"), 1.0);
  EXPECT_EQ(num("1.5"), 1.5);
  EXPECT_EQ(num("-2.5e-3"), -2.5e-3);
  EXPECT_EQ(num("+3"), 3.0);
  EXPECT_EQ(num(".5"), 0.5);
  EXPECT_EQ(num("5."), 5.0);
  EXPECT_EQ(num("1e-3"), 1e-3);
  EXPECT_EQ(num("1E3"), 1000.0);
  EXPECT_EQ(num("0"), 0.0);
}

TEST(ParseNumber, SuffixTable) {
  EXPECT_EQ(num("1t"), 1e12);
  EXPECT_EQ(num("1g"), 1e9);
  EXPECT_EQ(num("1meg"), 1e6);
  EXPECT_EQ(num("1MEG"), 1e6);
  EXPECT_EQ(num("1k"), 1e3);
  EXPECT_EQ(num("1m"), 1e-3);
  EXPECT_EQ(num("1M"), 1e-3);  // SPICE: M is milli, not mega
  EXPECT_EQ(num("1u"), 1e-6);
  EXPECT_EQ(num("1n"), 1e-9);
  EXPECT_EQ(num("1p"), 1e-12);
  EXPECT_EQ(num("1f"), 1e-15);
  EXPECT_EQ(num("1mil"), 25.4e-6);
  EXPECT_EQ(num("2mil"), 50.8e-6);
}

TEST(ParseNumber, SuffixesAreExactDecimals) {
  EXPECT_EQ(num("10u"), 1e-5);
  EXPECT_EQ(num("4.7k"), 4700.0);
  EXPECT_EQ(num("2.2e3k"), 2.2e6);
  EXPECT_EQ(num("100n"), 1e-7);
  EXPECT_EQ(num("0.1u"), 1e-7);
}

TEST(ParseNumber, MicroSignIsMicro) {  // LTspice writes 470µ (micro sign) or 470μ (Greek mu)
  EXPECT_EQ(num("470\xC2\xB5"), 470e-6);
  EXPECT_EQ(num("470\xCE\xBC"), 470e-6);
  EXPECT_EQ(num("2.2\xC2\xB5" "F"), 2.2e-6);
  EXPECT_FALSE(parse_number("470\xC2").has_value());  // half a micro sign is no number
}

TEST(ParseNumber, UnitLettersAreIgnored) {
  EXPECT_EQ(num("10uF"), 1e-5);
  EXPECT_EQ(num("1kohm"), 1000.0);
  EXPECT_EQ(num("1KOhm"), 1000.0);
  EXPECT_EQ(num("5V"), 5.0);
  EXPECT_EQ(num("2A"), 2.0);
  EXPECT_EQ(num("100Hz"), 100.0);
  EXPECT_EQ(num("3Meg"), 3e6);
  EXPECT_EQ(num("4megohm"), 4e6);
  EXPECT_EQ(num("1mH"), 1e-3);
  EXPECT_EQ(num("1F"), 1e-15);  // the classic: F is femto, not farad
  EXPECT_EQ(num("1e"), 1.0);    // an e without digits is a unit letter
}

TEST(ParseNumber, Malformed) {
  for (const char* bad : {"", "x", "1x2", "1k5", "--1", "+-1", "1.2.3", "e5", ".", "-", "1 2", "1e999",
                          "1e+", "1_000", "0x10", "1,5", "k1", "inf", "nan"})
    EXPECT_FALSE(parse_number(bad).has_value()) << "'" << bad << "'";
}

TEST(ParseNumberScan, StopsAfterTheLetters) {
  std::string s = "2.5kohm*3";
  std::size_t i = 0;
  double v = 0;
  ASSERT_TRUE(scan_number(s, i, v));
  EXPECT_EQ(v, 2500.0);
  EXPECT_EQ(i, 7u);
  i = 8;
  ASSERT_TRUE(scan_number(s, i, v));
  EXPECT_EQ(v, 3.0);
  i = 0;
  std::string t = "abc";
  EXPECT_FALSE(scan_number(t, i, v));
  EXPECT_EQ(i, 0u);
}

}  // namespace
}  // namespace lcs::parse
