#include "solver/model/klu_factor.h"

#include <klu.h>

namespace lcs {

struct KluFactor::Handles {
  klu_common common;
  klu_symbolic* symbolic = nullptr;
  klu_numeric* numeric = nullptr;
};

KluFactor::KluFactor(const Eigen::SparseMatrix<double>& matrix)
    : handles_(std::make_unique<Handles>()), n_(static_cast<int>(matrix.rows())) {
  Eigen::SparseMatrix<double> a = matrix;
  a.makeCompressed();
  Handles& h = *handles_;
  klu_defaults(&h.common);
  if (n_ == 0 || a.nonZeros() == 0) return;  // empty: singular (KLU's analysis refuses it too)
  h.symbolic = klu_analyze(n_, a.outerIndexPtr(), a.innerIndexPtr(), &h.common);
  if (!h.symbolic) return;
  h.numeric = klu_factor(a.outerIndexPtr(), a.innerIndexPtr(), a.valuePtr(), h.symbolic, &h.common);
  numeric_ = h.numeric;
}

KluFactor::~KluFactor() {
  Handles& h = *handles_;
  if (h.numeric) klu_free_numeric(&h.numeric, &h.common);
  if (h.symbolic) klu_free_symbolic(&h.symbolic, &h.common);
}

Eigen::VectorXd KluFactor::solve(Eigen::VectorXd rhs) const {
  Handles& h = *handles_;
  klu_solve(h.symbolic, h.numeric, n_, 1, rhs.data(), &h.common);
  return rhs;
}

long KluFactor::factor_entries() const {
  const klu_numeric* numeric = handles_->numeric;
  return numeric ? static_cast<long>(numeric->lnz) + static_cast<long>(numeric->unz) : 0;
}

}  // namespace lcs
