#include "solver/integrators/radau_iia.h"
#include "solver/model/empty_safe.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "solver/integrators/start_complementarity.h"
#include "solver/model/numerical_failure.h"

namespace lcs {

ButcherTableau radau_iia_tableau(int stages) {
  ButcherTableau t;
  if (stages == 2) {  // order 3, stage order 2
    t.c.resize(2);
    t.c << 1.0 / 3, 1.0;
    t.a.resize(2, 2);
    t.a << 5.0 / 12, -1.0 / 12,
           3.0 / 4, 1.0 / 4;
  } else if (stages == 3) {  // order 5, stage order 3
    const double r = std::sqrt(6.0);
    t.c.resize(3);
    t.c << (4 - r) / 10, (4 + r) / 10, 1.0;
    t.a.resize(3, 3);
    t.a << (88 - 7 * r) / 360, (296 - 169 * r) / 1800, (-2 + 3 * r) / 225,
           (296 + 169 * r) / 1800, (88 + 7 * r) / 360, (-2 - 3 * r) / 225,
           (16 - r) / 36, (16 + r) / 36, 1.0 / 9;
  } else {
    throw std::invalid_argument("Radau IIA: " + std::to_string(stages) +
                                " stages (2 and 3 are implemented)");
  }
  return t;
}

namespace {

// a ⊗ b (the tensor product of 8.4.2).
Eigen::MatrixXd kron(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  Eigen::MatrixXd k(a.rows() * b.rows(), a.cols() * b.cols());
  if (k.size() == 0) return k;  // blocks of an empty matrix point at null (UBSan)
  for (Eigen::Index i = 0; i < a.rows(); ++i)
    for (Eigen::Index j = 0; j < a.cols(); ++j)
      k.block(i * b.rows(), j * b.cols(), b.rows(), b.cols()) = a(i, j) * b;
  return k;
}

}  // namespace

struct RadauIIA::StepFactors {
  // X = Px x + PZ Z + PU U (X, Z, U stacked by stage);  W = Qx x + Qu U + M Z.
  // Only the last stage row block of P is kept: x+ = X_s = Sx x + Sz Z + Su U.
  Eigen::MatrixXd Sx, Sz, Su, Qx, Qu;
  std::unique_ptr<LcpWarmSolver> lcp;
  // Implicit Euler over the same step, w = CEx x + CEu u(t+h) + ME z: where the stage LCP has
  // several solutions and the previous mode has ended, its choice of mode (one stable solution)
  // is the stages' (made when first needed).
  Eigen::MatrixXd CEx, CEu;
  std::unique_ptr<LcpWarmSolver> euler;
};

RadauIIA::RadauIIA(const LcsProblem& model, int stages)
    : TimeStepper(model), tableau_(radau_iia_tableau(stages)) {
  const Lcs& s = model.lcs();
  U_.resize(stages * s.inputs());
  q_.resize(stages * s.pairs());
  x_next_.resize(s.states());
}

RadauIIA::~RadauIIA() = default;

RadauIIA::StepFactors& RadauIIA::factors(double h) {
  auto it = cache_.find(h);
  if (it != cache_.end()) return *it->second;
  const Lcs& s = model_.lcs();
  const int n = s.states(), m = s.pairs(), k = s.inputs(), st = stages();
  const Eigen::MatrixXd& a = tableau_.a;
  const Eigen::MatrixXd Is = Eigen::MatrixXd::Identity(st, st);
  const Eigen::MatrixXd ones = Eigen::MatrixXd::Ones(st, 1);

  // N X = 1⊗x + h(𝒜⊗B) Z + h(𝒜⊗E) U with N = I - h(𝒜⊗A). N's eigenvalues are 1 - h λ μ
  // (λ of 𝒜, μ of A); one vanishes only for μ = 1/(h λ), in the right half-plane as λ is, so N
  // is nonsingular whenever A has no eigenvalue there (a passive circuit).
  Eigen::MatrixXd Px(st * n, n), PZ(st * n, st * m), PU(st * n, st * k);
  if (n > 0) {
    Eigen::PartialPivLU<Eigen::MatrixXd> N(Eigen::MatrixXd::Identity(st * n, st * n) -
                                           h * kron(a, s.A));
    Px = solve_or_empty(N, kron(ones, Eigen::MatrixXd::Identity(n, n)));
    PZ = solve_or_empty(N, h * kron(a, s.B));
    PU = solve_or_empty(N, h * kron(a, s.E));
  }
  auto f = std::make_unique<StepFactors>();
  // The last stage's rows (stiffly accurate); with no states there are none, and a block of an
  // empty matrix points at null (UBSan).
  auto last_stage = [&](const Eigen::MatrixXd& P) {
    return P.size() > 0 ? Eigen::MatrixXd(P.bottomRows(n)) : Eigen::MatrixXd::Zero(n, P.cols()).eval();
  };
  f->Sx = last_stage(Px);
  f->Sz = last_stage(PZ);
  f->Su = last_stage(PU);
  const Eigen::MatrixXd IC = kron(Is, s.C);
  f->Qx = IC * Px;
  f->Qu = IC * PU + kron(Is, s.F);
  f->lcp = std::make_unique<LcpWarmSolver>(kron(Is, s.D) + IC * PZ);
  if (model_.has_transfer_pairs()) f->lcp->watch_multiplicity();
  ++stats_.factorisations;
  return *cache_.emplace(h, std::move(f)).first->second;
}

void RadauIIA::DoStart(double t0, double h_run, const Eigen::VectorXd& x, Eigen::VectorXd& z) {
  z = consistent_start_z(model_, t0, h_run, x, stats_, z, &multistability_);
}

void RadauIIA::DoStep(double t, double h, Eigen::VectorXd& x, Eigen::VectorXd& z) {
  StepFactors& f = factors(h);
  const int m = model_.lcs().pairs(), k = model_.lcs().inputs();
  for (int j = 0; j < stages(); ++j)
    model_.input_values(t + tableau_.c(j) * h, U_.segment(j * k, k));  // U_j = u(t + c_j h)
  q_.noalias() = f.Qx * x;
  q_.noalias() += f.Qu * U_;
  if (f.lcp->stats().solves == 0 && m > 0) f.lcp->prefer(z.replicate(stages(), 1));
  else f.lcp->continue_last_block(stages());
  const LcpSolution* sol_ptr = &f.lcp->solve(q_);
  if (sol_ptr->status == LcpStatus::NotUnique) sol_ptr = &mode_from_euler(f, t, h, x, z);
  const LcpSolution& sol = *sol_ptr;
  multistability_.check(*f.lcp, model_, t + h, stages());
  if (sol.status != LcpStatus::Solved)
    throw NumericalFailure(t + h, std::string("the Radau IIA step's LCP has no solution (Lemke: ") +
                                      lcp_status_name(sol.status) + ")");
  x_next_.noalias() = f.Sx * x;
  x_next_.noalias() += f.Sz * sol.z;
  x_next_.noalias() += f.Su * U_;
  x = x_next_;
  if (m > 0) z = sol.z.tail(m);  // a tail of an empty vector points at null (UBSan)
  else z.resize(0);
}

const LcpSolution& RadauIIA::mode_from_euler(StepFactors& f, double t, double h, const Eigen::VectorXd& x,
                                             const Eigen::VectorXd& z) {
  const Lcs& s = model_.lcs();
  const int n = s.states();
  if (!f.euler) {
    const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(n, n);
    Eigen::PartialPivLU<Eigen::MatrixXd> W(I - h * s.A);
    const Eigen::MatrixXd Phi = n > 0 ? solve_or_empty(W, I) : Eigen::MatrixXd(0, 0);
    const Eigen::MatrixXd Pu = n > 0 ? solve_or_empty(W, h * s.E) : Eigen::MatrixXd(0, s.inputs());
    const Eigen::MatrixXd WB = n > 0 ? solve_or_empty(W, h * s.B) : Eigen::MatrixXd(0, s.pairs());
    f.CEx = s.C * Phi;
    f.CEu = s.C * Pu + s.F;
    f.euler = std::make_unique<LcpWarmSolver>(s.D + s.C * WB);
    f.euler->watch_multiplicity();
  }
  const Eigen::VectorXd u1 = model_.input_values(t + h);
  f.euler->prefer(z, true);
  const LcpSolution& e = f.euler->solve(f.CEx * x + f.CEu * u1);
  multistability_.check(*f.euler, model_, t + h);  // throws when Euler cannot choose either
  f.lcp->prefer(e.z.replicate(stages(), 1), true);
  return f.lcp->solve(q_);
}

StepperStats RadauIIA::stats() const {
  StepperStats s = stats_;  // s.lcp holds the start LCP (consistent_start_z)
  for (const auto& [h, f] : cache_) s.lcp += f->lcp->stats();
  return s;
}

}  // namespace lcs
