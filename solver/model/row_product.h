// The product of two row-major sparse matrices, row by row (Gustavson's algorithm): each row of
// the result is the sum of the rows of B that a row of A names, gathered in a dense accumulator.
// Formation's branch rows are such products (the loop and cutset maps times the primary
// unknowns' rows), O(N^2) entries on a multiplier; Eigen's row-major product went through
// column-major copies of its operands and result, a third of formation there.
#pragma once

#include <Eigen/Sparse>

namespace lcs {

// A * B, entries that cancel to exactly zero dropped. O(flops + nnz(result) log) time, one
// dense row of B.cols() doubles of workspace.
Eigen::SparseMatrix<double, Eigen::RowMajor> row_product(const Eigen::SparseMatrix<double, Eigen::RowMajor>& A,
                                                         const Eigen::SparseMatrix<double, Eigen::RowMajor>& B);

}  // namespace lcs
