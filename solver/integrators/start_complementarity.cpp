#include "solver/integrators/start_complementarity.h"

#include <stdexcept>
#include "solver/model/empty_safe.h"

#include <algorithm>
#include <string>

#include "solver/integrators/event_driven.h"
#include "solver/lcp/lcp.h"
#include "solver/lcp/sparse_active_set.h"
#include "solver/model/conduction_rates.h"
#include "solver/model/dense_budget.h"
#include "solver/model/sparse_lcs.h"

#include <Eigen/SparseLU>
#include "solver/model/numerical_failure.h"

namespace lcs {

namespace {

// The step must be tiny against the circuit's fastest rate too, not only against h_run: the
// error of the start z is about h times that rate, |A| or, for a pair with D_ii > 0 (index 0),
// the rate sum_j |(CB)_ij| / D_ii at which conduction through it moves the state.
double start_step(const Lcs& s, double h_run) {
  double rate = s.A.size() > 0 ? s.A.cwiseAbs().rowwise().sum().maxCoeff() : 0.0;
  rate = std::max(rate, fastest_finite_rate(conduction_rates(s)));
  return 1e-8 * (rate > 0 ? std::min(h_run, 1.0 / rate) : h_run);
}


// The start's step h on the sparse LCS: the same rate as start_step, from sparse products.
double sparse_start_step(const SparseLcs& s, double h_run) {
  double rate = 0;
  Eigen::VectorXd rows = Eigen::VectorXd::Zero(s.A.rows());
  for (int k = 0; k < s.A.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(s.A, k); it; ++it) rows(it.row()) += std::abs(it.value());
  if (rows.size() > 0) rate = rows.maxCoeff();
  rate = std::max(rate, fastest_finite_rate(conduction_rates(s)));
  return 1e-8 * (rate > 0 ? std::min(h_run, 1.0 / rate) : h_run);
}

// Whether the start LCP's answer leaves something for the event method's mode selection to
// decide (see consistent_start_z): a pair with no O(1) entry of its own (D_ii = 0), or one at
// z = w = 0. `q` is w at z = 0.
bool start_is_ambiguous(const Eigen::VectorXd& diagonal, const Eigen::VectorXd& row_size,
                        const Eigen::VectorXd& q, const Eigen::VectorXd& z, const Eigen::VectorXd& w) {
  const double qs = q.size() > 0 ? q.cwiseAbs().maxCoeff() : 0.0;
  const double zs = (z.size() > 0 ? z.cwiseAbs().maxCoeff() : 0.0) + qs;
  for (int i = 0; i < z.size(); ++i) {
    const bool index_one = !(diagonal(i) > 1e-12 * row_size(i));
    const bool degenerate = std::abs(z(i)) <= 1e-9 * zs && std::abs(w(i)) <= 1e-9 * qs;
    if (index_one || degenerate) return true;
  }
  return false;
}

// consistent_start_z on the sparse system (large circuits without transistors or lines): the
// same implicit Euler step's LCP, solved by active sets (sparse_active_set.h). False when the
// mode search fails (the dense path decides then).
bool sparse_start_z(const LcsProblem& model, const SparseLcs& s, double t0, double h_run,
                    const Eigen::VectorXd& x, StepperStats& stats, const Eigen::VectorXd& prefer,
                    Eigen::VectorXd& z) {
  const double h = sparse_start_step(s, h_run);
  const int n = static_cast<int>(s.A.rows()), m = static_cast<int>(s.D.rows());
  Eigen::SparseMatrix<double> W(n, n);
  W.setIdentity();
  W -= h * s.A;
  SparseActiveSetLcp lcp(W, Eigen::SparseMatrix<double>(-h * s.B), s.C, s.D);
  if (prefer.size() == m && m > 0 && prefer.cwiseAbs().maxCoeff() > 0) lcp.prefer(prefer);
  const Eigen::VectorXd u = model.input_values(t0 + h);
  const Eigen::VectorXd a = x + h * (s.E * u), b = s.F * u;
  Eigen::VectorXd y, w;
  const bool solved = lcp.solve(a, b, y, z, w);
  SparseActiveSetStats own = lcp.stats();
  own.cache_bytes = 0;  // freed on return: only the steppers' caches stay
  stats.sparse += own;
  ++stats.factorisations;
  if (!solved) return false;
  // Eigen's SparseLU divides by the size: a circuit without states (resistors and diodes only)
  // has q = b.
  Eigen::VectorXd q = b;
  if (n > 0) {
    Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> free_flow(W);
    if (free_flow.info() != Eigen::Success) return true;
    q += s.C * Eigen::VectorXd(free_flow.solve(a));
  }
  Eigen::VectorXd diagonal(m), row_size = Eigen::VectorXd::Zero(m);
  for (int i = 0; i < m; ++i) diagonal(i) = s.D.coeff(i, i);
  for (int k = 0; k < s.D.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(s.D, k); it; ++it)
      row_size(it.row()) = std::max(row_size(it.row()), std::abs(it.value()));
  if (start_is_ambiguous(diagonal, row_size, q, z, w)) {
    try {
      z = event_mode_z(model, t0, h_run, x);
    } catch (const NumericalFailure&) {
    } catch (const std::invalid_argument&) {  // sources the event method cannot hold (SFFM)
    }
  }
  return true;
}

}  // namespace

Eigen::VectorXd consistent_start_z(const LcsProblem& model, double t0, double h_run,
                                   const Eigen::VectorXd& x, StepperStats& stats,
                                   const Eigen::VectorXd& prefer, MultistabilityNotes* notes) {
  // Implicit Euler: x+ = W^-1 (x + h B z + h E u+), W = I - h A, so
  // w+ = C W^-1 x + (C W^-1 h E + F) u+  +  (D + C W^-1 h B) z.
  const SparseLcs* sparse =
      model.has_history() || model.has_transfer_pairs() ? nullptr : model.sparse_lcs().get();
  if (sparse) {
    Eigen::VectorXd z;
    if (sparse_start_z(model, *sparse, t0, h_run, x, stats, prefer, z)) return z;
  }
  if (!dense_within_budget(model.state_count(), model.pair_count(), 4))
    throw NumericalFailure(t0, "no start from the sparse circuit, and the dense start LCP is not formed: " +
                                   dense_budget_reason(model.state_count(), model.pair_count(), 4));
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
  if (sol.status != LcpStatus::Solved) {
    // Rows whose entries are all O(h) (an inductor's current through RON = 0 diodes with unequal
    // thresholds) can fall below Lemke's tolerance against their O(1) neighbours: the event
    // method's mode selection, from the operating point's mode, decides then.
    if (prefer.size() == s.pairs() && s.pairs() > 0) {
      try {
        return event_mode_z(model, t0, h_run, x, &prefer);
      } catch (const NumericalFailure&) {
      } catch (const std::invalid_argument&) {  // sources the event method cannot hold (SFFM)
      }
    }
    throw NumericalFailure(t0, std::string("no consistent initial complementarity state (Lemke: ") +
                                   lcp_status_name(sol.status) + ")");
  }
  // The LCP alone is not enough where a pair's own row has no O(1) entry (D_ii = 0: a diode whose
  // only other path is an inductor, w = i_L) or where it leaves a pair at z = w = 0. Its z is
  // then set by O(h) entries: the 1e-15 A of rounding an operating point leaves in i_L, divided
  // by h/L, put such a diode's voltage 0.36 V off; a pair coupled to a neighbour by O(1) entries
  // was left at its threshold, 0.7 V off (tests/random). The theta method carried either into
  // its steps as a ringing. There the event method's mode selection decides, which checks the
  // mode against its derivatives and index-one constraints; a state it cannot fit (one that
  // must jump) keeps the LCP's answer.
  const Eigen::VectorXd row_size =
      s.pairs() > 0 ? Eigen::VectorXd(s.D.cwiseAbs().rowwise().maxCoeff()) : Eigen::VectorXd(0);
  const bool ambiguous = start_is_ambiguous(s.D.diagonal(), row_size, q, sol.z, sol.w);
  if (ambiguous && lcp.multiplicity() != LcpWarmSolver::Multiplicity::SeveralKeptContinuous) {
    try {
      return event_mode_z(model, t0, h_run, x);
    } catch (const NumericalFailure&) {
    } catch (const std::invalid_argument&) {  // sources the event method cannot hold (SFFM)
    }
  }
  return sol.z;
}

}  // namespace lcs
