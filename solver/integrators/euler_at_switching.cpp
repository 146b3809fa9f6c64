#include "solver/integrators/euler_at_switching.h"

#include <algorithm>

#include "solver/integrators/theta_method.h"

namespace lcs {

bool mode_changed(const Eigen::Ref<const Eigen::VectorXd>& z_a, const Eigen::Ref<const Eigen::VectorXd>& z_b) {
  if (z_a.size() != z_b.size()) return true;
  if (z_a.size() == 0) return false;
  const double floor = kConductingFraction * std::max(z_a.cwiseAbs().maxCoeff(), z_b.cwiseAbs().maxCoeff());
  for (Eigen::Index i = 0; i < z_a.size(); ++i)
    if ((z_a(i) > floor) != (z_b(i) > floor)) return true;
  return false;
}

bool steps_diverge(const Eigen::VectorXd& x0, const Eigen::VectorXd& x, const Eigen::VectorXd& x_euler) {
  if (x0.size() == 0) return false;
  const double apart = (x - x_euler).cwiseAbs().maxCoeff();
  const double moved = (x - x0).cwiseAbs().maxCoeff() + (x_euler - x0).cwiseAbs().maxCoeff();
  return apart > kDivergence * moved;
}

EulerAtSwitching::EulerAtSwitching(const LcsProblem& model, bool sparse, bool step_after)
    : euler_(std::make_unique<ThetaMethod>(model, 1.0, sparse)), step_after_(step_after) {}

EulerAtSwitching::~EulerAtSwitching() = default;

void EulerAtSwitching::remember(const Eigen::VectorXd& x, const Eigen::VectorXd& z) {
  x_before_ = x;  // no allocation after the first step: the sizes do not change
  z_before_ = z;
}

bool EulerAtSwitching::replace_switching_step(double t, double h, Eigen::VectorXd& x, Eigen::VectorXd& z,
                                              bool switched_inside) {
  if (!switched_inside && !mode_changed(z_before_, z)) return false;
  x_euler_ = x_before_;
  z_euler_ = z_before_;
  euler_->guess_from_given_mode();  // where Euler's LCP has several solutions: the continuous one
  euler_->Step(t, h, x_euler_, z_euler_);
  if (!mode_changed(z, z_euler_) && !steps_diverge(x_before_, x, x_euler_)) return false;
  x = x_euler_;
  z = z_euler_;
  ++taken_;
  step_after_due_ = step_after_;
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
