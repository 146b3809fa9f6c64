// DelayHistory (delay_history.h): what a line's history keeps and returns.
#include "solver/model/delay_history.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace lcs {
namespace {

// A wave a(t) = sin(2 pi t / 3) recorded every 1e-3 over [0, 10] into a line of delay 1 and one
// of delay 0.25 (10,001 samples: the history trims its oldest in bulk past 4096). A method whose
// steps are at most the shortest delay (the smooth method: IDA records its step, then reads rows
// inside it) reads as far back as the newest record minus the longest and the shortest delay;
// those reads must still find the recorded wave, not the value held before the run (0 here).
TEST(DelayHistory, TrimKeepsWhatAReadOneStepBehindTheNewestRecordNeeds) {
  DelayHistory history({1.0, 0.25});
  history.reset({0.0, 0.0});
  const auto wave = [](double t) { return std::sin(2 * M_PI * t / 3) + 2; };
  for (int i = 0; i <= 10000; ++i) {
    const double t = i * 1e-3;
    history.record(t, {wave(t), wave(t)});
    // The reads of a row inside the last step of at most 0.25: u(t) = a(t - delay).
    const double row = t - 0.2499;
    if (row < 1.0) continue;
    ASSERT_NEAR(history.value(0, row), wave(row - 1.0), 1e-5) << "t = " << t;
    ASSERT_NEAR(history.value(1, row), wave(row - 0.25), 1e-5) << "t = " << t;
  }
  EXPECT_LT(history.times().size(), 10001u);  // it did trim
}

// Reads before the first record hold the value before the run; reads at a jump take the later side.
TEST(DelayHistory, BeforeTheFirstRecordTheWaveHoldsAndAJumpReadsItsLaterValue) {
  DelayHistory history({0.5});
  history.reset({3.0});
  history.record(1.0, {1.0});
  history.record(2.0, {2.0});
  history.record(2.0, {7.0});
  history.record(3.0, {8.0});
  EXPECT_EQ(history.value(0, 1.4), 3.0);
  EXPECT_EQ(history.value(0, 2.5), 7.0);
  EXPECT_DOUBLE_EQ(history.value(0, 2.0), 1.5);   // between 1 and 2: linear through (1,1), (2,2)
  EXPECT_DOUBLE_EQ(history.value(0, 3.0), 7.5);   // between the jump's later side and (3, 8)
}

}  // namespace
}  // namespace lcs
