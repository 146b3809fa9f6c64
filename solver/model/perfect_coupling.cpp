#include "solver/model/perfect_coupling.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <utility>

namespace lcs {

namespace {

// Groups of states that Mdyn couples (connected components of its off-diagonal pattern).
std::vector<std::vector<int>> coupled_groups(const Eigen::MatrixXd& M) {
  const int n = static_cast<int>(M.rows());
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  auto root = [&](int a) {
    while (parent[a] != a) a = parent[a] = parent[parent[a]];
    return a;
  };
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j)
      if (M(i, j) != 0 || M(j, i) != 0) parent[root(i)] = root(j);
  std::vector<std::vector<int>> by_root(n);
  for (int i = 0; i < n; ++i) by_root[root(i)].push_back(i);
  std::vector<std::vector<int>> groups;
  for (std::vector<int>& g : by_root)
    if (!g.empty()) groups.push_back(std::move(g));
  return groups;
}

// Which rows of V (a basis of the group's null space, one row per state) become eta: the last
// rows that are independent of those already taken, so the first windings keep the state. A row
// nearly in the span of the taken ones (relative 1e-3) is passed over: N_E stays well conditioned.
std::vector<int> rows_to_eliminate(const Eigen::MatrixXd& V) {
  const int rows = static_cast<int>(V.rows()), dim = static_cast<int>(V.cols());
  const double largest = V.rowwise().norm().maxCoeff();
  std::vector<int> taken;
  Eigen::MatrixXd basis(dim, 0);  // orthonormal basis of the taken rows
  for (int i = rows - 1; i >= 0 && static_cast<int>(taken.size()) < dim; --i) {
    Eigen::VectorXd v = V.row(i).transpose();
    if (basis.cols() > 0) v -= basis * (basis.transpose() * v);
    if (v.norm() <= 1e-3 * largest) continue;
    basis.conservativeResize(Eigen::NoChange, basis.cols() + 1);
    basis.col(basis.cols() - 1) = v.normalized();
    taken.push_back(i);
  }
  if (static_cast<int>(taken.size()) < dim) {  // every row nearly dependent: the best-conditioned
    Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(V.transpose());
    taken.clear();
    for (int k = 0; k < dim; ++k) taken.push_back(static_cast<int>(qr.colsPermutation().indices()(k)));
    std::sort(taken.begin(), taken.end());
    return taken;
  }
  std::reverse(taken.begin(), taken.end());
  return taken;
}

}  // namespace

FluxReduction flux_reduction(const Eigen::MatrixXd& Mdyn, const Eigen::VectorXd& size,
                             const std::vector<bool>& may_be_flux_free) {
  const int n = static_cast<int>(Mdyn.rows());
  FluxReduction out;
  for (int j = 0; j < n; ++j)
    if (!(size(j) > 0)) return out;  // not an inductance matrix; the caller's check reports it
  std::vector<std::pair<int, Eigen::VectorXd>> columns;  // (state eliminated, null vector)
  for (const std::vector<int>& group : coupled_groups(Mdyn)) {
    const int g = static_cast<int>(group.size());
    if (std::none_of(group.begin(), group.end(), [&](int j) { return may_be_flux_free[j]; })) continue;
    Eigen::VectorXd d(g);  // scaled to unit size: the eigenvalues compare with 1
    for (int a = 0; a < g; ++a) d(a) = 1 / std::sqrt(size(group[a]));
    Eigen::MatrixXd scaled(g, g);
    for (int a = 0; a < g; ++a)
      for (int b = 0; b < g; ++b) scaled(a, b) = d(a) * Mdyn(group[a], group[b]) * d(b);
    Eigen::MatrixXd V;  // the null space in scaled coordinates
    if (g == 1) {       // a state alone: flux-free only when its own terms cancel
      if (std::abs(scaled(0, 0)) > kFluxFreeTolerance) continue;
      V = Eigen::MatrixXd::Ones(1, 1);
    } else {
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(scaled);
      std::vector<int> null_cols;
      for (int a = 0; a < g; ++a)
        if (std::abs(eig.eigenvalues()(a)) <= kFluxFreeTolerance) null_cols.push_back(a);
      if (null_cols.empty()) continue;
      V.resize(g, null_cols.size());
      for (size_t c = 0; c < null_cols.size(); ++c) V.col(c) = eig.eigenvectors().col(null_cols[c]);
    }
    const std::vector<int> elim = rows_to_eliminate(V);
    Eigen::MatrixXd Nx = d.asDiagonal() * V;  // back to x: Mdyn (D V) = 0
    Eigen::MatrixXd NE(elim.size(), Nx.cols());
    for (size_t a = 0; a < elim.size(); ++a) NE.row(a) = Nx.row(elim[a]);
    Nx = Nx * NE.inverse();  // now eta = x_eliminated
    const double big = Nx.cwiseAbs().maxCoeff();
    for (size_t c = 0; c < elim.size(); ++c) {
      Eigen::VectorXd col = Eigen::VectorXd::Zero(n);
      for (int a = 0; a < g; ++a) col(group[a]) = std::abs(Nx(a, c)) <= 1e-14 * big ? 0.0 : Nx(a, c);
      for (size_t b = 0; b < elim.size(); ++b) col(group[elim[b]]) = b == c ? 1.0 : 0.0;
      columns.emplace_back(group[elim[c]], col);
    }
  }
  if (columns.empty()) return out;
  std::sort(columns.begin(), columns.end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<bool> leaves(n, false);
  out.N.resize(n, columns.size());
  for (size_t c = 0; c < columns.size(); ++c) {
    out.N.col(c) = columns[c].second;
    out.eliminated.push_back(columns[c].first);
    leaves[columns[c].first] = true;
  }
  for (int j = 0; j < n; ++j)
    if (!leaves[j]) out.kept.push_back(j);
  out.T = Eigen::MatrixXd::Zero(n, out.kept.size());
  for (size_t j = 0; j < out.kept.size(); ++j) out.T(out.kept[j], j) = 1;
  return out;
}

bool substitute_flux_free(const FluxReduction& reduction, const Eigen::MatrixXd& R, int n,
                          Eigen::MatrixXd& Cmap) {
  const Eigen::MatrixXd& N = reduction.N;
  const int r = static_cast<int>(reduction.kept.size()), e = static_cast<int>(N.cols());
  const int rest = static_cast<int>(R.cols()) - n;
  const Eigen::MatrixXd Rx = R.leftCols(n);
  const Eigen::MatrixXd S = N.transpose() * Rx * N;
  // Singular against the size S would have without cancellation, |N|^T |Rx| |N|.
  const double size = (N.cwiseAbs().transpose() * Rx.cwiseAbs() * N.cwiseAbs()).maxCoeff();
  if (!(size > 0)) return false;
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(S / size);
  if (!(svd.singularValues().minCoeff() > 1e-10)) return false;
  Eigen::MatrixXd constraint(e, r + rest);  // N^T R [T xi; rest]
  if (r > 0) constraint.leftCols(r) = N.transpose() * Rx * reduction.T;  // r = 0: no state left
  constraint.rightCols(rest) = N.transpose() * R.rightCols(rest);
  const Eigen::MatrixXd eta = -Eigen::FullPivLU<Eigen::MatrixXd>(S).solve(constraint);
  Cmap = Eigen::MatrixXd::Zero(n + rest, r + rest);
  if (r > 0) Cmap.topLeftCorner(n, r) = reduction.T;
  Cmap.topRows(n) += N * eta;
  Cmap.bottomRightCorner(rest, rest).setIdentity();
  return true;
}

}  // namespace lcs
