#include "solver/integrators/theta_method.h"

#include <algorithm>

#include "solver/model/numerical_failure.h"

namespace lcs {

struct ThetaMethod::StepFactors {
  // x_free = Phi x + Pz z + Pu0 u + Pu1 u+;  x+ = x_free + WB z+;  q = C x_free + F u+.
  Eigen::MatrixXd Phi, Pz, Pu0, Pu1, WB;
  Eigen::MatrixXd CPhi, CPz, CPu0, CPu1F;
  std::unique_ptr<LcpWarmSolver> lcp;
};

ThetaMethod::ThetaMethod(const CircuitModel& model, double theta)
    : TimeStepper(model), theta_(theta) {}

ThetaMethod::~ThetaMethod() = default;

ThetaMethod::StepFactors& ThetaMethod::factors(double h, double theta) {
  auto key = std::make_pair(h, theta);
  auto it = cache_.find(key);
  if (it != cache_.end()) return *it->second;
  const Lcs& s = model_.lcs();
  const int n = s.states();
  auto f = std::make_unique<StepFactors>();
  Eigen::MatrixXd I = Eigen::MatrixXd::Identity(n, n);
  Eigen::PartialPivLU<Eigen::MatrixXd> W(I - h * theta * s.A);
  const double explicit_part = h * (1 - theta);
  f->Phi = n > 0 ? W.solve(I + explicit_part * s.A) : Eigen::MatrixXd(0, 0);
  f->Pz = n > 0 ? W.solve(explicit_part * s.B) : Eigen::MatrixXd(0, s.pairs());
  f->Pu0 = n > 0 ? W.solve(explicit_part * s.E) : Eigen::MatrixXd(0, s.inputs());
  f->Pu1 = n > 0 ? W.solve(h * theta * s.E) : Eigen::MatrixXd(0, s.inputs());
  f->WB = n > 0 ? W.solve(h * theta * s.B) : Eigen::MatrixXd(0, s.pairs());
  f->CPhi = s.C * f->Phi;
  f->CPz = s.C * f->Pz;
  f->CPu0 = s.C * f->Pu0;
  f->CPu1F = s.C * f->Pu1 + s.F;
  f->lcp = std::make_unique<LcpWarmSolver>(s.D + s.C * f->WB);
  ++stats_.factorisations;
  return *cache_.emplace(key, std::move(f)).first->second;
}

void ThetaMethod::DoStart(double t0, double h_run, const Eigen::VectorXd& x, Eigen::VectorXd& z) {
  // z(t0+) from an implicit Euler LCP with a tiny step: the rational complementarity problem
  // of 4.5 at large s. Only theta < 1 reuses z_n; for theta = 1 it is just the t0 output.
  // The step must be tiny against the circuit's fastest rate too, not only against h_run: the
  // error of this z is about h times that rate, |A| or, for a pair with D_ii > 0 (index 0),
  // the rate sum_j |(CB)_ij| / D_ii at which conduction through it moves the state.
  const Lcs& s = model_.lcs();
  double rate = s.A.size() > 0 ? s.A.cwiseAbs().rowwise().sum().maxCoeff() : 0.0;
  if (s.pairs() > 0 && s.states() > 0) {
    const Eigen::MatrixXd CB = s.C * s.B;
    for (int i = 0; i < s.pairs(); ++i)
      if (s.D(i, i) > 0) rate = std::max(rate, CB.row(i).cwiseAbs().sum() / s.D(i, i));
  }
  const double h = 1e-8 * (rate > 0 ? std::min(h_run, 1.0 / rate) : h_run);
  StepFactors& f = factors(h, 1.0);
  u1_ = model_.input_values(t0 + h);
  q_ = f.CPhi * x + f.CPu1F * u1_;
  const LcpSolution& sol = f.lcp->solve(q_);
  if (sol.status != LcpStatus::Solved)
    throw NumericalFailure(t0, std::string("no consistent initial complementarity state (Lemke: ") +
                                   lcp_status_name(sol.status) + ")");
  z = sol.z;
}

void ThetaMethod::DoStep(double t, double h, Eigen::VectorXd& x, Eigen::VectorXd& z) {
  StepFactors& f = factors(h, theta_);
  u1_ = model_.input_values(t + h);
  q_ = f.CPhi * x + f.CPu1F * u1_;
  if (theta_ != 1.0) {
    u0_ = model_.input_values(t);
    q_ += f.CPz * z + f.CPu0 * u0_;
  }
  const LcpSolution& sol = f.lcp->solve(q_);
  if (sol.status != LcpStatus::Solved)
    throw NumericalFailure(t + h, std::string("the step's LCP has no solution (Lemke: ") +
                                      lcp_status_name(sol.status) + ")");
  Eigen::VectorXd x_next = f.Phi * x + f.Pu1 * u1_ + f.WB * sol.z;
  if (theta_ != 1.0) x_next += f.Pz * z + f.Pu0 * u0_;
  x = std::move(x_next);
  z = sol.z;
}

StepperStats ThetaMethod::stats() const {
  StepperStats s = stats_;
  s.lcp = {};
  for (const auto& [key, f] : cache_) {
    const LcpWarmStats& w = f->lcp->stats();
    s.lcp.solves += w.solves;
    s.lcp.warm_hits += w.warm_hits;
    s.lcp.lemke_calls += w.lemke_calls;
    s.lcp.lemke_pivots += w.lemke_pivots;
  }
  return s;
}

}  // namespace lcs
