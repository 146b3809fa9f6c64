#include "solver/model/row_product.h"

#include <algorithm>
#include <stdexcept>
#include <vector>

namespace lcs {

Eigen::SparseMatrix<double, Eigen::RowMajor> row_product(const Eigen::SparseMatrix<double, Eigen::RowMajor>& A,
                                                         const Eigen::SparseMatrix<double, Eigen::RowMajor>& B) {
  using RowSparse = Eigen::SparseMatrix<double, Eigen::RowMajor>;
  if (A.cols() != B.rows()) throw std::logic_error("row_product: inner sizes differ");
  const Eigen::Index rows = A.rows(), cols = B.cols();
  std::vector<double> accumulator(cols, 0.0);
  std::vector<Eigen::Index> mark(cols, -1);
  std::vector<Eigen::Index> pattern;
  // A symbolic pass sizes the result, so the numeric pass writes it in place, once.
  Eigen::Index entries = 0;
  for (Eigen::Index r = 0; r < rows; ++r)
    for (RowSparse::InnerIterator a(A, r); a; ++a)
      for (RowSparse::InnerIterator b(B, a.col()); b; ++b)
        if (mark[b.col()] != r) {
          mark[b.col()] = r;
          ++entries;
        }
  std::fill(mark.begin(), mark.end(), -1);
  RowSparse out(rows, cols);
  out.reserve(entries);
  for (Eigen::Index r = 0; r < rows; ++r) {
    pattern.clear();
    for (RowSparse::InnerIterator a(A, r); a; ++a)
      for (RowSparse::InnerIterator b(B, a.col()); b; ++b) {
        const Eigen::Index c = b.col();
        if (mark[c] != r) {
          mark[c] = r;
          pattern.push_back(c);
        }
        accumulator[c] += a.value() * b.value();
      }
    std::sort(pattern.begin(), pattern.end());
    out.startVec(r);
    for (Eigen::Index c : pattern) {
      if (accumulator[c] != 0) out.insertBack(r, c) = accumulator[c];
      accumulator[c] = 0;
    }
  }
  out.finalize();
  return out;
}

}  // namespace lcs
