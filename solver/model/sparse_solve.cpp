#include "solver/model/sparse_solve.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <Eigen/SparseLU>

#include "solver/model/empty_safe.h"
#include "solver/model/singleton_rows.h"
#include "solver/model/structural_zeros.h"

namespace lcs {

namespace {

bool solve_dense(const SparseMatrixD& E, const Eigen::VectorXd& row_scale, const Eigen::MatrixXd& R,
                 bool clear_structural, Eigen::MatrixXd& X) {
  const Eigen::MatrixXd Ed(E);
  Eigen::FullPivLU<Eigen::MatrixXd> lu(row_scale.asDiagonal() * Ed);
  if (!lu.isInvertible()) return false;
  X = solve_or_empty(lu, row_scale.asDiagonal() * R);
  if (clear_structural) clear_structural_zeros(Ed, R, X);
  return true;
}

// 1 / (the largest entry of each row) (1 for an empty row).
Eigen::VectorXd unit_row_scale(const SparseMatrixD& E) {
  Eigen::VectorXd row_scale = Eigen::VectorXd::Zero(E.rows());
  for (int k = 0; k < E.outerSize(); ++k)
    for (SparseMatrixD::InnerIterator it(E, k); it; ++it)
      row_scale(it.row()) = std::max(row_scale(it.row()), std::abs(it.value()));
  for (Eigen::Index r = 0; r < E.rows(); ++r) row_scale(r) = row_scale(r) > 0 ? 1.0 / row_scale(r) : 1.0;
  return row_scale;
}

double max_abs(const SparseMatrixD& S) {
  double out = 0;
  for (int k = 0; k < S.outerSize(); ++k)
    for (SparseMatrixD::InnerIterator it(S, k); it; ++it) out = std::max(out, std::abs(it.value()));
  return out;
}

bool all_finite(const SparseMatrixD& S) {
  for (int k = 0; k < S.outerSize(); ++k)
    for (SparseMatrixD::InnerIterator it(S, k); it; ++it)
      if (!std::isfinite(it.value())) return false;
  return true;
}

// The sparse counterpart of clear_structural_zeros: the pattern of E^-1 R is read off one solve
// with random values on E's and R's patterns (Schwartz-Zippel, as there); an entry of X is cleared
// only where that random solve is negligible in its column and X's entry is negligible too.
void clear_structural_zeros_sparse(const SparseMatrixD& E, const SparseMatrixD& R, SparseMatrixD& X) {
  std::mt19937_64 rng(0x5eed);
  std::uniform_real_distribution<double> magnitude(1.0, 2.0);
  auto draw = [&] {
    const double sign = rng() & 1 ? 1.0 : -1.0;  // drawn first, as gcc and clang did (checked)
    return sign * magnitude(rng);
  };
  SparseMatrixD random = E, random_rhs = R;
  for (int k = 0; k < random.outerSize(); ++k)
    for (SparseMatrixD::InnerIterator it(random, k); it; ++it) it.valueRef() = draw();
  for (int k = 0; k < random_rhs.outerSize(); ++k)
    for (SparseMatrixD::InnerIterator it(random_rhs, k); it; ++it) it.valueRef() = draw();
  Eigen::SparseLU<SparseMatrixD, Eigen::COLAMDOrdering<int>> lu;
  lu.compute(random);
  if (lu.info() != Eigen::Success) return;
  const SparseMatrixD reach = lu.solve(random_rhs);
  for (int c = 0; c < X.outerSize(); ++c) {
    double reach_scale = 0, column = 0;
    for (SparseMatrixD::InnerIterator it(reach, c); it; ++it) reach_scale = std::max(reach_scale, std::abs(it.value()));
    for (SparseMatrixD::InnerIterator it(X, c); it; ++it) column = std::max(column, std::abs(it.value()));
    SparseMatrixD::InnerIterator r(reach, c);
    for (SparseMatrixD::InnerIterator it(X, c); it; ++it) {
      while (r && r.row() < it.row()) ++r;
      const double reached = r && r.row() == it.row() ? std::abs(r.value()) : 0.0;
      if (reached <= 1e-9 * reach_scale && std::abs(it.value()) <= 1e-9 * column) it.valueRef() = 0;
    }
  }
  X.prune([](const Eigen::Index&, const Eigen::Index&, const double& v) { return v != 0; });
}

// E diagonal (a circuit whose capacitors all sit in the tree: Mdyn = diag(C)): X = E^-1 R entry
// by entry, as the singleton-row substitution would compute it on the scaled system ((s r) /
// (s d), the same rounding), without its copies of an R that can hold O(n^2) entries.
bool solve_diagonal(const SparseMatrixD& E, const Eigen::VectorXd& row_scale, const SparseMatrixD& R,
                    SparseMatrixD& X) {
  Eigen::VectorXd pivot(E.rows());
  for (int k = 0; k < E.outerSize(); ++k) {
    SparseMatrixD::InnerIterator it(E, k);
    if (!it || it.row() != k || it.value() == 0) return false;
    pivot(k) = row_scale(k) * it.value();
    if (++it) return false;
  }
  X = R;
  for (int c = 0; c < X.outerSize(); ++c)
    for (SparseMatrixD::InnerIterator it(X, c); it; ++it)
      it.valueRef() = row_scale(it.row()) * it.value() / pivot(it.row());
  X.prune([](const Eigen::Index&, const Eigen::Index&, const double& v) { return v != 0; });
  return true;
}

}  // namespace

// The size threshold is a choice, not a measurement: small circuits keep the dense results they
// always had, and the circuits where formation cost mattered (hundreds of diodes) take the sparse
// path, where the singleton rows usually leave no LU at all. KLU was not tried.
bool solve_scaled(const SparseMatrixD& E, const SparseMatrixD& R, bool clear_structural,
                  SparseMatrixD& X) {
  const Eigen::Index n = E.rows();
  if (n == 0 || R.cols() == 0) {
    X = SparseMatrixD(n, R.cols());
    return true;
  }
  const Eigen::VectorXd row_scale = unit_row_scale(E);
  if (n < kSparseSolveSize) {
    Eigen::MatrixXd dense;
    if (!solve_dense(E, row_scale, Eigen::MatrixXd(R), clear_structural, dense)) return false;
    X = dense.sparseView();
    return true;
  }
  // |s d| is 1 to rounding: a diagonal amplifies nothing, and a non-finite X is R's own.
  if (solve_diagonal(E, row_scale, R, X) && all_finite(X)) return true;
  const SparseMatrixD scaled = row_scale.asDiagonal() * E;
  const SparseMatrixD Rs = row_scale.asDiagonal() * R;
  if (solve_by_singleton_rows(scaled, Rs, X)) {
    // Substitution combines entries only along the structure's paths: no rounding fill to clear,
    // but a row whose pivot is tiny against the rest of its row amplifies like any triangle does.
    if (all_finite(X) && !(max_abs(X) > 1e12 * std::max(1.0, max_abs(Rs)))) return true;
  }
  Eigen::SparseLU<SparseMatrixD, Eigen::COLAMDOrdering<int>> lu;
  lu.compute(scaled);
  if (lu.info() != Eigen::Success) return false;
  X = lu.solve(Rs);
  X.prune([](const Eigen::Index&, const Eigen::Index&, const double& v) { return v != 0; });
  // As for a dense right-hand side: a numerically singular E goes to the rank-revealing LU.
  const double rs = max_abs(Rs), xs = max_abs(X);
  const double residual = max_abs(SparseMatrixD(scaled * X - Rs));
  if (!all_finite(X) || !(residual <= 1e-9 * std::max(1.0, rs) * std::max(1.0, xs)) || xs > 1e12 * rs) {
    Eigen::MatrixXd dense;
    if (!solve_dense(E, row_scale, Eigen::MatrixXd(R), clear_structural, dense)) return false;
    X = dense.sparseView();
    return true;
  }
  if (clear_structural) clear_structural_zeros_sparse(E, R, X);
  return true;
}

}  // namespace lcs
