#include "solver/integrators/theta_method.h"
#include "solver/model/empty_safe.h"

#include "solver/integrators/descriptor_start.h"
#include "solver/integrators/start_complementarity.h"
#include "solver/model/dense_budget.h"
#include "solver/model/sparse_lcs.h"
#include "solver/model/numerical_failure.h"

namespace lcs {

struct ThetaMethod::StepFactors {
  // x_free = Phi x + Pz z + Pu0 u + Pu1 u+;  x+ = x_free + WB z+;  q = C x_free + F u+.
  Eigen::MatrixXd Phi, Pz, Pu0, Pu1, WB;
  Eigen::MatrixXd CPhi, CPz, CPu0, CPu1F;
  std::unique_ptr<LcpWarmSolver> lcp;
};

struct ThetaMethod::SparseStep {
  std::unique_ptr<SparseActiveSetLcp> lcp;
  bool fresh = true;  // no step taken yet: the last mode is its first guess
};

ThetaMethod::ThetaMethod(const LcsProblem& model, double theta, bool sparse, int descriptor_pairs,
                         bool euler_at_switching)
    : TimeStepper(model), theta_(theta) {
  if (sparse && !model.has_history()) sparse_lcs_ = model.sparse_lcs();
  if (sparse && model.pair_count() >= descriptor_pairs) descriptor_ = model.sparse_descriptor();
  if (descriptor_) stats_.descriptor_unknowns = descriptor_->unknowns();
  if (theta < 1 && euler_at_switching)
    switching_ = std::make_unique<EulerAtSwitching>(model, theta, sparse);
}

ThetaMethod::SparseStep* ThetaMethod::sparse_step(double h) {
  auto it = sparse_cache_.find(h);
  if (it != sparse_cache_.end()) return it->second.get();
  const SparseLcs& s = *sparse_lcs_;
  const int n = static_cast<int>(s.A.rows());
  SparseActiveSetLcp::Sparse I(n, n);
  I.setIdentity();
  auto step = std::make_unique<SparseStep>();
  step->lcp = std::make_unique<SparseActiveSetLcp>(
      SparseActiveSetLcp::Sparse(I - h * theta_ * s.A), SparseActiveSetLcp::Sparse(-h * theta_ * s.B),
      s.C, s.D);
  step->lcp->set_warm_only(model_.has_transfer_pairs());
  ++stats_.factorisations;
  return sparse_cache_.emplace(h, std::move(step)).first->second.get();
}

ThetaMethod::~ThetaMethod() = default;

ThetaMethod::StepFactors& ThetaMethod::factors(double h) {
  auto it = cache_.find(h);
  if (it != cache_.end()) return *it->second;
  const Lcs& s = model_.lcs();
  const int n = s.states();
  const double theta = theta_;
  auto f = std::make_unique<StepFactors>();
  Eigen::MatrixXd I = Eigen::MatrixXd::Identity(n, n);
  Eigen::PartialPivLU<Eigen::MatrixXd> W(I - h * theta * s.A);
  const double explicit_part = h * (1 - theta);
  f->Phi = n > 0 ? solve_or_empty(W, I + explicit_part * s.A) : Eigen::MatrixXd(0, 0);
  f->Pz = n > 0 ? solve_or_empty(W, explicit_part * s.B) : Eigen::MatrixXd(0, s.pairs());
  f->Pu0 = n > 0 ? solve_or_empty(W, explicit_part * s.E) : Eigen::MatrixXd(0, s.inputs());
  f->Pu1 = n > 0 ? solve_or_empty(W, h * theta * s.E) : Eigen::MatrixXd(0, s.inputs());
  f->WB = n > 0 ? solve_or_empty(W, h * theta * s.B) : Eigen::MatrixXd(0, s.pairs());
  f->CPhi = s.C * f->Phi;
  f->CPz = s.C * f->Pz;
  f->CPu0 = s.C * f->Pu0;
  f->CPu1F = s.C * f->Pu1 + s.F;
  f->lcp = std::make_unique<LcpWarmSolver>(s.D + s.C * f->WB);
  if (model_.has_transfer_pairs()) f->lcp->watch_multiplicity();
  ++stats_.factorisations;
  return *cache_.emplace(h, std::move(f)).first->second;
}

void ThetaMethod::DoStart(double t0, double h_run, const Eigen::VectorXd& x, Eigen::VectorXd& z) {
  // Only theta < 1 reuses z_n; for theta = 1 it is just the t0 output.
  if (descriptor_ && descriptor_start_z(model_, *descriptor_, t0, x, stats_, z)) return;
  z = consistent_start_z(model_, t0, h_run, x, stats_, z, &multistability_);
}

void ThetaMethod::DoStep(double t, double h, Eigen::VectorXd& x, Eigen::VectorXd& z) {
  if (!switching_) return theta_step(t, h, x, z);
  if (switching_->euler_step_if_due(t, h, x, z)) {
    resume_ = true;
    return;
  }
  switching_->remember(x, z);
  theta_step(t, h, x, z);
  resume_ = switching_->replace_switching_step(t, h, x, z);
}

void ThetaMethod::theta_step(double t, double h, Eigen::VectorXd& x, Eigen::VectorXd& z) {
  const bool resume = resume_;
  resume_ = false;
  if (sparse_lcs_) {
    // K x+ + L z+ = a: x+ - hθ(A x+ + B z+) = x + h(1-θ)(A x + B z + E u) + hθ E u+.
    SparseStep* step = sparse_step(h);
    if (step->fresh || resume) step->lcp->prefer(z);
    step->fresh = false;
    const SparseLcs& s = *sparse_lcs_;
    u1_ = model_.input_values(t + h);
    a_ = x;
    a_.noalias() += (h * theta_) * (s.E * u1_);
    if (theta_ != 1.0) {
      u0_ = model_.input_values(t);
      const double explicit_part = h * (1 - theta_);
      a_ += explicit_part * (s.A * x + s.B * z);
      a_.noalias() += explicit_part * (s.E * u0_);
    }
    b_.noalias() = s.F * u1_;
    if (step->lcp->solve(a_, b_, y_, zs_, w_)) {
      x = y_;
      z = zs_;
      return;
    }
    ++stats_.sparse_fallbacks;  // the dense LCP and Lemke decide this step
  }
  if (descriptor_) {
    auto found = descriptor_cache_.find(h);
    if (found == descriptor_cache_.end()) {
      found = descriptor_cache_.emplace(h, std::make_unique<DescriptorStep>(*descriptor_, h, theta_)).first;
      ++stats_.factorisations;
    }
    if (resume) found->second->guess_from_given_mode();
    if (found->second->step(model_, t, x, z)) return;
    ++stats_.sparse_fallbacks;
  }
  if (!cache_.count(h) && !dense_within_budget(model_.state_count(), model_.pair_count(), 4))
    throw NumericalFailure(t + h, "the sparse step found no mode, and the dense step LCP that would decide it is "
                                  "not formed: " + dense_budget_reason(model_.state_count(), model_.pair_count(), 4));
  StepFactors& f = factors(h);
  u1_ = model_.input_values(t + h);
  q_ = f.CPhi * x + f.CPu1F * u1_;
  if (theta_ != 1.0) {
    u0_ = model_.input_values(t);
    q_ += f.CPz * z + f.CPu0 * u0_;
  }
  f.lcp->prefer(z, resume);  // a new step size's solver (or after an Euler step) starts from z's mode
  const LcpSolution& sol = f.lcp->solve(q_);
  multistability_.check(*f.lcp, model_, t + h);
  if (sol.status != LcpStatus::Solved)
    throw NumericalFailure(t + h, std::string("the step's LCP has no solution (Lemke: ") +
                                      lcp_status_name(sol.status) + ")");
  Eigen::VectorXd x_next = f.Phi * x + f.Pu1 * u1_ + f.WB * sol.z;
  if (theta_ != 1.0) x_next += f.Pz * z + f.Pu0 * u0_;
  x = std::move(x_next);
  z = sol.z;
}

StepperStats ThetaMethod::stats() const {
  StepperStats s = stats_;  // s.lcp holds the start LCP (consistent_start_z)
  for (const auto& [h, f] : cache_) s.lcp += f->lcp->stats();
  for (const auto& [h, step] : sparse_cache_) s.sparse += step->lcp->stats();
  for (const auto& [h, step] : descriptor_cache_) s.sparse += step->stats();
  if (switching_) switching_->add_cost_to(s);
  return s;
}

}  // namespace lcs
