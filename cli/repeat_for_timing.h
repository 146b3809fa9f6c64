// The timing policy of `bench`: machines are shared and noisy, so a fast run is repeated until
// `min_seconds` of CPU are spent (at least once, at most 50 times) and the least time is kept
// (the least disturbed run).
#pragma once

namespace lcs {

// `run(k)` does run k and returns its CPU seconds; returns the least of them. With
// `min_repeats` > 1, at least that many runs while they have spent under `repeat_budget` seconds:
// a first run also pays for first touching its memory (page faults; `bench --scale rectifiers`
// at 1000 diodes, 1000 steps: 0.085-0.12 s for one run, 0.046-0.059 s the least of three), so a
// series whose short runs are repeated and long ones not would step up where the repeats stop.
template <class Run>
double least_cpu_of_repeats(double min_seconds, Run run, int min_repeats = 1, double repeat_budget = 2.0) {
  double least = 0, spent = 0;
  for (int k = 0; k < 50 && (k == 0 || spent < min_seconds || (k < min_repeats && spent < repeat_budget)); ++k) {
    const double cpu = run(k);
    spent += cpu;
    if (k == 0 || cpu < least) least = cpu;
  }
  return least;
}

}  // namespace lcs
