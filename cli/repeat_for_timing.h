// The timing policy of `bench`: machines are shared and noisy, so a fast run is repeated until
// `min_seconds` of CPU are spent (at least once, at most 50 times) and the least time is kept
// (the least disturbed run).
#pragma once

namespace lcs {

// `run(k)` does run k and returns its CPU seconds; returns the least of them.
template <class Run>
double least_cpu_of_repeats(double min_seconds, Run run) {
  double least = 0, spent = 0;
  for (int k = 0; k < 50 && (k == 0 || spent < min_seconds); ++k) {
    const double cpu = run(k);
    spent += cpu;
    if (k == 0 || cpu < least) least = cpu;
  }
  return least;
}

}  // namespace lcs
