// Helpers shared by the LCP tests: seeded random problem generators and residual measures.
#pragma once

#include <algorithm>
#include <cmath>
#include <random>

#include <Eigen/Dense>

#include "solver/lcp/lcp.h"

namespace lcs::lcp_test {

inline Eigen::MatrixXd random_matrix(std::mt19937& rng, int n, int m) {
  std::normal_distribution<double> g(0.0, 1.0);
  Eigen::MatrixXd A(n, m);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) A(i, j) = g(rng);
  return A;
}

inline Eigen::VectorXd random_vector(std::mt19937& rng, int n) { return random_matrix(rng, n, 1); }

// Symmetric positive definite.
inline Eigen::MatrixXd random_spd(std::mt19937& rng, int n) {
  Eigen::MatrixXd A = random_matrix(rng, n, n);
  return A * A.transpose() + 0.1 * Eigen::MatrixXd::Identity(n, n);
}

// Nonsymmetric, strictly row diagonally dominant with positive diagonal: a P-matrix.
inline Eigen::MatrixXd random_p_matrix(std::mt19937& rng, int n) {
  Eigen::MatrixXd A = random_matrix(rng, n, n);
  std::uniform_real_distribution<double> u(0.1, 1.0);
  for (int i = 0; i < n; ++i) {
    A(i, i) = 0.0;
    A(i, i) = A.row(i).cwiseAbs().sum() + u(rng);
  }
  return A;
}

// Skew-symmetric plus positive semidefinite (rank r): monotone, copositive plus.
inline Eigen::MatrixXd random_monotone(std::mt19937& rng, int n, int r) {
  Eigen::MatrixXd K = random_matrix(rng, n, n);
  Eigen::MatrixXd P = random_matrix(rng, n, r);
  return (K - K.transpose()) + P * P.transpose();
}

// q with a known ("planted") solution z0: z0 >= 0, w0 >= 0, z0 ⟂ w0, q = w0 - M z0.
// Each index is active with probability p_active; a few indices are degenerate (both zero)
// when degenerate = true.
struct Planted {
  Eigen::VectorXd q, z, w;
};
inline Planted planted(std::mt19937& rng, const Eigen::MatrixXd& M, double p_active,
                       bool degenerate = false) {
  const int n = static_cast<int>(M.rows());
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Planted p;
  p.z = Eigen::VectorXd::Zero(n);
  p.w = Eigen::VectorXd::Zero(n);
  for (int i = 0; i < n; ++i) {
    double r = u(rng);
    if (degenerate && r < 0.15) continue;  // z_i = w_i = 0
    if (u(rng) < p_active) p.z(i) = 0.1 + u(rng);
    else p.w(i) = 0.1 + u(rng);
  }
  p.q = p.w - M * p.z;
  return p;
}

// Scale-free residual: complementarity and sign violations of z measured against |z|_inf and
// of w_i against the magnitude of the terms summed into it, |q_i| + sum_j |M_ij z_j|.
inline double relative_residual(const Eigen::MatrixXd& M, const Eigen::VectorXd& q,
                                const Eigen::VectorXd& z) {
  Eigen::VectorXd w = M * z + q;
  Eigen::VectorXd ws = q.cwiseAbs() + M.cwiseAbs() * z.cwiseAbs();
  double zs = std::max(z.cwiseAbs().maxCoeff(), 1e-300);
  double r = 0.0;
  for (int i = 0; i < z.size(); ++i) {
    double wsi = std::max(ws(i), 1e-300);
    double zi = z(i) / zs, wi = w(i) / wsi;
    r = std::max({r, -zi, -wi, std::abs(std::min(zi, wi))});
  }
  return r;
}

// Absolute-residual tolerance appropriate for a problem of this scale.
inline double abs_tol(const Eigen::MatrixXd& M, const Eigen::VectorXd& q, const Eigen::VectorXd& z,
                      double rel = 1e-9) {
  double s = q.cwiseAbs().maxCoeff() + M.cwiseAbs().maxCoeff() * z.cwiseAbs().maxCoeff();
  return rel * std::max(s, 1.0);
}

}  // namespace lcs::lcp_test

namespace lcs::lcp_test {

// Largest |w_i - (M z + q)_i| relative to the magnitude of the terms summed into w_i.
inline double w_mismatch(const Eigen::MatrixXd& M, const Eigen::VectorXd& q,
                         const Eigen::VectorXd& z, const Eigen::VectorXd& w) {
  Eigen::VectorXd ws = q.cwiseAbs() + M.cwiseAbs() * z.cwiseAbs();
  double r = 0.0;
  for (int i = 0; i < q.size(); ++i)
    r = std::max(r, std::abs(w(i) - (M.row(i).dot(z) + q(i))) / std::max(ws(i), 1e-300));
  return r;
}

// Small nonnegative integer matrices with a positive diagonal (strictly copositive) and integer
// q in [-2, 1]: full of ties in the minimum-ratio test, the degenerate case Lemke must survive.
struct IntegerProblem {
  Eigen::MatrixXd M;
  Eigen::VectorXd q;
};
inline IntegerProblem random_degenerate_integer_problem(std::mt19937& rng, int n) {
  std::uniform_int_distribution<int> d(0, 3), qd(-2, 1);
  IntegerProblem p{Eigen::MatrixXd(n, n), Eigen::VectorXd(n)};
  for (int i = 0; i < n; ++i) {
    p.q(i) = qd(rng);
    for (int j = 0; j < n; ++j) p.M(i, j) = d(rng);
    if (p.M(i, i) == 0) p.M(i, i) = 1;
  }
  return p;
}

}  // namespace lcs::lcp_test
