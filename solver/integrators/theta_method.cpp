#include "solver/integrators/theta_method.h"
#include "solver/model/empty_safe.h"

#include "solver/integrators/start_complementarity.h"
#include "solver/model/numerical_failure.h"

namespace lcs {

struct ThetaMethod::StepFactors {
  // x_free = Phi x + Pz z + Pu0 u + Pu1 u+;  x+ = x_free + WB z+;  q = C x_free + F u+.
  Eigen::MatrixXd Phi, Pz, Pu0, Pu1, WB;
  Eigen::MatrixXd CPhi, CPz, CPu0, CPu1F;
  std::unique_ptr<LcpWarmSolver> lcp;
};

ThetaMethod::ThetaMethod(const LcsProblem& model, double theta)
    : TimeStepper(model), theta_(theta) {}

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
  z = consistent_start_z(model_, t0, h_run, x, stats_, z, &multistability_);
}

void ThetaMethod::DoStep(double t, double h, Eigen::VectorXd& x, Eigen::VectorXd& z) {
  StepFactors& f = factors(h);
  u1_ = model_.input_values(t + h);
  q_ = f.CPhi * x + f.CPu1F * u1_;
  if (theta_ != 1.0) {
    u0_ = model_.input_values(t);
    q_ += f.CPz * z + f.CPu0 * u0_;
  }
  f.lcp->prefer(z);  // a new step size's solver starts from the last mode
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
  return s;
}

}  // namespace lcs
