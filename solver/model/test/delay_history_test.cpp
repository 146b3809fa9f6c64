// DelayHistory (delay_history.h): what a line's history keeps and returns.
#include "solver/model/delay_history.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
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

// Reads between samples are continuous in s for every degree the methods use: the interpolant
// of one interval is fixed by that interval, so neighbouring reads differ by about the slope
// times their distance. Samples unevenly spaced (as IDA's steps are), of a(t) = sin t: before
// the stencil was fixed per interval, the linear read jumped at the midpoint of t_i-1 and t_i+1
// (it switched to extrapolating from t_i-1, t_i): by up to 0.17 here, by 3.7e-4 V in
// tline_lossy_rectifier with --method smooth, where IDA's steps collapsed onto the jump.
TEST(DelayHistory, ReadsAreContinuousBetweenUnevenSamples) {
  std::vector<double> times = {0.0};
  for (int i = 1; times.back() < 6; ++i) times.push_back(times.back() + (i % 3 == 0 ? 0.9 : 0.13 * (1 + i % 2)));
  for (int degree = 1; degree <= 4; ++degree) {
    SCOPED_TRACE("degree " + std::to_string(degree));
    DelayHistory history({1.0});
    history.reset({0.0});
    history.set_degree(degree);
    for (double t : times) history.record(t, {std::sin(t)});
    const double ds = 1e-7;
    double worst = 0;
    for (double s = 0.5 * ds; s < times.back(); s += ds * 997) {
      worst = std::max(worst, std::abs(history.wave(0, s + ds) - history.wave(0, s)));
    }
    // |a'| <= 1, and an interpolant of degree <= 4 through these samples has slope below 3.
    EXPECT_LT(worst, 3 * ds);
    for (size_t i = 1; i + 1 < times.size(); ++i) {  // just either side of every midpoint
      const double mid = 0.5 * (times[i - 1] + times[i + 1]);
      EXPECT_LT(std::abs(history.wave(0, mid + 1e-12) - history.wave(0, mid - 1e-12)), 1e-10) << "at " << mid;
    }
  }
}

}  // namespace
}  // namespace lcs
