#include "solver/model/sparse_lcs.h"

namespace lcs {

std::unique_ptr<SparseLcs> sparse_lcs_if_worth(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B,
                                               const Eigen::MatrixXd& C, const Eigen::MatrixXd& D,
                                               const Eigen::MatrixXd& E, const Eigen::MatrixXd& F) {
  const Eigen::Index n = A.rows(), m = D.rows();
  if (m < kSparsePairs && n + m < kSparseUnknowns) return nullptr;
  auto s = std::make_unique<SparseLcs>();
  s->A = A.sparseView();
  s->B = B.sparseView();
  s->C = C.sparseView();
  s->D = D.sparseView();
  const double nnz = static_cast<double>(s->A.nonZeros() + s->B.nonZeros() + s->C.nonZeros() +
                                         s->D.nonZeros());
  if (nnz > kSparseDensity * static_cast<double>(n + m) * static_cast<double>(n + m)) return nullptr;
  s->E = E;
  s->F = F;
  return s;
}

bool sparse_lcs_worth(const SparseLcs& s) {
  const Eigen::Index n = s.A.rows(), m = s.D.rows();
  if (m < kSparsePairs && n + m < kSparseUnknowns) return false;
  const double nnz = static_cast<double>(s.A.nonZeros() + s.B.nonZeros() + s.C.nonZeros() + s.D.nonZeros());
  return nnz <= kSparseDensity * static_cast<double>(n + m) * static_cast<double>(n + m);
}

}  // namespace lcs
