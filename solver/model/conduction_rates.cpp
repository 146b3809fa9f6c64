#include "solver/model/conduction_rates.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace lcs {

namespace {
constexpr double kInfinity = std::numeric_limits<double>::infinity();
}  // namespace

Eigen::VectorXd conduction_rates(const Lcs& s) {
  Eigen::VectorXd r = Eigen::VectorXd::Zero(s.pairs());
  const Eigen::MatrixXd CB = s.states() > 0 ? Eigen::MatrixXd(s.C * s.B) : Eigen::MatrixXd();
  for (int i = 0; i < s.pairs(); ++i) {
    const double sum = s.states() > 0 ? CB.row(i).cwiseAbs().sum() : 0.0;
    r(i) = s.D(i, i) > 0 ? sum / s.D(i, i) : kInfinity;
  }
  return r;
}

Eigen::VectorXd conduction_rates(const SparseLcs& s) {
  const Eigen::SparseMatrix<double, Eigen::RowMajor> CB = s.C * s.B;
  Eigen::VectorXd r(CB.rows());
  for (int i = 0; i < CB.rows(); ++i) {
    double sum = 0;
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(CB, i); it; ++it) sum += std::abs(it.value());
    const double d = s.D.coeff(i, i);
    r(i) = d > 0 ? sum / d : kInfinity;
  }
  return r;
}

double fastest_finite_rate(const Eigen::VectorXd& rates) {
  double fastest = 0;
  for (Eigen::Index i = 0; i < rates.size(); ++i)
    if (std::isfinite(rates(i))) fastest = std::max(fastest, rates(i));
  return fastest;
}

}  // namespace lcs
