// The random circuits through the command line: `lcspice run FILE --method M -o out.csv` for the
// first kCliSeeds seeds of the CI range and every registered method must exit 0 and write the CSV
// of SPEC §3 (header, one field per probe in every row, at least 12 significant digits, times
// strictly increasing from 0 to TSTOP), holding the rows the same method computes in-process.
#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include "solver/integrators/method_registry.h"
#include "tests/cli_support.h"
#include "tests/random/differential.h"
#include "tests/random/method_run.h"

namespace lcs::random_circuit {
namespace {

namespace cli = lcs::cli_testing;

constexpr std::uint64_t kFirstCliSeed = 1;
constexpr std::uint64_t kCliSeeds = 5;

// SPEC §3: RFC 4180 header, a name with a comma double-quoted.
std::string expected_header(const std::vector<std::string>& names) {
  std::string line = "time";
  for (const std::string& n : names) line += "," + (n.find(',') != std::string::npos ? "\"" + n + "\"" : n);
  return line;
}

// Significant digits of a number as printed ("-1.23400000000000e-05" has 15).
int significant_digits(const std::string& field) {
  int digits = 0;
  bool leading = true;
  for (char c : field) {
    if (c == 'e' || c == 'E') break;
    if (!std::isdigit(static_cast<unsigned char>(c))) continue;
    if (leading && c == '0') continue;
    leading = false;
    ++digits;
  }
  return leading ? 99 : digits;  // 0 printed as "0.00000000000000e+00" has all its digits
}

bool parses_fully(const std::string& field, double& value) {
  char* end = nullptr;
  value = std::strtod(field.c_str(), &end);
  return !field.empty() && end == field.c_str() + field.size() && std::isfinite(value);
}

class RandomCircuitsCli : public ::testing::TestWithParam<std::uint64_t> {};

TEST_P(RandomCircuitsCli, EveryMethodExitsZeroWithTheSpecCsv) {
  const Deck deck = valid_deck(GetParam());
  const cli::fs::path dir = cli::scratch_dir("random_" + std::to_string(deck.seed));
  const cli::fs::path netlist = dir / "circuit.cir";
  std::ofstream(netlist) << deck.text;
  for (const MethodEntry& entry : method_registry()) {
    SCOPED_TRACE("seed " + std::to_string(deck.seed) + ", --method " + entry.name + ", netlist:\n" + deck.text);
    const MethodRun in_process = run_method(deck.text, entry);
    ASSERT_TRUE(in_process.failure.empty()) << in_process.failure;
    const cli::fs::path out = dir / (entry.name + ".csv");
    const cli::Result r =
        cli::run_lcspice("run '" + netlist.string() + "' --method " + entry.name + " -o '" + out.string() + "'", dir);
    ASSERT_EQ(r.code, 0) << r.err;
    const std::string text = cli::read_file(out);
    EXPECT_EQ(text.substr(0, text.find('\n')), expected_header(in_process.names));
    const cli::Csv csv = cli::parse_csv(text);
    ASSERT_EQ(csv.rows.size(), in_process.times.size());
    EXPECT_NE(r.err.find("wrote " + std::to_string(csv.rows.size()) + " rows"), std::string::npos) << r.err;
    for (size_t k = 0; k < csv.raw.size(); ++k) {
      ASSERT_EQ(csv.raw[k].size(), csv.header.size()) << "row " << k;
      for (size_t c = 0; c < csv.raw[k].size(); ++c) {
        double value = 0;
        const std::string& field = csv.raw[k][c];
        ASSERT_TRUE(parses_fully(field, value)) << "row " << k << " field " << c << ": '" << field << "'";
        EXPECT_GE(significant_digits(field), 12) << "row " << k << ": " << field;
        const double expected = c == 0 ? in_process.times[k] : in_process.rows[k](static_cast<int>(c - 1));
        EXPECT_NEAR(value, expected, 1e-12 * std::abs(expected) + 1e-300) << "row " << k << " column " << c;
      }
      if (k > 0) {
        ASSERT_GT(csv.rows[k][0], csv.rows[k - 1][0]) << "row " << k;
      }
    }
    EXPECT_EQ(csv.rows.front()[0], 0.0);
    EXPECT_NEAR(csv.rows.back()[0], in_process.tstop, 1e-12 * in_process.tstop);
  }
}

INSTANTIATE_TEST_SUITE_P(Seeds, RandomCircuitsCli, ::testing::Range(kFirstCliSeed, kFirstCliSeed + kCliSeeds),
                         [](const ::testing::TestParamInfo<std::uint64_t>& info) {
                           return "seed_" + std::to_string(info.param);
                         });

}  // namespace
}  // namespace lcs::random_circuit
