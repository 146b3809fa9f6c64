// The LCP matrix of a sparse system, M = Q - P K^-1 L (the operating point's D - C A^-1 B, a
// time step's D + h C (I - h A)^-1 B), examined without forming it whole (issue 12): a circuit
// of many diodes is often many small circuits that meet only at sources, and M is then block
// diagonal. M_ij can be nonzero only if Q_ij is, or pair i's row of P and pair j's column of L
// meet one connected component of K's graph (K^-1 is block diagonal over those components). So
// the pairs split into blocks that M never couples, and M is a P-matrix exactly when every
// block is (a principal minor of a block diagonal matrix is the product of its blocks' minors;
// Stewart 2.2).
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include <Eigen/Dense>
#include <Eigen/Sparse>

namespace lcs {

// The blocks of pairs (0 .. m-1) that M couples structurally, each sorted, in order of their
// first pair. K: n x n, L: n x m, P: m x n, Q: m x m.
std::vector<std::vector<int>> coupled_pair_blocks(const Eigen::SparseMatrix<double>& K,
                                                  const Eigen::SparseMatrix<double>& L,
                                                  const Eigen::SparseMatrix<double>& P,
                                                  const Eigen::SparseMatrix<double>& Q);

// M = Q - P K^-1 L one block at a time, by sparse solves with one factorisation of K: a block
// of b pairs costs b solves, O(b nnz(LU)), never the m x m matrix.
class SchurBlocks {
 public:
  // Nullopt when K is singular (the dense path decides then).
  static std::optional<SchurBlocks> make(const Eigen::SparseMatrix<double>& K,
                                         const Eigen::SparseMatrix<double>& L,
                                         const Eigen::SparseMatrix<double>& P,
                                         const Eigen::SparseMatrix<double>& Q);
  // Column j of M, restricted to the rows `rows`.
  Eigen::VectorXd column(int j, const std::vector<int>& rows) const;
  // M restricted to one block (rows and columns `block`).
  Eigen::MatrixXd block(const std::vector<int>& block) const;
  // Whether the block's symmetric part (M + M^T)/2 has a positive diagonal and is strictly
  // diagonally dominant, M_ii > (sum_j!=i |M_ij| + |M_ji|) / 2: then it is positive definite
  // (Gershgorin) and the block a P-matrix. O(b) memory: columns are summed as they come.
  bool symmetric_part_dominant(const std::vector<int>& block) const;
  // What symmetric_part_dominant(block) costs, in entry operations: b solves with K's factors
  // (twice their entries each, plus the solution's n) and the b x b products with P's rows.
  // A block coupled end to end (a clamped ladder) makes it O(b (n + nnz(LU)) + b nnz(P)).
  double dominance_work(const std::vector<int>& block) const;

 private:
  SchurBlocks() = default;
  struct Factor;
  std::shared_ptr<const Factor> factor_;
  Eigen::SparseMatrix<double> L_, Q_;
  Eigen::SparseMatrix<double, Eigen::RowMajor> P_;
};

}  // namespace lcs
