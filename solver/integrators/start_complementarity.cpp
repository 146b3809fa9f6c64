#include "solver/integrators/start_complementarity.h"
#include "solver/model/empty_safe.h"

#include <algorithm>
#include <string>

#include "solver/integrators/event_driven.h"
#include "solver/lcp/lcp.h"
#include "solver/model/numerical_failure.h"

namespace lcs {

namespace {

// The step must be tiny against the circuit's fastest rate too, not only against h_run: the
// error of the start z is about h times that rate, |A| or, for a pair with D_ii > 0 (index 0),
// the rate sum_j |(CB)_ij| / D_ii at which conduction through it moves the state.
double start_step(const Lcs& s, double h_run) {
  double rate = s.A.size() > 0 ? s.A.cwiseAbs().rowwise().sum().maxCoeff() : 0.0;
  if (s.pairs() > 0 && s.states() > 0) {
    const Eigen::MatrixXd CB = s.C * s.B;
    for (int i = 0; i < s.pairs(); ++i)
      if (s.D(i, i) > 0) rate = std::max(rate, CB.row(i).cwiseAbs().sum() / s.D(i, i));
  }
  return 1e-8 * (rate > 0 ? std::min(h_run, 1.0 / rate) : h_run);
}

}  // namespace

Eigen::VectorXd consistent_start_z(const LcsProblem& model, double t0, double h_run,
                                   const Eigen::VectorXd& x, StepperStats& stats,
                                   const Eigen::VectorXd& prefer, MultistabilityNotes* notes) {
  // Implicit Euler: x+ = W^-1 (x + h B z + h E u+), W = I - h A, so
  // w+ = C W^-1 x + (C W^-1 h E + F) u+  +  (D + C W^-1 h B) z.
  const Lcs& s = model.lcs();
  const int n = s.states();
  const double h = start_step(s, h_run);
  Eigen::MatrixXd I = Eigen::MatrixXd::Identity(n, n);
  Eigen::PartialPivLU<Eigen::MatrixXd> W(I - h * s.A);
  const Eigen::MatrixXd Phi = n > 0 ? solve_or_empty(W, I) : Eigen::MatrixXd(0, 0);
  const Eigen::MatrixXd Pu = n > 0 ? solve_or_empty(W, h * s.E) : Eigen::MatrixXd(0, s.inputs());
  const Eigen::MatrixXd WB = n > 0 ? solve_or_empty(W, h * s.B) : Eigen::MatrixXd(0, s.pairs());
  LcpWarmSolver lcp(s.D + s.C * WB);
  if (model.has_transfer_pairs()) lcp.watch_multiplicity();
  ++stats.factorisations;
  const Eigen::VectorXd q = s.C * Phi * x + (s.C * Pu + s.F) * model.input_values(t0 + h);
  if (prefer.size() == s.pairs() && s.pairs() > 0 && prefer.cwiseAbs().maxCoeff() > 0) lcp.prefer(prefer);
  const LcpSolution& sol = lcp.solve(q);
  stats.lcp += lcp.stats();
  MultistabilityNotes own;
  (notes ? *notes : own).check(lcp, model, t0);
  if (sol.status != LcpStatus::Solved)
    throw NumericalFailure(t0, std::string("no consistent initial complementarity state (Lemke: ") +
                                   lcp_status_name(sol.status) + ")");
  // The LCP alone is not enough where a pair's own row has no O(1) entry (D_ii = 0: a diode whose
  // only other path is an inductor, w = i_L) or where it leaves a pair at z = w = 0. Its z is
  // then set by O(h) entries: the 1e-15 A of rounding an operating point leaves in i_L, divided
  // by h/L, put such a diode's voltage 0.36 V off; a pair coupled to a neighbour by O(1) entries
  // was left at its threshold, 0.7 V off (tests/random). The theta method carried either into
  // its steps as a ringing. There the event method's mode selection decides, which checks the
  // mode against its derivatives and index-one constraints; a state it cannot fit (one that
  // must jump) keeps the LCP's answer.
  bool ambiguous = false;
  const double qs = q.size() > 0 ? q.cwiseAbs().maxCoeff() : 0.0;
  const double zs = (sol.z.size() > 0 ? sol.z.cwiseAbs().maxCoeff() : 0.0) + qs;
  for (int i = 0; i < s.pairs(); ++i) {
    const bool index_one = !(s.D(i, i) > 1e-12 * s.D.row(i).cwiseAbs().maxCoeff());
    const bool degenerate = std::abs(sol.z(i)) <= 1e-9 * zs && std::abs(sol.w(i)) <= 1e-9 * qs;
    ambiguous = ambiguous || index_one || degenerate;
  }
  if (ambiguous && lcp.multiplicity() != LcpWarmSolver::Multiplicity::SeveralKeptContinuous) {
    try {
      return event_mode_z(model, t0, h_run, x);
    } catch (const NumericalFailure&) {
    }
  }
  return sol.z;
}

}  // namespace lcs
