#include "solver/model/singleton_rows.h"

#include <vector>

namespace lcs {

bool solve_by_singleton_rows(const Eigen::SparseMatrix<double>& E, const Eigen::SparseMatrix<double>& R,
                             Eigen::SparseMatrix<double>& X) {
  using RowMajor = Eigen::SparseMatrix<double, Eigen::RowMajor>;
  const int n = static_cast<int>(E.rows());
  const RowMajor Erows = E, Rrows = R;
  std::vector<int> left(n, 0), solved_by(n, -1), queue;
  for (int r = 0; r < n; ++r) {
    for (RowMajor::InnerIterator it(Erows, r); it; ++it)
      if (it.value() != 0) ++left[r];
    if (left[r] == 1) queue.push_back(r);
  }
  std::vector<Eigen::SparseVector<double>> rows(n, Eigen::SparseVector<double>(R.cols()));
  int solved = 0;
  for (size_t q = 0; q < queue.size(); ++q) {
    const int r = queue[q];
    if (left[r] != 1) continue;  // its unknown was taken by another row meanwhile
    int j = -1;
    double pivot = 0;
    for (RowMajor::InnerIterator it(Erows, r); it; ++it)
      if (it.value() != 0 && solved_by[it.col()] < 0) {
        j = static_cast<int>(it.col());
        pivot = it.value();
      }
    Eigen::SparseVector<double> x = Rrows.row(r).transpose();
    for (RowMajor::InnerIterator it(Erows, r); it; ++it)
      if (it.value() != 0 && it.col() != j) x -= it.value() * rows[it.col()];
    rows[j] = x / pivot;
    solved_by[j] = r;
    left[r] = 0;
    ++solved;
    for (Eigen::SparseMatrix<double>::InnerIterator it(E, j); it; ++it)
      if (it.value() != 0 && it.row() != r && --left[it.row()] == 1) queue.push_back(static_cast<int>(it.row()));
  }
  if (solved < n) return false;
  // X by rows, each row freed as it is copied, then once to columns: no triplets (16 bytes an
  // entry, and a multiplier's X holds O(n^2) entries: they were most of its formation's memory).
  Eigen::Index entries = 0;
  for (const Eigen::SparseVector<double>& row : rows) entries += row.nonZeros();
  RowMajor Xrows(n, R.cols());
  Xrows.reserve(entries);
  for (int j = 0; j < n; ++j) {
    Xrows.startVec(j);
    for (Eigen::SparseVector<double>::InnerIterator it(rows[j]); it; ++it)
      if (it.value() != 0) Xrows.insertBack(j, it.index()) = it.value();
    rows[j] = Eigen::SparseVector<double>();
  }
  Xrows.finalize();
  X = Xrows;
  return true;
}

}  // namespace lcs
