#include "solver/model/lcs_problem.h"

#include <algorithm>
#include <limits>

#include "solver/model/dense_budget.h"
#include "solver/model/sparse_lcs.h"


namespace lcs {

Eigen::VectorXd LcsProblem::physical_state(const Eigen::VectorXd& x, double t) const {
  return x + lcs_.Gamma * input_values(t);
}

Eigen::VectorXd LcsProblem::lcs_state(const Eigen::VectorXd& physical, double t) const {
  return physical - lcs_.Gamma * input_values(t);
}

std::vector<double> LcsProblem::waves(double t, const Eigen::VectorXd& x, const Eigen::VectorXd& z) const {
  const Eigen::VectorXd u = input_values(t);
  std::vector<double> out(delayed_.size());
  for (size_t k = 0; k < delayed_.size(); ++k) {
    const DelayedWave& w = delayed_[k];
    out[k] = w.j.dot(u);
    if (x.size() > 0) out[k] += w.g.dot(x);
    if (z.size() > 0) out[k] += w.h.dot(z);
  }
  return out;
}

void LcsProblem::accept(double t, const Eigen::VectorXd& x, const Eigen::VectorXd& z) const {
  if (delayed_.empty()) return;
  history().record(t, waves(t, x, z));
}

void LcsProblem::begin_history(const std::vector<double>& before) const {
  if (delayed_.empty()) return;
  history().reset(before);
}

double LcsProblem::max_step() const { return max_step_; }

int LcsProblem::state_count() const {
  if (dense_formed_) return lcs_.states();
  return deferred_ ? static_cast<int>(deferred_->A.rows()) : static_cast<int>(states_.size());
}

int LcsProblem::pair_count() const {
  if (dense_formed_) return lcs_.pairs();
  return deferred_ ? static_cast<int>(deferred_->D.rows()) : static_cast<int>(pairs_.size());
}

void LcsProblem::form_dense() const {
  // One copy: whoever asks holds at least the matrices themselves (dense_budget.h).
  if (!dense_within_budget(state_count(), pair_count(), 1))
    throw DenseBudgetExceeded(dense_budget_reason(state_count(), pair_count(), 1));
  Lcs& s = lcs_;
  if (!deferred_) {
    deferred_ = make_deferred_();
    s.E = deferred_->E;
    s.F = deferred_->F;
  }
  s.A = Eigen::MatrixXd(deferred_->A);
  s.B = Eigen::MatrixXd(deferred_->B);
  s.C = Eigen::MatrixXd(deferred_->C);
  s.D = Eigen::MatrixXd(deferred_->D);
  dense_formed_ = true;
}

}  // namespace lcs
