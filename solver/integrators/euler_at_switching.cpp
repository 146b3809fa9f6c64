#include "solver/integrators/euler_at_switching.h"

#include <algorithm>
#include <cmath>

#include "solver/integrators/theta_method.h"
#include "solver/model/conduction_rates.h"

namespace lcs {

namespace {

double conducting_floor(const Eigen::VectorXd& z_a, const Eigen::VectorXd& z_b) {
  const double a = z_a.size() > 0 ? z_a.cwiseAbs().maxCoeff() : 0.0;
  const double b = z_b.size() > 0 ? z_b.cwiseAbs().maxCoeff() : 0.0;
  return kConductingFraction * std::max(a, b);
}

// A tree diode's pair (PairInfo::voltage_type) has z the reverse-voltage margin and w the current:
// z > 0 is blocking, and the rate formula says nothing of its conduction. Left out of the gate
// (rate 0): a diode in series with an inductor (D_ii = 0) counted as infinitely stiff and had
// resonant charging's turn-off replaced (18.4772 V where theta's own step gave 18.5822, event
// 18.5727).
Eigen::VectorXd without_tree_diodes(const LcsProblem& model, Eigen::VectorXd r) {
  const std::vector<PairInfo>& pairs = model.pairs();
  if (static_cast<Eigen::Index>(pairs.size()) != r.size()) return r;
  for (Eigen::Index i = 0; i < r.size(); ++i)
    if (pairs[i].voltage_type) r(i) = 0;
  return r;
}

}  // namespace

bool mode_changed(const Eigen::VectorXd& z_a, const Eigen::VectorXd& z_b) {
  if (z_a.size() != z_b.size()) return true;
  const double floor = conducting_floor(z_a, z_b);
  for (Eigen::Index i = 0; i < z_a.size(); ++i)
    if ((z_a(i) > floor) != (z_b(i) > floor)) return true;
  return false;
}

bool steps_diverge(const Eigen::VectorXd& x0, const Eigen::VectorXd& x, const Eigen::VectorXd& x_euler) {
  for (Eigen::Index i = 0; i < x0.size(); ++i) {
    const double apart = std::abs(x(i) - x_euler(i));
    const double moved = std::abs(x(i) - x0(i)) + std::abs(x_euler(i) - x0(i));
    const double size = std::max({std::abs(x0(i)), std::abs(x(i)), std::abs(x_euler(i))});
    if (apart > kDivergence * moved && apart > 1e-3 * size) return true;
  }
  return false;
}

Eigen::VectorXd pair_rates(const LcsProblem& model) {
  if (const std::shared_ptr<const SparseLcs>& s = model.sparse_lcs())
    return without_tree_diodes(model, conduction_rates(*s));
  if (model.dense_deferred()) return Eigen::VectorXd();
  return without_tree_diodes(model, conduction_rates(model.lcs()));
}

EulerAtSwitching::EulerAtSwitching(const LcsProblem& model, double theta, bool sparse)
    : euler_(std::make_unique<ThetaMethod>(model, 1.0, sparse)),
      stiff_bound_(1.0 / (1.0 - theta)),
      rates_(pair_rates(model)) {}

EulerAtSwitching::~EulerAtSwitching() = default;

void EulerAtSwitching::remember(const Eigen::VectorXd& x, const Eigen::VectorXd& z) {
  x_before_ = x;  // no allocation after the first step: the sizes do not change
  z_before_ = z;
}

bool EulerAtSwitching::stiff(double h, const Eigen::VectorXd& z) const {
  if (rates_.size() != z.size()) return true;
  const double floor = conducting_floor(z_before_, z);
  for (Eigen::Index i = 0; i < z.size(); ++i)
    if ((z(i) > floor || z_before_(i) > floor) && h * rates_(i) > stiff_bound_) return true;
  return false;
}

bool EulerAtSwitching::replace_switching_step(double t, double h, Eigen::VectorXd& x, Eigen::VectorXd& z) {
  if (!mode_changed(z_before_, z) || !stiff(h, z)) return false;
  x_euler_ = x_before_;
  z_euler_ = z_before_;
  euler_->guess_from_given_mode();  // where Euler's LCP has several solutions: the continuous one
  euler_->Step(t, h, x_euler_, z_euler_);
  if (!mode_changed(z, z_euler_) && !steps_diverge(x_before_, x, x_euler_)) return false;
  x = x_euler_;
  z = z_euler_;
  ++taken_;
  step_after_due_ = true;
  return true;
}

bool EulerAtSwitching::euler_step_if_due(double t, double h, Eigen::VectorXd& x, Eigen::VectorXd& z) {
  if (!step_after_due_) return false;
  step_after_due_ = false;
  euler_->guess_from_given_mode();
  euler_->Step(t, h, x, z);
  ++taken_;
  return true;
}

void EulerAtSwitching::add_cost_to(StepperStats& s) const {
  const StepperStats e = euler_->stats();
  s.lcp += e.lcp;
  s.sparse += e.sparse;
  s.factorisations += e.factorisations;
  s.sparse_fallbacks += e.sparse_fallbacks;
  s.switching_steps_by_euler += taken_;
}

}  // namespace lcs
