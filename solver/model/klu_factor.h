// One sparse LU factorisation by KLU (SuiteSparse), for the model's one-off solves with large
// sparse matrices (pair_blocks.h, lcs_index.cpp). KLU reports a singular matrix (ok() false):
// Eigen's SparseLU did not return on a 1000 x 1000 matrix with empty columns (the D of a
// 1000-diode ladder with RON = 0), so `analyze` hung there.
#pragma once

#include <memory>

#include <Eigen/Dense>
#include <Eigen/Sparse>

namespace lcs {

class KluFactor {
 public:
  explicit KluFactor(const Eigen::SparseMatrix<double>& matrix);  // square
  ~KluFactor();
  KluFactor(const KluFactor&) = delete;
  KluFactor& operator=(const KluFactor&) = delete;

  bool ok() const { return numeric_ != nullptr; }  // factorised: not (structurally) singular
  Eigen::VectorXd solve(Eigen::VectorXd rhs) const;  // requires ok()
  // Entries of L and U (a solve's work is about twice this), 0 when not ok().
  long factor_entries() const;

 private:
  struct Handles;
  std::unique_ptr<Handles> handles_;
  void* numeric_ = nullptr;
  int n_ = 0;
};

}  // namespace lcs
