#include "solver/integrators/taylor_segment.h"

#include <algorithm>
#include <cmath>

namespace lcs {

std::optional<TaylorSegment> TaylorSegment::build(const Eigen::MatrixXd& M, const Eigen::MatrixXd& L,
                                                  const Eigen::VectorXd& X0, double len,
                                                  const std::function<Eigen::VectorXd(double)>& exact_state) {
  const double norm1 = M.size() > 0 ? M.cwiseAbs().colwise().sum().maxCoeff() : 0.0;  // ||M||_1
  if (!(len > 0) || !std::isfinite(norm1)) return std::nullopt;
  const double pieces = std::max(1.0, std::ceil(2 * norm1 * len));
  if (pieces > kMaxPieces) return std::nullopt;
  TaylorSegment seg;
  seg.len_ = len;
  seg.rho_ = len / pieces;
  const double rho = seg.rho_;
  const double l_max = L.size() > 0 ? L.cwiseAbs().maxCoeff() : 0.0;
  const int max_terms = static_cast<int>(M.rows()) + 60;
  for (int i = 0; i < static_cast<int>(pieces); ++i) {
    // S_k = M^k X(r_i) ρ^k / k!: the terms scaled to the piece, so a(r_i + x ρ) = Σ_k (L S_k) x^k
    // with x in [0, 1]. ||S_k+1||_1 <= ||S_k||_1 / (2 (k+1)), so once max|L| ||S_k||_1 is below
    // the tolerance the rest of the series is too. The huge entries of S_k (a fitted input's
    // coefficient c_j / h^j) are M's nilpotent shift: they become exact zeros past its degree.
    Eigen::VectorXd S = i == 0 ? X0 : exact_state(i * rho);
    if (!S.allFinite()) return std::nullopt;
    std::vector<Eigen::VectorXd> waves;
    double scale = 0;
    for (int k = 0;; ++k) {
      waves.push_back(L * S);
      scale = std::max(scale, waves.back().cwiseAbs().maxCoeff());
      if (l_max * S.lpNorm<1>() <= kTermTol * scale) break;
      if (k + 1 >= max_terms) return std::nullopt;
      S = M * (S * (rho / (k + 1)));  // scaled first: M S alone could overflow where S ρ does not
    }
    Eigen::MatrixXd W(L.rows(), static_cast<Eigen::Index>(waves.size()));
    for (size_t k = 0; k < waves.size(); ++k) W.col(static_cast<Eigen::Index>(k)) = waves[k];
    if (!W.allFinite()) return std::nullopt;
    seg.terms_.push_back(std::move(W));
  }
  return seg;
}

void TaylorSegment::eval(double r, std::vector<double>& values, std::vector<double>& slopes) const {
  r = std::max(0.0, r);
  const int i = static_cast<int>(std::min<double>(pieces() - 1, std::floor(r / rho_)));
  const double x = (r - i * rho_) / rho_;
  const Eigen::MatrixXd& W = terms_[i];
  const Eigen::Index waves = W.rows(), K = W.cols();
  values.assign(static_cast<size_t>(waves), 0.0);
  slopes.assign(static_cast<size_t>(waves), 0.0);
  for (Eigen::Index w = 0; w < waves; ++w) {
    double v = 0, dv = 0;
    for (Eigen::Index k = K - 1; k >= 0; --k) {
      dv = dv * x + v;  // the derivative's Horner runs one term behind
      v = v * x + W(w, k);
    }
    values[static_cast<size_t>(w)] = v;
    slopes[static_cast<size_t>(w)] = dv / rho_;
  }
}

}  // namespace lcs
