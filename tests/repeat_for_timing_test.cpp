#include "cli/repeat_for_timing.h"

#include <functional>
#include <vector>

#include <gtest/gtest.h>

namespace lcs {
namespace {

// Runs with given CPU times, recording how many were made.
struct Runs {
  std::vector<double> cpu;
  int made = 0;
  double operator()(int k) {
    ++made;
    return cpu.at(k);
  }
};

TEST(LeastCpuOfRepeats, RepeatsShortRunsUntilTheMinimumAndKeepsTheLeast) {
  Runs runs{{0.02, 0.01, 0.03, 0.5}};
  EXPECT_EQ(least_cpu_of_repeats(0.05, std::ref(runs)), 0.01);
  EXPECT_EQ(runs.made, 3);  // 0.02 + 0.01 + 0.03 reach 0.05
}

TEST(LeastCpuOfRepeats, ALongRunIsMadeOnceUnlessRepeatsAreAskedFor) {
  Runs once{{0.3, 0.1, 0.1}};
  EXPECT_EQ(least_cpu_of_repeats(0.05, std::ref(once)), 0.3);
  EXPECT_EQ(once.made, 1);
  // The scale bench's policy: three runs, so a cold first run (page faults) is not all there is.
  Runs thrice{{0.3, 0.1, 0.2, 0.05}};
  EXPECT_EQ(least_cpu_of_repeats(0.05, std::ref(thrice), 3), 0.1);
  EXPECT_EQ(thrice.made, 3);
}

TEST(LeastCpuOfRepeats, RepeatsStopAtTheirBudget) {
  Runs runs{{1.5, 0.7, 0.6}};
  EXPECT_EQ(least_cpu_of_repeats(0.05, std::ref(runs), 3, 2.0), 0.7);
  EXPECT_EQ(runs.made, 2);  // 1.5 + 0.7 spent: no third run
}

}  // namespace
}  // namespace lcs
