#include "solver/model/pair_blocks.h"

#include <cmath>
#include <map>
#include <numeric>

#include "solver/model/klu_factor.h"

namespace lcs {

namespace {

using Sparse = Eigen::SparseMatrix<double>;

struct UnionFind {
  std::vector<int> parent;
  explicit UnionFind(int size) : parent(size) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int a) {
    while (parent[a] != a) a = parent[a] = parent[parent[a]];
    return a;
  }
  void join(int a, int b) {
    a = find(a);
    b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
};

}  // namespace

std::vector<std::vector<int>> coupled_pair_blocks(const Sparse& K, const Sparse& L, const Sparse& P,
                                                  const Sparse& Q) {
  const int n = static_cast<int>(K.rows()), m = static_cast<int>(Q.rows());
  UnionFind sets(n + m);  // unknowns 0 .. n-1 of K, then the pairs
  for (int c = 0; c < K.outerSize(); ++c)
    for (Sparse::InnerIterator it(K, c); it; ++it) sets.join(static_cast<int>(it.row()), c);
  for (int j = 0; j < L.outerSize(); ++j)
    for (Sparse::InnerIterator it(L, j); it; ++it) sets.join(static_cast<int>(it.row()), n + j);
  for (int c = 0; c < P.outerSize(); ++c)
    for (Sparse::InnerIterator it(P, c); it; ++it) sets.join(n + static_cast<int>(it.row()), c);
  for (int j = 0; j < Q.outerSize(); ++j)
    for (Sparse::InnerIterator it(Q, j); it; ++it) sets.join(n + static_cast<int>(it.row()), n + j);
  std::map<int, int> block_of_root;
  std::vector<std::vector<int>> blocks;
  for (int i = 0; i < m; ++i) {
    const auto [found, fresh] = block_of_root.emplace(sets.find(n + i), static_cast<int>(blocks.size()));
    if (fresh) blocks.emplace_back();
    blocks[found->second].push_back(i);
  }
  return blocks;
}

struct SchurBlocks::Factor {
  explicit Factor(const Sparse& K) : lu(K) {}
  KluFactor lu;
};

std::optional<SchurBlocks> SchurBlocks::make(const Sparse& K, const Sparse& L, const Sparse& P,
                                             const Sparse& Q) {
  SchurBlocks s;
  if (K.rows() > 0) {
    auto f = std::make_shared<Factor>(K);
    if (!f->lu.ok()) return std::nullopt;
    s.factor_ = std::move(f);
  }
  s.L_ = L;
  s.P_ = P;
  s.Q_ = Q;
  return s;
}

Eigen::VectorXd SchurBlocks::column(int j, const std::vector<int>& rows) const {
  Eigen::VectorXd out(static_cast<Eigen::Index>(rows.size()));
  Eigen::VectorXd x;
  if (factor_) x = factor_->lu.solve(Eigen::VectorXd(L_.col(j)));
  for (size_t k = 0; k < rows.size(); ++k) {
    const int i = rows[k];
    double v = Q_.coeff(i, j);
    if (factor_)
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(P_, i); it; ++it)
        v -= it.value() * x(it.col());
    out(static_cast<Eigen::Index>(k)) = v;
  }
  return out;
}

Eigen::MatrixXd SchurBlocks::block(const std::vector<int>& block) const {
  const Eigen::Index b = static_cast<Eigen::Index>(block.size());
  Eigen::MatrixXd out(b, b);
  for (Eigen::Index k = 0; k < b; ++k) out.col(k) = column(block[k], block);
  return out;
}

double SchurBlocks::dominance_work(const std::vector<int>& block) const {
  const double b = static_cast<double>(block.size());
  double rows = 0;  // entries of P in the block's rows: one column's restriction reads them all
  for (int i : block) rows += static_cast<double>(P_.outerIndexPtr()[i + 1] - P_.outerIndexPtr()[i]) + 1;
  const double solve = factor_ ? 2.0 * static_cast<double>(factor_->lu.factor_entries()) + static_cast<double>(L_.rows()) : 0.0;
  return b * (solve + rows);
}

bool SchurBlocks::symmetric_part_dominant(const std::vector<int>& block) const {
  const Eigen::Index b = static_cast<Eigen::Index>(block.size());
  Eigen::VectorXd diagonal(b), off = Eigen::VectorXd::Zero(b);  // off_i: sum |M_ij| + |M_ji|
  for (Eigen::Index k = 0; k < b; ++k) {
    const Eigen::VectorXd col = column(block[k], block);
    diagonal(k) = col(k);
    for (Eigen::Index i = 0; i < b; ++i) {
      if (i == k) continue;
      off(i) += std::abs(col(i));
      off(k) += std::abs(col(i));
    }
  }
  // The margin of the dense test's positive_definite (p_matrix.cpp): rounding is not dominance.
  for (Eigen::Index i = 0; i < b; ++i)
    if (!(diagonal(i) - 0.5 * off(i) > 1e-9 * std::abs(diagonal(i)))) return false;
  return true;
}

}  // namespace lcs
