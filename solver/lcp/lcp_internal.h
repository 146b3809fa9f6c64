// Internals of the LCP module shared by lemke.cpp, warm_solver.cpp, enumeration.cpp, residual.cpp
// and sparse_active_set.cpp.
// Not part of the public interface (lcp.h); may change without notice.
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <unordered_set>
#include <vector>

#include <Eigen/Dense>

#include "solver/lcp/lcp.h"

namespace lcs::lcp_detail {

// The rounding that computing w_i = sum_j M_ij z_j + q_i leaves, relative to the sizes that meet
// in it (|q_i| + sum_j |M_ij z_j|): the products' own (n eps at most, ~sqrt(n) eps typically)
// and z's from a backward-stable solve. Used by lcp_solved_to_rounding and by the sparse
// active-set search's judgement of trimmed pairs.
constexpr double kRowRounding = 64 * std::numeric_limits<double>::epsilon();

// Positive diagonal equilibration S = diag(row) * M * diag(col), all factors powers of two
// (so scaling is exact in floating point). LCP(q, M) and LCP(diag(row) q, S) are equivalent:
//   z = diag(col) * y,   w = diag(row)^{-1} * v,   y ⟂ v  <=>  z ⟂ w.
// Computed by Ruiz iteration in the max norm: afterwards every non-zero row and column of S
// has max-norm within a factor ~2 of 1. All solvers work on S and on q normalised to
// max-norm 1, so their absolute tolerances are in fact relative to |M| and |q|.
struct Equilibration {
  Eigen::VectorXd row, col;
  Eigen::MatrixXd S;
};
Equilibration equilibrate(const Eigen::MatrixXd& M);

// qt = diag(row) * q / qn with qn = |diag(row) q|_inf (qn = 1 if q = 0). Returns qn.
double normalise_q(const Equilibration& eq, const Eigen::VectorXd& q, Eigen::VectorXd& qt);

// Natural residual of LCP(qt, S) at y, allocation free given a preallocated v (size n).
double scaled_residual(const Eigen::MatrixXd& S, const Eigen::VectorXd& qt,
                       const Eigen::VectorXd& y, Eigen::VectorXd& v);

void check_square(const Eigen::MatrixXd& M, const Eigen::VectorXd& q, const char* who);

// Lemke's method on an equilibrated matrix. Holds the workspace so repeated solves of the same
// size do not allocate in the tableau (the final polish factorises M_JJ and may allocate).
class LemkeEngine {
 public:
  LemkeEngine() = default;
  explicit LemkeEngine(const Eigen::MatrixXd& M) { set_matrix(M); }
  void set_matrix(const Eigen::MatrixXd& M);
  const Equilibration& equilibration() const { return eq_; }

  // M must be the matrix given to set_matrix. out.z / out.w are resized only if needed.
  void solve(const Eigen::MatrixXd& M, const Eigen::VectorXd& q, const LemkeOptions& options,
             LcpSolution& out);
  // After a Solved result (n <= 64): bit i set when z_i is basic in the final complementary
  // basis, including a basic z_i at zero level (degenerate vertex). That basis matrix is
  // nonsingular, unlike the block of the support {z_i > 0} when solutions are not unique.
  // The final basis's basic z variables: set[i] = 1 for z_i basic (any n).
  void basic_z(std::string& set) const;

  // Parametric principal pivoting from the current complementary basis (warm_solver.cpp): that
  // basis must be feasible for LCP(from_q, M); the path q(s) = q + s (from_q - q) is followed
  // from s = 1 to s = 0 (Murty, Linear Complementarity, ch. 5; Lemke's scheme with covering
  // vector from_q - q started from a solved basis), one principal pivot where a basic variable
  // reaches 0. False, leaving the basis unusable, where the path folds back (the pivot's sign:
  // where a transistor circuit's branch ends, a regenerative switching), past max_pivots, or
  // when the answer misses feas_tol: the caller then runs solve(). Rows reaching 0 together
  // (degenerate: on a TTL adder, 846 of its 868 misses that went to Lemke before they were
  // handled) leave one by one, the first whose pivot continues the path first. Solved: out
  // as solve() fills it (no polish), and the basis is the new one.
  bool solve_from_basis(const Eigen::MatrixXd& M, const Eigen::VectorXd& q, const Eigen::VectorXd& from_q,
                        const LemkeOptions& options, int max_pivots, LcpSolution& out);

 private:
  void pivot(int row, int entering);
  void entering_column(int var);
  int lexicographic_leaving_row(double pivot_tol);
  void refactor();
  LcpStatus pivot_to_end(const LemkeOptions& options, int& pivots);
  void solve_path(const Eigen::MatrixXd& M, const Eigen::VectorXd& q, double qn,
                  const LemkeOptions& options, double shift, LcpSolution& out);
  void finish(const Eigen::MatrixXd& M, const Eigen::VectorXd& q, double qn,
              const LemkeOptions& options, bool solved, LcpSolution& out);
  void answer_from_basis(const Eigen::MatrixXd& M, const Eigen::VectorXd& q, double qn, LcpSolution& out) const;

  int n_ = 0;
  Equilibration eq_;
  Eigen::MatrixXd Binv_;        // inverse of the current basis matrix
  Eigen::VectorXd b_;           // current basic values Binv * qt
  Eigen::VectorXd a_;           // entering column Binv * column(var)
  Eigen::VectorXd qt_, y_, y2_, v_;
  Eigen::VectorXd dq_, bd_;     // solve_from_basis: from_q - q normalised, and Binv * dq_
  Eigen::RowVectorXd prow_;     // pivot row scratch
  std::vector<int> basis_;      // variable in each row: w_i = i, z_i = n + i, s = 2n
  std::vector<int> ray_;        // at a ray termination: the z_i growing along the ray
  std::vector<int> keep_, keep2_, tied_;
  std::unordered_set<std::uint64_t> visited_;  // hashes of the bases on the current path
  int since_refactor_ = 0;
};

}  // namespace lcs::lcp_detail
