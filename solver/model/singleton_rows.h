// Solving E X = R by substitution where E's rows can be ordered into a triangle.
//
// Most static equations of a circuit hold one static unknown once the others are known: a link
// diode's current is its z, a link resistor's current is its loop voltage (tree capacitors and
// sources) over R, a source's own value. Taking such rows one at a time (a row with a single
// unknown left determines it; the rows it appears in then lose one) is the singleton pass of a
// block-triangular ordering (Duff and Reid's, as KLU's BTF does): for ladders, rectifier banks and
// multipliers it solves every row, in O(nnz(X)) and with no fill beyond X's own, where an LU
// solve with thousands of right-hand-side columns costs O(columns * nnz(LU)).
#pragma once

#include <Eigen/Sparse>

namespace lcs {

// X = E^-1 R when the singleton rows determine every unknown (E square; each row's largest entry
// is its unit, so the pivots are the rows' own coefficients). False when a coupled core is left
// (then X is unspecified and an LU decides).
bool solve_by_singleton_rows(const Eigen::SparseMatrix<double>& E, const Eigen::SparseMatrix<double>& R,
                             Eigen::SparseMatrix<double>& X);

}  // namespace lcs
