// How large a dense LCS lcspice forms. A circuit's A, B, C, D hold (n + m)^2 numbers (n states,
// m pairs) once formed dense, and the methods that work on them (event's exponentials, Radau's
// stage systems, the smooth method's Jacobian, the dense step LCP of the fixed-step methods'
// fallback, `analyze`'s uniqueness and index reports) hold a few more matrices of that size and
// cost O((n + m)^3). Sparse circuits step without them (sparse_lcs.h, sparse_descriptor.h); a
// circuit whose dense working set would exceed the budget is refused by the method, with the sizes,
// instead of being killed by the machine. Measured (issue 12's families, `/usr/bin/time lcspice`):
// `analyze` of a 1000-stage multiplier (n + m = 4000) 6.5 s and 560 MB; of a 2500-stage one
// (10000) killed at 200 s with 3.1 GB.
#pragma once

#include <cstddef>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace lcs {

// The dense working set a method may form: its matrices of (n + m)^2 numbers together.
constexpr std::size_t kDenseBudgetBytes = std::size_t{1} << 30;
// `analyze`'s dense reports (index, uniqueness) are O((n + m)^3) in time: up to n + m = 4096.
constexpr std::size_t kAnalyzeDenseBytes = std::size_t{128} << 20;

// Bytes of one dense (n + m) x (n + m) matrix of doubles (the formed A, B, C, D together).
inline std::size_t dense_lcs_bytes(int states, int pairs) {
  const std::size_t k = static_cast<std::size_t>(states) + static_cast<std::size_t>(pairs);
  return k * k * sizeof(double);
}

inline std::string format_bytes(std::size_t bytes) {
  char buf[32];
  if (bytes >= (std::size_t{1} << 30)) std::snprintf(buf, sizeof buf, "%.1f GB", bytes / double(1 << 30));
  else std::snprintf(buf, sizeof buf, "%.0f MB", bytes / double(1 << 20));
  return buf;
}

// "the dense LCS of 5001 states and 5000 pairs (0.7 GB a matrix, 3 of them: 2.2 GB, over the 1.0 GB
// budget for dense matrices)"; `copies` counts the matrices of that size the user keeps at once.
inline std::string dense_budget_reason(int states, int pairs, int copies, std::size_t budget = kDenseBudgetBytes) {
  const std::size_t one = dense_lcs_bytes(states, pairs);
  return "the dense LCS of " + std::to_string(states) + " states and " + std::to_string(pairs) + " pairs (" +
         format_bytes(one) + " a matrix" +
         (copies > 1 ? ", " + std::to_string(copies) + " of them: " + format_bytes(one * copies) : std::string()) +
         ") is over the " + format_bytes(budget) + " budget for dense matrices";
}

inline bool dense_within_budget(int states, int pairs, int copies, std::size_t budget = kDenseBudgetBytes) {
  return dense_lcs_bytes(states, pairs) <= budget / static_cast<std::size_t>(copies < 1 ? 1 : copies);
}

// Thrown by LcsProblem::lcs() when forming the dense matrices would exceed the budget: the
// callers that can say at which time check first (and throw NumericalFailure); this is the
// backstop, reported with exit code 3.
class DenseBudgetExceeded : public std::runtime_error {
 public:
  explicit DenseBudgetExceeded(const std::string& why) : std::runtime_error(why) {}
};

}  // namespace lcs
