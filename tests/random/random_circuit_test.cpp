// Random-circuit differential test (issue 9): the circuits of a fixed seed range run through every
// registered method (differential.h says what is checked). CI runs seeds kFirstSeed to
// kFirstSeed + kSeedCount - 1 in blocks of kSeedsPerBlock (one ctest test each, so ctest -j
// spreads them). Long runs:
//
//   LCSPICE_RANDOM_SEEDS=first:count build/tests/random/random_circuit_test
//
// and LCSPICE_RANDOM_REPORT=1 prints one line per seed (time, discards, each method's worst mean
// discrepancy). A failure prints the seed, what disagreed and the netlist.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "tests/random/differential.h"

namespace lcs::random_circuit {
namespace {

constexpr std::uint64_t kFirstSeed = 1;
constexpr std::uint64_t kSeedCount = 120;
constexpr std::uint64_t kSeedsPerBlock = 10;

struct SeedRange {
  std::uint64_t first = kFirstSeed, count = kSeedCount;
};

SeedRange seed_range() {
  SeedRange r;
  const char* env = std::getenv("LCSPICE_RANDOM_SEEDS");
  if (!env) return r;
  unsigned long long first = 0, count = 0;
  if (std::sscanf(env, "%llu:%llu", &first, &count) != 2 || count == 0) {
    std::fprintf(stderr, "LCSPICE_RANDOM_SEEDS=%s: expected first:count (e.g. 1000:5000)\n", env);
    std::exit(1);
  }
  r.first = first;
  r.count = count;
  return r;
}

std::vector<std::uint64_t> block_starts() {
  const SeedRange r = seed_range();
  std::vector<std::uint64_t> out;
  for (std::uint64_t s = r.first; s < r.first + r.count; s += kSeedsPerBlock) out.push_back(s);
  return out;
}

std::string report_line(const SeedVerdict& v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "seed %llu %.3fs discards %d%s", static_cast<unsigned long long>(v.deck.seed),
                v.seconds, v.discarded, v.deck.rough ? " rough" : "");
  std::string line = buf;
  for (const MethodVerdict& m : v.methods) {
    if (!m.compared) {
      line += "  " + m.method + (m.documented_failure.empty() ? " -" : " exit-3");
      continue;
    }
    std::snprintf(buf, sizeof buf, "  %s %.2e", m.method.c_str(), m.discrepancy);
    line += buf;
    if (m.history.size() > 1) line += "(h/" + std::to_string(1 << (m.history.size() - 1)) + ")";
  }
  return line + (v.problems.empty() ? "" : "  FAILED");
}

class RandomCircuits : public ::testing::TestWithParam<std::uint64_t> {};

TEST_P(RandomCircuits, EveryMethodRunsCleanAndAgreesWithTheEventMethod) {
  const SeedRange r = seed_range();
  const std::uint64_t first = GetParam(), end = std::min(first + kSeedsPerBlock, r.first + r.count);
  const bool report = std::getenv("LCSPICE_RANDOM_REPORT") != nullptr;
  for (std::uint64_t seed = first; seed < end; ++seed) {
    const SeedVerdict v = check_seed(seed);
    if (report) std::printf("%s\n", report_line(v).c_str());
    if (!v.problems.empty()) ADD_FAILURE() << describe_failure(v);
  }
}

INSTANTIATE_TEST_SUITE_P(Seeds, RandomCircuits, ::testing::ValuesIn(block_starts()),
                         [](const ::testing::TestParamInfo<std::uint64_t>& info) {
                           const std::uint64_t last =
                               std::min(info.param + kSeedsPerBlock, seed_range().first + seed_range().count) - 1;
                           return "seeds_" + std::to_string(info.param) + "_to_" + std::to_string(last);
                         });

}  // namespace
}  // namespace lcs::random_circuit
