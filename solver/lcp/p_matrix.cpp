#include "solver/lcp/p_matrix.h"

#include <algorithm>
#include <cmath>

namespace lcs {

namespace {

bool positive_definite(const Eigen::MatrixXd& S) {
  if (S.rows() == 0) return true;
  Eigen::LLT<Eigen::MatrixXd> llt(S);
  if (llt.info() != Eigen::Success) return false;
  const double scale = S.diagonal().cwiseAbs().maxCoeff();
  return llt.matrixL().toDenseMatrix().diagonal().minCoeff() > 1e-9 * std::sqrt(scale);
}

bool symmetric(const Eigen::MatrixXd& M) {
  const double scale = M.size() > 0 ? M.cwiseAbs().maxCoeff() : 0.0;
  return (M - M.transpose()).cwiseAbs().maxCoeff() <= 1e-12 * std::max(scale, 1e-300);
}

bool symmetric_psd(const Eigen::MatrixXd& M) {
  const double scale = M.size() > 0 ? M.cwiseAbs().maxCoeff() : 0.0;
  if (!symmetric(M)) return false;
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(M);
  return eig.eigenvalues().minCoeff() >= -1e-12 * std::max(scale, 1e-300);
}

}  // namespace

PMatrixReport p_matrix_report(const Eigen::MatrixXd& M, int max_exact) {
  PMatrixReport r;
  const int n = static_cast<int>(M.rows());
  if (n == 0) return r;
  // x^T M x > 0 for x != 0: P; a symmetric M is then positive definite, and its O(n^3)
  // eigenvalues are not needed (they were 1.2 s of `analyze` at 1000 pairs).
  if (positive_definite(M + M.transpose())) {
    r.symmetric_psd = symmetric(M);
    return r;
  }
  r.symmetric_psd = symmetric_psd(M);
  if (n > max_exact) {
    r.verdict = PMatrixReport::Verdict::Unchecked;
    return r;
  }
  // Subsets by size, so the first failure is a smallest one.
  Eigen::VectorXd row_norm(n);
  for (int i = 0; i < n; ++i) row_norm(i) = std::max(M.row(i).norm(), 1e-300);
  std::vector<int> masks(std::size_t(1) << n);
  for (std::size_t s = 0; s < masks.size(); ++s) masks[s] = static_cast<int>(s);
  std::stable_sort(masks.begin(), masks.end(), [](int a, int b) {
    return __builtin_popcount(static_cast<unsigned>(a)) < __builtin_popcount(static_cast<unsigned>(b));
  });
  for (int mask : masks) {
    if (mask == 0) continue;
    std::vector<int> set;
    for (int i = 0; i < n; ++i)
      if (mask & (1 << i)) set.push_back(i);
    const int k = static_cast<int>(set.size());
    Eigen::MatrixXd sub(k, k);
    double scale = 1;
    for (int a = 0; a < k; ++a) {
      scale *= row_norm(set[a]);
      for (int b = 0; b < k; ++b) sub(a, b) = M(set[a], set[b]);
    }
    const double minor = sub.determinant() / scale;
    if (minor <= 1e-12) {
      r.verdict = PMatrixReport::Verdict::NotP;
      r.failing = set;
      r.minor = minor;
      return r;
    }
  }
  return r;
}

std::vector<Eigen::VectorXd> distinct_in_w(const Eigen::MatrixXd& M, const Eigen::VectorXd& q,
                                           const std::vector<Eigen::VectorXd>& solutions) {
  std::vector<Eigen::VectorXd> out, ws;
  double scale = q.size() > 0 ? q.cwiseAbs().maxCoeff() : 0.0;
  for (const Eigen::VectorXd& z : solutions)
    if (z.size() > 0) scale = std::max(scale, (M.cwiseAbs() * z.cwiseAbs()).maxCoeff());
  for (const Eigen::VectorXd& z : solutions) {
    const Eigen::VectorXd w = M * z + q;
    bool seen = false;
    for (const Eigen::VectorXd& v : ws)
      if (w.size() == 0 || (w - v).cwiseAbs().maxCoeff() <= 1e-9 * std::max(scale, 1e-300)) seen = true;
    if (seen) continue;
    ws.push_back(w);
    out.push_back(z);
  }
  return out;
}

int lcp_solution_index(const Eigen::MatrixXd& M, const Eigen::VectorXd& z) {
  std::vector<int> J;
  const double scale = z.size() > 0 ? z.cwiseAbs().maxCoeff() : 0.0;
  for (int i = 0; i < z.size(); ++i)
    if (z(i) > 1e-12 * scale) J.push_back(i);
  const int k = static_cast<int>(J.size());
  if (k == 0) return 1;
  Eigen::MatrixXd sub(k, k);
  double norms = 1;
  for (int a = 0; a < k; ++a) {
    for (int b = 0; b < k; ++b) sub(a, b) = M(J[a], J[b]);
    norms *= std::max(sub.row(a).norm(), 1e-300);
  }
  const double det = sub.determinant() / norms;
  return det > 1e-12 ? 1 : det < -1e-12 ? -1 : 0;
}

}  // namespace lcs
