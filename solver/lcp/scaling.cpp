// Exact (power-of-two) Ruiz equilibration of M and normalisation of q, shared by all solvers so
// that their tolerances are relative to the scale of the data (circuits mix 1e-9 and 1e9).
#include <cmath>
#include <stdexcept>
#include <string>

#include "solver/lcp/lcp_internal.h"

namespace lcs::lcp_detail {

namespace {

double nearest_power_of_two(double x) {
  int e = static_cast<int>(std::lround(std::log2(x)));
  return std::ldexp(1.0, e);
}

bool within_band(double m) { return m == 0.0 || (m >= 0.5 && m <= 2.0); }

}  // namespace

void check_square(const Eigen::MatrixXd& M, const Eigen::VectorXd& q, const char* who) {
  if (M.rows() != M.cols() || M.rows() != q.size())
    throw std::invalid_argument(std::string(who) + ": M must be n x n and q of size n (got " +
                                std::to_string(M.rows()) + "x" + std::to_string(M.cols()) +
                                ", " + std::to_string(q.size()) + ")");
  if (!q.allFinite()) throw std::invalid_argument(std::string(who) + ": q is not finite");
}

Equilibration equilibrate(const Eigen::MatrixXd& M) {
  if (M.rows() != M.cols()) throw std::invalid_argument("LCP: M must be square");
  if (!M.allFinite()) throw std::invalid_argument("LCP: M is not finite");
  const Eigen::Index n = M.rows();
  Equilibration eq;
  eq.S = M;
  eq.row = Eigen::VectorXd::Ones(n);
  eq.col = Eigen::VectorXd::Ones(n);
  Eigen::VectorXd fr(n), fc(n);
  for (int it = 0; it < 60; ++it) {
    bool done = true;
    for (Eigen::Index i = 0; i < n; ++i) {
      double m = eq.S.row(i).cwiseAbs().maxCoeff();
      done = done && within_band(m);
      fr(i) = m > 0 ? nearest_power_of_two(1.0 / std::sqrt(m)) : 1.0;
    }
    for (Eigen::Index j = 0; j < n; ++j) {
      double m = eq.S.col(j).cwiseAbs().maxCoeff();
      done = done && within_band(m);
      fc(j) = m > 0 ? nearest_power_of_two(1.0 / std::sqrt(m)) : 1.0;
    }
    if (done) break;
    eq.S = fr.asDiagonal() * eq.S * fc.asDiagonal();
    eq.row.array() *= fr.array();
    eq.col.array() *= fc.array();
  }
  return eq;
}

double normalise_q(const Equilibration& eq, const Eigen::VectorXd& q, Eigen::VectorXd& qt) {
  qt = eq.row.cwiseProduct(q);
  double qn = qt.cwiseAbs().maxCoeff();
  if (!(qn > 0)) qn = 1.0;  // q = 0 (or n = 0)
  qt /= qn;
  return qn;
}

}  // namespace lcs::lcp_detail
