// Solving formation's linear systems E X = R with a sparse E and a dense right-hand side.
//
// Formation eliminates the static (resistive) unknowns and inverts the capacitance/inductance
// matrix. Both systems are as sparse as the circuit, but their right-hand sides are dense (one
// column per state, pair and input), so a solve costs O(columns * nnz(LU)), against the O(n^3)
// of a dense factorisation. Below kSparseSolveSize unknowns the dense full-pivoting LU is
// faster and is kept (the results of small circuits do not change); above it Eigen's SparseLU
// (COLAMD ordering) is used, after the singleton rows (singleton_rows.h). KLU was not tried.
#pragma once

#include <Eigen/Dense>
#include <Eigen/Sparse>

namespace lcs {

using SparseMatrixD = Eigen::SparseMatrix<double>;

// Systems with at least this many unknowns take the sparse path (a choice: sparse_solve.cpp).
constexpr int kSparseSolveSize = 96;

// X = E^-1 R with E's rows scaled to unit size first (a 1e16 ohm resistor next to a 1 V source is
// not a singular system), sparse (only exact zeros left out). Entries of X that E's structure
// makes exactly zero are set to 0 (structural_zeros.h) when `clear_structural` is set. Returns
// false when E is singular (X unspecified). E is square; R has E.rows() rows.
bool solve_scaled(const SparseMatrixD& E, const SparseMatrixD& R, bool clear_structural,
                  SparseMatrixD& X);

}  // namespace lcs
