// A transient that starts at an unstable equilibrium (unstable_start.h): the symmetric astable
// multivibrator's operating point has both transistors saturated, and its mode there grows at
// about 2e10/s. Before: the event method overflowed exp(M h) to inf at the first step (inf times a
// zero deviation: "numerical failure at t = 1e-06 s: v(1) is not a finite number"), and nothing
// told the user that where the circuit leaves that point is an accident of rounding.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/cli_support.h"

namespace lcs::cli_testing {
namespace {

// The junction lines are given (no refit), so every method integrates the same LCS.
const std::string kAstable =
    "symmetric astable multivibrator\n"
    "VCC 1 0 DC 5\n"
    "RC1 1 c1 1k\nRC2 1 c2 1k\nRB1 1 b1 47k\nRB2 1 b2 47k\n"
    "C1 c1 b2 10n\nC2 c2 b1 10n\n"
    "Q1 c1 b1 0 QN\nQ2 c2 b2 0 QN\n"
    ".model QN NPN(BF=300 CJE=10p VONE=0.68 RONE=5 VONC=0.57 RONC=170)\n"
    ".tran 1u 3m\n";

const char* const kWarning =
    "lcspice: warning: the operating point is an unstable equilibrium: in its mode (conducting: q1:be, q1:bc, "
    "q2:be, q2:bc) a deviation grows at ";

// The times v(c1) rises through 2.5 V (linear interpolation between rows).
std::vector<double> rising_edges(const Csv& csv) {
  const std::vector<double> t = column(csv, "time"), v = column(csv, "v(c1)");
  std::vector<double> edges;
  for (size_t k = 1; k < t.size(); ++k)
    if (v[k - 1] < 2.5 && v[k] >= 2.5) edges.push_back(t[k - 1] + (2.5 - v[k - 1]) / (v[k] - v[k - 1]) * (t[k] - t[k - 1]));
  return edges;
}

TEST(UnstableStart, SymmetricAstableIsWarnedAboutAndOscillates) {
  const fs::path deck = write_deck("unstable_", "astable", kAstable);
  const fs::path dir = scratch_dir("unstable_astable_run");
  const Result r = run_lcspice("run '" + deck.string() + "' -o '" + (dir / "out.csv").string() + "'", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find(kWarning), std::string::npos) << r.err;
  const Csv csv = parse_csv(read_file(dir / "out.csv"));
  const std::vector<double> v = column(csv, "v(c1)");
  EXPECT_GT(*std::max_element(v.begin(), v.end()) - *std::min_element(v.begin(), v.end()), 4.5);
  // The period is the circuit's, whatever rounding chose for the phase: the event method's
  // against radau5 at a step of 0.1 µs (order 5; its own error is far below the 1e-3 asked).
  const std::vector<double> exact = rising_edges(csv), fine = rising_edges(run_csv(deck, "radau5", "--step 1e-7"));
  ASSERT_GE(exact.size(), 3u);
  ASSERT_GE(fine.size(), 3u);
  const double period = exact.back() - exact[exact.size() - 2], reference = fine.back() - fine[fine.size() - 2];
  EXPECT_NEAR(period / reference, 1.0, 1e-3) << period << " against " << reference;
  // RB C ln((2 VCC - VONE - Vsat)/(VCC - VONE)) per half period, Vsat about 0.1 V: 0.70 ms.
  EXPECT_NEAR(period, 2 * 47e3 * 10e-9 * std::log((10 - 0.68 - 0.1) / (5 - 0.68)), 0.05 * period);
}

TEST(UnstableStart, NoWarningWhereTheStartIsGivenOrStable) {
  // .ic breaks the symmetry: the start is no equilibrium.
  std::string with_ic = kAstable + ".ic v(b2)=0.2\n";
  const fs::path deck = write_deck("unstable_", "astable_ic", with_ic);
  const fs::path dir = scratch_dir("unstable_astable_ic_run");
  Result r = run_lcspice("run '" + deck.string() + "' -o '" + (dir / "out.csv").string() + "'", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.err.find("unstable equilibrium"), std::string::npos) << r.err;
  // A stable operating point: the half-wave rectifier and the transistor switch.
  for (const char* name : {"half_wave_rectifier", "bjt_switch_rc_load"}) {
    r = run_lcspice("run '" + circuit(name).string() + "' -o '" + (dir / "out2.csv").string() + "'", dir);
    ASSERT_EQ(r.code, 0) << name << ": " << r.err;
    EXPECT_EQ(r.err.find("unstable equilibrium"), std::string::npos) << name << ": " << r.err;
  }
}

}  // namespace
}  // namespace lcs::cli_testing
