// Is M a P-matrix (every principal minor positive)? Exactly then LCP(q, M) has a unique solution
// for every q (Stewart 2.2, Theorem 2.x of Cottle-Pang-Stone 3.3.7). Diode networks give
// symmetric positive semidefinite M (a unique w, 5.4); transistors make M non-symmetric, and the
// full Ebers-Moll model keeps a lone transistor's block a P-matrix only because alpha_F,
// alpha_R < 1 (5.4.7). Feedback between transistors (a flip-flop) is what breaks it.
#pragma once

#include <vector>

#include <Eigen/Dense>

namespace lcs {

struct PMatrixReport {
  enum class Verdict { P, NotP, Unchecked };
  Verdict verdict = Verdict::P;
  bool symmetric_psd = false;   // symmetric positive semidefinite (P0): w is unique
  std::vector<int> failing;     // NotP: a smallest index set whose principal minor is <= 0
  double minor = 0;             // that minor (relative to the product of the rows' norms)
};

// Exact for n <= max_exact (all 2^n principal minors, smallest sets first, relative tolerance
// 1e-12); above it only the sufficient test "M + M^T positive definite" (then P), else Unchecked.
PMatrixReport p_matrix_report(const Eigen::MatrixXd& M, int max_exact = 16);

// lcp_solution_index is declared in lcp.h (the warm solver uses it) and defined here.

}  // namespace lcs
