#include "solver/integrators/exponential_action.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace lcs {

namespace {

// theta_m for a backward error of 2^-53: (degree, bound). Where published tables differ in the
// last digit, the smaller bound (more pieces) is kept.
constexpr struct {
  int degree;
  double theta;
} kTheta[] = {{1, 2.29e-16}, {2, 2.58e-8}, {3, 1.39e-5}, {4, 3.40e-4}, {5, 2.40e-3},  {6, 9.07e-3},
              {7, 2.38e-2},  {8, 5.00e-2}, {9, 8.96e-2}, {10, 1.44e-1}, {11, 2.14e-1}, {12, 3.00e-1},
              {13, 4.00e-1}, {14, 5.14e-1}, {15, 6.41e-1}, {16, 7.80e-1}, {17, 9.31e-1}, {18, 1.09},
              {19, 1.26},    {20, 1.44},   {21, 1.62},   {22, 1.82},    {23, 2.01},    {24, 2.22},
              {25, 2.43},    {26, 2.64},   {27, 2.86},   {28, 3.08},    {29, 3.31},    {30, 3.54},
              {35, 4.7},     {40, 6.0},    {45, 7.2},    {50, 8.5},     {55, 9.9}};

constexpr double kTol = 0x1p-53;

// Above this fraction of nonzero entries a dense product is as fast (measured on Eigen's
// products: a sparse one costs about three dense entries' time per nonzero).
constexpr double kSparseDensity = 0.1;

}  // namespace

ExponentialAction::ExponentialAction(const Eigen::MatrixXd& A) : A_(&A) {
  const long n = A.rows();
  if (n == 0) return;
  mu_ = A.trace() / static_cast<double>(n);
  Eigen::MatrixXd shifted = A;
  shifted.diagonal().array() -= mu_;
  norm1_ = shifted.cwiseAbs().colwise().sum().maxCoeff();
  const double nonzeros = static_cast<double>((A.array() != 0).count());
  if (nonzeros <= kSparseDensity * static_cast<double>(n) * static_cast<double>(n)) {
    sparse_ = A.sparseView(0.0, 0.0);
    sparse_.makeCompressed();
    relative_cost_ = std::max(nonzeros, 1.0) / (static_cast<double>(n) * static_cast<double>(n));
  }
}

ExponentialAction::Plan ExponentialAction::plan(double t) const {
  const double size = std::abs(t) * norm1_;
  Plan best;
  if (!(size > 0)) return best;  // exp(t A) b = e^(t mu) b
  long best_cost = std::numeric_limits<long>::max();
  for (const auto& [degree, theta] : kTheta) {
    const double pieces = std::ceil(size / theta);
    if (pieces > 1e12) continue;  // (degree 1 or 2 on a large norm)
    const long cost = degree * static_cast<long>(pieces);
    if (cost < best_cost) {
      best_cost = cost;
      best = {degree, static_cast<long>(pieces)};
    }
  }
  return best;
}

long ExponentialAction::planned_products(double t) const {
  const Plan p = plan(t);
  return p.degree * p.pieces;
}

long ExponentialAction::apply(double t, const Eigen::VectorXd& b, Eigen::VectorXd& out) const {
  const Plan p = plan(t);
  out = b;
  if (p.degree == 0) {
    out *= std::exp(t * mu_);
    return 0;
  }
  const double eta = std::exp(t * mu_ / static_cast<double>(p.pieces));
  Eigen::VectorXd term, product;
  long products = 0;
  for (long piece = 0; piece < p.pieces; ++piece) {
    term = out;
    double previous = term.lpNorm<Eigen::Infinity>();
    for (int k = 1; k <= p.degree; ++k) {
      if (relative_cost_ < 1)
        product.noalias() = sparse_ * term;
      else
        product.noalias() = *A_ * term;
      ++products;
      term = (t / (static_cast<double>(p.pieces) * k)) * (product - mu_ * term);
      out += term;
      const double current = term.lpNorm<Eigen::Infinity>();
      if (previous + current <= kTol * out.lpNorm<Eigen::Infinity>()) break;
      previous = current;
    }
    out *= eta;
  }
  return products;
}

}  // namespace lcs
