#include "solver/model/structural_zeros.h"

#include <cmath>
#include <random>

namespace lcs {

void clear_structural_zeros(const Eigen::MatrixXd& E, const Eigen::MatrixXd& R,
                            Eigen::MatrixXd& solution) {
  const Eigen::Index n = E.rows();
  if (n == 0 || R.cols() == 0) return;
  std::mt19937_64 rng(0x5eed);  // fixed: formation stays reproducible
  std::uniform_real_distribution<double> magnitude(1.0, 2.0);
  Eigen::MatrixXd random = Eigen::MatrixXd::Zero(n, n);
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = 0; j < n; ++j)
      if (E(i, j) != 0) {
        const double sign = rng() & 1 ? 1.0 : -1.0;  // drawn first, as gcc and clang did (checked)
        random(i, j) = sign * magnitude(rng);
      }
  Eigen::FullPivLU<Eigen::MatrixXd> lu(random);
  if (!lu.isInvertible()) return;  // structurally singular: E was not invertible either
  const Eigen::MatrixXd inverse = lu.inverse();
  const double scale = inverse.cwiseAbs().maxCoeff();
  // Reach(r, c): some j with inverse(r, j) structurally nonzero and R(j, c) != 0.
  Eigen::MatrixXd inverse_pattern = (inverse.cwiseAbs().array() > 1e-9 * scale).cast<double>();
  Eigen::MatrixXd rhs_pattern = (R.array() != 0.0).cast<double>();
  const Eigen::MatrixXd reach = inverse_pattern * rhs_pattern;
  for (Eigen::Index c = 0; c < solution.cols(); ++c) {
    const double column = solution.col(c).cwiseAbs().maxCoeff();
    for (Eigen::Index r = 0; r < n; ++r)
      if (reach(r, c) == 0 && std::abs(solution(r, c)) <= 1e-9 * column) solution(r, c) = 0;
  }
}

}  // namespace lcs
