#include "solver/integrators/shockley_dae.h"

#include "solver/model/klu_factor.h"
#include "solver/model/sparse_lcs.h"

#include <memory>

#include <algorithm>
#include <functional>


namespace lcs {

namespace {

// One LU of a Newton matrix, dense or (on a sparse LCS) KLU's; solve() is not finite when the
// matrix is singular.
class NewtonFactor {
 public:
  explicit NewtonFactor(const Eigen::MatrixXd& dense) : dense_(dense) {}
  explicit NewtonFactor(const Eigen::SparseMatrix<double>& sparse) : sparse_(std::make_unique<KluFactor>(sparse)) {}
  Eigen::VectorXd solve(const Eigen::VectorXd& rhs) const {
    if (!sparse_) return dense_.solve(rhs);
    if (!sparse_->ok()) return Eigen::VectorXd::Constant(rhs.size(), std::nan(""));
    return sparse_->solve(rhs);
  }

 private:
  Eigen::PartialPivLU<Eigen::MatrixXd> dense_;
  std::unique_ptr<KluFactor> sparse_;
};

// diag(dw) - D diag(dz): the Newton matrix of the pairs' rows, sparse when the LCS is.
NewtonFactor pair_factor(const SparseLcs* sparse, const LcsProblem& model, const Eigen::VectorXd& dz,
                         const Eigen::VectorXd& dw) {
  if (!sparse) return NewtonFactor(Eigen::MatrixXd(Eigen::MatrixXd(dw.asDiagonal()) - model.lcs().D * dz.asDiagonal()));
  Eigen::SparseMatrix<double> M = -sparse->D * dz.asDiagonal();
  for (int k = 0; k < M.rows(); ++k) M.coeffRef(k, k) += dw(k);
  return NewtonFactor(M);
}

// The forward branch solves IS (e^x - 1) + GMIN N Vt x = i for x = -m / N Vt > 0. Beyond this
// ratio i / IS (e^x would pass 1e300) the GMIN term is below rounding and x = ln(i / IS): no
// exponential is ever formed that could overflow, whatever s a Newton iterate tries.
constexpr double kLargestRatio = 1e300;

// The largest margin tolerance, as a fraction of N Vt (see error_weights).
constexpr double kMarginFractionOfNVt = 0.01;

}  // namespace

ShockleyCurve::Point ShockleyCurve::at(double s) const {
  Point p;
  if (s >= 0) {
    const double e = std::exp(-s / nvt);
    p.current = is * std::expm1(-s / nvt) - kGmin * s;
    p.margin = s;
    p.dcurrent = -is / nvt * e - kGmin;
    p.dmargin = 1.0;
    return p;
  }
  const double g = g0(), a = kGmin * nvt / is;
  p.current = -g * s;
  p.dcurrent = -g;
  const double c = p.current / is;
  double x;
  if (!(c < kLargestRatio)) {
    x = std::log(c);  // also carries inf and NaN on to the caller
  } else {
    // f(x) = e^x - 1 + a x - c is convex and increasing, and f(ln(1 + c)) = a ln(1 + c) >= 0:
    // Newton's method from there decreases monotonically to the root.
    x = std::log1p(c);
    for (int it = 0; it < 60; ++it) {
      const double dx = (std::expm1(x) + a * x - c) / (std::exp(x) + a);
      x -= dx;
      if (std::abs(dx) <= 1e-15 * x) break;
    }
  }
  p.margin = -nvt * x;
  // e^x = 1 + c - a x on the curve.
  p.dmargin = g / (is / nvt * (1 + c - a * x) + kGmin);
  return p;
}

ShockleyDae::ShockleyDae(const LcsProblem& model, bool sparse) : model_(model) {
  if (sparse && !model.has_history()) sparse_ = model.sparse_lcs().get();
  if (sparse_) {
    n_ = static_cast<int>(sparse_->A.rows());
    m_ = static_cast<int>(sparse_->D.rows());
  } else {
    const Lcs& lcs = model.lcs();
    n_ = lcs.states();
    m_ = lcs.pairs();
  }
  for (const PairInfo& p : model.pairs()) {
    curves_.push_back({p.smooth.is, p.smooth.n * kThermalVoltage});
    voltage_type_.push_back(p.voltage_type);
  }
  z_.resize(m_);
  w_.resize(m_);
  dz_.resize(m_);
  dw_.resize(m_);
  set_tolerances(rtol_, margin_atol_, voltage_scale_);
}

Eigen::VectorXd ShockleyDae::state_rate(const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::VectorXd& z,
                                        const Eigen::VectorXd& u) const {
  if (sparse_) return sparse_->A * x + sparse_->B * z + sparse_->E * u;
  const Lcs& lcs = model_.lcs();
  return lcs.A * x + lcs.B * z + lcs.E * u;
}

Eigen::VectorXd ShockleyDae::pair_rows(const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::VectorXd& u) const {
  if (sparse_) return sparse_->C * x + sparse_->F * u;
  const Lcs& lcs = model_.lcs();
  return lcs.C * x + lcs.F * u;
}

Eigen::VectorXd ShockleyDae::d_times(const Eigen::VectorXd& z) const {
  if (sparse_) return sparse_->D * z;
  return model_.lcs().D * z;
}

Eigen::VectorXd ShockleyDae::inputs(double t) const {
  if (t < segment_end_) return model_.input_values(t);
  return model_.inputs().values_before(segment_end_);
}

void ShockleyDae::on_curves(const Eigen::Ref<const Eigen::VectorXd>& s, Eigen::VectorXd& z,
                            Eigen::VectorXd& w, Eigen::VectorXd* dz, Eigen::VectorXd* dw) const {
  for (int k = 0; k < m_; ++k) {
    const ShockleyCurve::Point p = curves_[k].at(s(k));
    z(k) = voltage_type_[k] ? p.margin : p.current;
    w(k) = voltage_type_[k] ? p.current : p.margin;
    if (dz) (*dz)(k) = voltage_type_[k] ? p.dmargin : p.dcurrent;
    if (dw) (*dw)(k) = voltage_type_[k] ? p.dcurrent : p.dmargin;
  }
}

Eigen::VectorXd ShockleyDae::complementarity_variables(const Eigen::VectorXd& s) const {
  Eigen::VectorXd z(m_), w(m_);
  on_curves(s, z, w, nullptr, nullptr);
  return z;
}

Eigen::VectorXd ShockleyDae::parameters_from_ideal(double t, const Eigen::VectorXd& x,
                                                   const Eigen::VectorXd& z_ideal) const {
  const Eigen::VectorXd w = pair_rows(x, inputs(t)) + d_times(z_ideal);
  Eigen::VectorXd s(m_);
  for (int k = 0; k < m_; ++k) {
    const double current = voltage_type_[k] ? w(k) : z_ideal(k);
    const double margin = voltage_type_[k] ? z_ideal(k) : w(k);
    s(k) = current > 0 ? -current / curves_[k].g0() : std::max(margin, 0.0);
  }
  return s;
}

bool ShockleyDae::residual(double t, const Eigen::Ref<const Eigen::VectorXd>& y,
                           const Eigen::Ref<const Eigen::VectorXd>& yp,
                           Eigen::Ref<Eigen::VectorXd> r) const {
  const Eigen::VectorXd u = inputs(t);
  const auto x = y.head(n_);
  on_curves(y.tail(m_), z_, w_, nullptr, nullptr);
  r.head(n_) = yp.head(n_) - state_rate(x, z_, u);
  r.tail(m_) = w_ - pair_rows(x, u) - d_times(z_);
  return r.allFinite();
}

void ShockleyDae::jacobian(double t, const Eigen::Ref<const Eigen::VectorXd>& y, double cj,
                           Eigen::Ref<Eigen::MatrixXd> J) const {
  const Lcs& lcs = model_.lcs();
  on_curves(y.tail(m_), z_, w_, &dz_, &dw_);
  J.topLeftCorner(n_, n_) = cj * Eigen::MatrixXd::Identity(n_, n_) - lcs.A;
  J.topRightCorner(n_, m_) = -lcs.B * dz_.asDiagonal();
  J.bottomLeftCorner(m_, n_) = -lcs.C;
  J.bottomRightCorner(m_, m_) = Eigen::MatrixXd(dw_.asDiagonal()) - lcs.D * dz_.asDiagonal();
}

const Eigen::SparseMatrix<double>& ShockleyDae::sparse_jacobian(const Eigen::Ref<const Eigen::VectorXd>& y,
                                                               double cj) const {
  const SparseLcs& s = *sparse_;
  on_curves(y.tail(m_), z_, w_, &dz_, &dw_);
  triplets_.clear();
  for (int k = 0; k < n_; ++k) triplets_.emplace_back(k, k, cj);
  for (int k = 0; k < m_; ++k) triplets_.emplace_back(n_ + k, n_ + k, dw_(k));
  using It = Eigen::SparseMatrix<double>::InnerIterator;
  for (int j = 0; j < s.A.outerSize(); ++j)
    for (It it(s.A, j); it; ++it) triplets_.emplace_back(it.row(), j, -it.value());
  for (int j = 0; j < s.B.outerSize(); ++j)
    for (It it(s.B, j); it; ++it) triplets_.emplace_back(it.row(), n_ + j, -it.value() * dz_(j));
  for (int j = 0; j < s.C.outerSize(); ++j)
    for (It it(s.C, j); it; ++it) triplets_.emplace_back(n_ + it.row(), j, -it.value());
  for (int j = 0; j < s.D.outerSize(); ++j)
    for (It it(s.D, j); it; ++it) triplets_.emplace_back(n_ + it.row(), n_ + j, -it.value() * dz_(j));
  sparse_jacobian_.resize(n_ + m_, n_ + m_);
  sparse_jacobian_.setFromTriplets(triplets_.begin(), triplets_.end());  // sums, keeps zeros
  return sparse_jacobian_;
}

Eigen::VectorXd ShockleyDae::derivative(double t, const Eigen::VectorXd& x,
                                        const Eigen::VectorXd& s) const {
  on_curves(s, z_, w_, nullptr, nullptr);
  return state_rate(x, z_, inputs(t));
}

Eigen::VectorXd ShockleyDae::parameter_rates(double t, const Eigen::VectorXd& x,
                                             const Eigen::VectorXd& s,
                                             const Eigen::VectorXd& xdot) const {
  if (m_ == 0) return Eigen::VectorXd(0);
  on_curves(s, z_, w_, &dz_, &dw_);
  // The source slopes: the right derivative, as the integration goes forward from t.
  Eigen::VectorXd sdot = pair_factor(sparse_, model_, dz_, dw_).solve(pair_rows(xdot, model_.input_derivatives(t)));
  if (!sdot.allFinite()) sdot.setZero();
  return sdot;
}

void ShockleyDae::set_tolerances(double rtol, double volts, double voltage_scale) {
  constexpr double kSiemens = 1e-12 / 1e-6;  // ngspice ABSTOL / VNTOL
  rtol_ = rtol;
  margin_atol_ = volts;
  voltage_scale_ = voltage_scale;
  state_atol_.resize(n_);
  capacitor_.assign(n_, true);
  for (int k = 0; k < n_; ++k) {
    capacitor_[k] = model_.states()[k].capacitor;
    state_atol_(k) = capacitor_[k] ? volts : volts * kSiemens;
  }
}

bool ShockleyDae::error_weights(const Eigen::Ref<const Eigen::VectorXd>& y,
                                Eigen::Ref<Eigen::VectorXd> w) const {
  for (int k = 0; k < n_; ++k) w(k) = 1.0 / (rtol_ * std::abs(y(k)) + state_atol_(k));
  pair_weights(y.head(n_), y.tail(m_), w.tail(m_));
  return w.allFinite() && (w.array() > 0).all();
}

void ShockleyDae::pair_weights(const Eigen::Ref<const Eigen::VectorXd>& x,
                               const Eigen::Ref<const Eigen::VectorXd>& s,
                               Eigen::Ref<Eigen::VectorXd> w) const {
  double scale = voltage_scale_;
  for (int k = 0; k < n_; ++k)
    if (capacitor_[k]) scale = std::max(scale, std::abs(x(k)));
  const double margin_tolerance = rtol_ * scale + margin_atol_;
  for (int k = 0; k < m_; ++k) {
    const double tolerance =
        std::max(margin_atol_, std::min(margin_tolerance, kMarginFractionOfNVt * curves_[k].nvt));
    w(k) = curves_[k].at(s(k)).dmargin / tolerance;
  }
}

bool ShockleyDae::solve_pairs(double t, const Eigen::VectorXd& x, Eigen::VectorXd& s,
                              long* iterations) const {
  if (m_ == 0) return true;
  const Eigen::VectorXd q = pair_rows(x, inputs(t));
  Eigen::VectorXd z(m_), w(m_), dz(m_), dw(m_), r(m_);
  auto evaluate = [&](const Eigen::VectorXd& ss, bool derivatives) {
    on_curves(ss, z, w, derivatives ? &dz : nullptr, derivatives ? &dw : nullptr);
    r = w - d_times(z) - q;
    return r.allFinite();
  };
  // The weighted RMS norm of a change d of s at s = at, as IDA measures it.
  Eigen::VectorXd weights(m_);
  auto norm = [&](const Eigen::VectorXd& d, const Eigen::VectorXd& at) {
    pair_weights(x, at, weights);
    return std::sqrt(d.cwiseProduct(weights).squaredNorm() / m_);
  };
  Eigen::VectorXd sk = s, s_try;
  for (int it = 0; it < 100; ++it) {
    if (!evaluate(sk, true)) return false;
    if (iterations) ++*iterations;
    const NewtonFactor lu = pair_factor(sparse_, model_, dz, dw);
    const Eigen::VectorXd ds = lu.solve(-r);
    if (!ds.allFinite()) return false;
    const double ds_norm = norm(ds, sk);
    // Newton converges quadratically: a step this far inside the integration tolerance is the
    // remaining error, so take it and stop.
    if (ds_norm <= 1e-3) {
      s = sk + ds;
      return true;
    }
    // Damped by the natural monotonicity test (Deuflhard): the next simplified Newton correction
    // must shrink, measured in the unknowns' own weighted units.
    bool accepted = false;
    for (double lambda = 1.0; lambda > 1e-10 && !accepted; lambda *= 0.5) {
      s_try = sk + lambda * ds;
      accepted = evaluate(s_try, false) && norm(lu.solve(-r), sk) <= (1 - lambda / 4) * ds_norm;
    }
    if (!accepted) return false;
    sk = s_try;
  }
  return false;
}

bool ShockleyDae::solve_rest_point(double t, Eigen::VectorXd& y, const std::vector<bool>& held,
                                   long* iterations) const {
  const int size = n_ + m_;
  const Eigen::VectorXd y0 = y, zero = Eigen::VectorXd::Zero(size);
  // Each state is pulled toward its value in y at one rate for all, 1e-9 of A's largest entry: a
  // conductance p C across every capacitor and p L in series with every inductor, so that a state
  // with no DC equation (a capacitor with no DC path, an inductor loop) takes the split of least
  // energy, as the ideal operating point's. The pull also moves the determined states a little
  // (a 100 uF emitter capacitor beside 25 pF junctions: p = 10 s^-1 against its 21 s^-1, v(e)
  // 69 uV off); polish_rest_point takes that out. A pull capped at 1e-8 of each state's own row
  // (tried) split two series capacitors of 1 nF and 100 nF with no DC path in proportion to
  // 1/(C p) instead of 1/C: v(b) 63 mV where least energy puts it at 6.86 mV.
  double a_max = 0;
  if (sparse_) {
    for (int k = 0; k < sparse_->A.nonZeros(); ++k) a_max = std::max(a_max, std::abs(sparse_->A.valuePtr()[k]));
  } else {
    a_max = model_.lcs().A.size() > 0 ? model_.lcs().A.cwiseAbs().maxCoeff() : 0.0;
  }
  const double pull = 1e-9 * std::max(a_max, 1e-300);
  auto is_held = [&](int k) { return k < n_ && k < static_cast<int>(held.size()) && held[k]; };
  auto evaluate = [&](const Eigen::VectorXd& at, Eigen::VectorXd& r) {
    if (!residual(t, at, zero, r)) return false;
    r.head(n_) += pull * (at.head(n_) - y0.head(n_));  // residual() has x' - f: here -f
    for (int k = 0; k < n_; ++k)
      if (is_held(k)) r(k) = at(k) - y0(k);
    return true;
  };
  auto linearise = [&](const Eigen::VectorXd& at) -> NewtonStep {
    std::shared_ptr<NewtonFactor> factor;
    if (sparse_) {
      // The sparse Jacobian at cj = 0 is dF/dy; the pull goes on the states' diagonal; a held state's row is e_k.
      const Eigen::SparseMatrix<double>& S = sparse_jacobian(at, 0.0);
      std::vector<Eigen::Triplet<double>> entries;
      entries.reserve(S.nonZeros());
      for (int c = 0; c < S.outerSize(); ++c)
        for (Eigen::SparseMatrix<double>::InnerIterator it(S, c); it; ++it)
          if (!is_held(static_cast<int>(it.row()))) entries.emplace_back(it.row(), c, it.value());
      for (int k = 0; k < n_; ++k) entries.emplace_back(k, k, is_held(k) ? 1.0 : pull);
      Eigen::SparseMatrix<double> M(size, size);
      M.setFromTriplets(entries.begin(), entries.end());
      factor = std::make_shared<NewtonFactor>(M);
    } else {
      Eigen::MatrixXd J(size, size);
      jacobian(t, at, 0.0, J);
      J.topLeftCorner(n_, n_).diagonal().array() += pull;
      for (int k = 0; k < n_; ++k)
        if (is_held(k)) {
          J.row(k).setZero();
          J(k, k) = 1.0;
        }
      factor = std::make_shared<NewtonFactor>(J);
    }
    return [factor](const Eigen::VectorXd& r) -> Eigen::VectorXd { return factor->solve(-r); };
  };
  if (!damped_newton(y, 200, iterations, evaluate, linearise)) return false;
  polish_rest_point(t, y, held, y0, iterations);
  return true;
}

// The pull's own error, taken out: Newton's method on the DC equations without the pull, from the
// pulled solution, each step the minimum-norm solution of the row- and column-equilibrated
// Jacobian (a complete orthogonal decomposition, rank at 1e-10): a direction the equations leave
// free (a capacitor with no DC path, an inductor loop) gets no step and keeps the pulled value,
// every other converges to the equations themselves. A pull scaled to A's rows still moved a
// boost converter's output 5.2 uV off its DC equations (its open switch's ROFF / L, 1e10 s^-1,
// sits in the inductor's row of A and cancels against the conducting diode's column); with ROFF
// = 1e12 ohm, by 0.25 V (still so: at that ROFF the equilibrated Jacobian's rank reads 2 of 3 and
// the polish makes no step). Dense: circuits up to kPolishMaxUnknowns unknowns; y is left as it
// is when the iteration does not converge.
void ShockleyDae::polish_rest_point(double t, Eigen::VectorXd& y, const std::vector<bool>& held,
                                    const Eigen::VectorXd& y0, long* iterations) const {
  const int size = n_ + m_;
  // Not with lines: the residual reads their delayed terms from the history the ideal start laid
  // down, not from y, so its zero at x' = 0 is not their DC relation. Polishing to it moved the
  // lossy-line rectifiers' start (v(out) 7.9 % off the event method's run).
  if (size == 0 || size > kPolishMaxUnknowns || model_.has_history()) return;
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(size);
  auto is_held = [&](int k) { return k < n_ && k < static_cast<int>(held.size()) && held[k]; };
  auto evaluate = [&](const Eigen::VectorXd& at, Eigen::VectorXd& r) {
    if (!residual(t, at, zero, r)) return false;
    for (int k = 0; k < n_; ++k)
      if (is_held(k)) r(k) = at(k) - y0(k);
    return true;
  };
  auto linearise = [&](const Eigen::VectorXd& at) -> NewtonStep {
    Eigen::MatrixXd J(size, size);
    if (sparse_)
      J = Eigen::MatrixXd(sparse_jacobian(at, 0.0));
    else
      jacobian(t, at, 0.0, J);
    for (int k = 0; k < n_; ++k)
      if (is_held(k)) {
        J.row(k).setZero();
        J(k, k) = 1.0;
      }
    Eigen::VectorXd rows = J.cwiseAbs().rowwise().maxCoeff();
    for (int k = 0; k < size; ++k) rows(k) = rows(k) > 0 ? 1.0 / rows(k) : 1.0;
    Eigen::MatrixXd scaled = rows.asDiagonal() * J;
    Eigen::VectorXd columns = scaled.cwiseAbs().colwise().maxCoeff().transpose();
    for (int k = 0; k < size; ++k) columns(k) = columns(k) > 0 ? 1.0 / columns(k) : 1.0;
    scaled = scaled * columns.asDiagonal();
    auto cod = std::make_shared<Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd>>();
    cod->setThreshold(1e-10);
    cod->compute(scaled);
    return [cod, rows, columns](const Eigen::VectorXd& r) -> Eigen::VectorXd {
      return columns.cwiseProduct(cod->solve(-rows.cwiseProduct(r)));
    };
  };
  Eigen::VectorXd polished = y;
  if (damped_newton(polished, 20, iterations, evaluate, linearise)) y = polished;
}

// Damped Newton's method from y: a step dy = step(r) from the linearisation at the iterate, halved
// until the natural monotonicity test passes (the next residual's step, with the same
// linearisation, shrinks by 1 - lambda/4; as in solve_pairs); converged when the step is below
// 1e-3 in IDA's error weights, y then the last iterate plus its step. False (y unchanged) when a
// residual or a step is not finite, the test fails at every lambda, or after `max_iterations`.
bool ShockleyDae::damped_newton(Eigen::VectorXd& y, int max_iterations, long* iterations,
                                const std::function<bool(const Eigen::VectorXd&, Eigen::VectorXd&)>& evaluate,
                                const std::function<NewtonStep(const Eigen::VectorXd&)>& linearise) const {
  const int size = static_cast<int>(y.size());
  Eigen::VectorXd r(size), weights(size), yk = y, y_try;
  auto norm = [&](const Eigen::VectorXd& d, const Eigen::VectorXd& at) {
    error_weights(at, weights);
    return std::sqrt(d.cwiseProduct(weights).squaredNorm() / size);
  };
  for (int it = 0; it < max_iterations; ++it) {
    if (!evaluate(yk, r)) return false;
    if (iterations) ++*iterations;
    const NewtonStep step = linearise(yk);
    const Eigen::VectorXd dy = step(r);
    if (!dy.allFinite()) return false;
    const double dy_norm = norm(dy, yk);
    if (dy_norm <= 1e-3) {
      y = yk + dy;
      return true;
    }
    bool accepted = false;
    for (double lambda = 1.0; lambda > 1e-10 && !accepted; lambda *= 0.5) {
      y_try = yk + lambda * dy;
      accepted = evaluate(y_try, r) && norm(step(r), yk) <= (1 - lambda / 4) * dy_norm;
    }
    if (!accepted) return false;
    yk = y_try;
  }
  return false;
}

}  // namespace lcs
