// Linear algebra that is well defined on empty operands. A circuit with no states, no pairs or
// no inputs gives 0-row or 0-column matrices; Eigen's decompositions and solves assert on (or,
// in Release, read through null pointers of) empty operands, so these return the empty result
// the mathematics gives instead (issue 9, defect 7).
#pragma once

#include <Eigen/Dense>

namespace lcs {

// X with A X = rhs, for a decomposition `a` of an n x n matrix A: n x k, empty when n or k is 0.
template <class Decomposition, class Rhs>
Eigen::MatrixXd solve_or_empty(const Decomposition& a, const Eigen::MatrixBase<Rhs>& rhs) {
  if (a.rows() == 0 || rhs.rows() == 0 || rhs.cols() == 0) return Eigen::MatrixXd::Zero(a.cols(), rhs.cols());
  return a.solve(rhs);
}

// max |m_ij|, 0 for an empty matrix.
template <class Derived>
double max_abs_or_zero(const Eigen::DenseBase<Derived>& m) {
  return m.size() > 0 ? m.cwiseAbs().maxCoeff() : 0.0;
}

}  // namespace lcs
