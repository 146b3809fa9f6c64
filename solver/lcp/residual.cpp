// Natural residual of an LCP: max_i max(|min(z_i, w_i)|, -z_i, -w_i, 0), w = M z + q.
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "solver/lcp/lcp.h"
#include "solver/lcp/lcp_internal.h"

namespace lcs {

namespace {

double natural_residual(const Eigen::VectorXd& z, const Eigen::VectorXd& w) {
  double r = 0.0;
  for (Eigen::Index i = 0; i < z.size(); ++i) {
    double zi = z(i), wi = w(i);
    double ri = std::max({std::abs(std::min(zi, wi)), -zi, -wi, 0.0});
    if (std::isnan(ri) || std::isnan(zi) || std::isnan(wi)) return std::numeric_limits<double>::infinity();
    r = std::max(r, ri);
  }
  return r;
}

}  // namespace

double lcp_residual(const Eigen::MatrixXd& M, const Eigen::VectorXd& q, const Eigen::VectorXd& z) {
  if (M.rows() != M.cols() || M.rows() != q.size() || z.size() != q.size())
    throw std::invalid_argument("lcp_residual: size mismatch");
  Eigen::VectorXd w = q;
  w.noalias() += M * z;
  return natural_residual(z, w);
}

bool lcp_solved_to_rounding(const Eigen::MatrixXd& M, const Eigen::VectorXd& q, const Eigen::VectorXd& z,
                            double tol) {
  if (M.rows() != M.cols() || M.rows() != q.size() || z.size() != q.size())
    throw std::invalid_argument("lcp_solved_to_rounding: size mismatch");
  if (!z.allFinite()) return false;
  const Eigen::Index n = q.size();
  if (n == 0) return true;
  const double t = tol * std::max({1.0, q.cwiseAbs().maxCoeff(), z.cwiseAbs().maxCoeff()});
  const Eigen::VectorXd w = M * z + q;
  const Eigen::VectorXd size = M.cwiseAbs() * z.cwiseAbs() + q.cwiseAbs();
  for (Eigen::Index i = 0; i < n; ++i) {
    const double ti = std::max(t, lcp_detail::kRowRounding * size(i));
    if (!(z(i) >= -t && w(i) >= -ti && (z(i) <= t || w(i) <= ti))) return false;
  }
  return true;
}

namespace lcp_detail {

double scaled_residual(const Eigen::MatrixXd& S, const Eigen::VectorXd& qt,
                       const Eigen::VectorXd& y, Eigen::VectorXd& v) {
  v = qt;
  v.noalias() += S * y;
  return natural_residual(y, v);
}

}  // namespace lcp_detail
}  // namespace lcs
