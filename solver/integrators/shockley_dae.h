// The circuit's LCS with every complementarity pair replaced by its diode's Shockley law: the
// smoothing of Stewart 8.2, where 0 <= w ⟂ z >= 0 gives way to a smooth monotone curve.
//
//   dx/dt = A x + B z + E u(t),   w = C x + D z + F u(t),
//   i_k = phi_k(m_k) = IS (exp(-m_k / (N Vt)) - 1) - GMIN m_k   for every pair k,
//
// where i_k is the diode current and m_k = VON + RS i_k - v_k its margin (the voltage the
// junction does not take). A current-type pair (link diode) has z_k = i_k and w_k = m_k, a
// voltage-type one (tree diode) z_k = m_k and w_k = i_k.
//
// The unknowns are not z but one parameter s_k per diode along its curve (ShockleyCurve): the
// margin while the diode blocks, the current over -G0 while it conducts. With y = [x; s] the DAE
//
//   F(t, y, y') = [ x' - (A x + B z(s) + E u);  w(s) - (C x + D z(s) + F u) ] = 0
//
// is semi-explicit and index 1, and no row holds an exponential of an unknown: a conducting
// diode's margin is a logarithm of s, a blocking diode's current a decaying exponential of s.
// (So no exponential can overflow whatever s a Newton iterate tries: where SPICE codes continue
// exp linearly beyond an exponent of about 80, the one exponential left here, inside the
// logarithm's evaluation, is bounded; see kLargestRatio.)
// Newton's method on the plain law i - phi(m) faces exp(-m / N Vt) with N Vt = 1.3 mV (N = 0.05):
// a predictor 50 mV into forward bias is off by e^38, which is what SPICE's pnjlim limiting is
// for; IDA offers no such hook, and this parametrisation makes it unnecessary.
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <vector>

#include <Eigen/Dense>
#include <Eigen/Sparse>

#include "solver/model/lcs_problem.h"

namespace lcs {

// ngspice's diode puts GMIN (`.options gmin`, default 1e-12 S) across every junction; so do we,
// for the same model, and because without it a blocking diode whose current is an inductor's
// (i = -IS whatever the margin) leaves its margin undetermined.
constexpr double kGmin = 1e-12;

// A diode's curve i = phi(m), parametrised by s: m = s for s >= 0, and i = -G0 s for s < 0 with
// G0 = -phi'(0) = IS / (N Vt) + GMIN. Both branches meet at the origin with equal slopes (C^1),
// and the current and the margin change sign with s.
struct ShockleyCurve {
  double is = 1e-14;  // saturation current, A
  double nvt = 0;     // N Vt, V

  double g0() const { return is / nvt + kGmin; }
  struct Point {
    double current, margin;    // i, m
    double dcurrent, dmargin;  // di/ds, dm/ds
  };
  Point at(double s) const;
};

class ShockleyDae {
 public:
  // `sparse` false keeps the dense residual and Jacobian for every circuit (to compare the two).
  explicit ShockleyDae(const LcsProblem& model, bool sparse = true);

  int states() const { return n_; }
  // The largest step: devices with history bound it, and so does the deck's TMAX (set_max_step).
  double max_step() const { return std::min(model_.max_step(), max_step_); }
  void set_max_step(double h) { max_step_ = h > 0 ? h : INFINITY; }
  int pairs() const { return m_; }
  int size() const { return n_ + m_; }
  // Sources at t >= `end` take their left limit at `end`: a step that lands on a breakpoint
  // must not see a jump that happens there (the integrator restarts after it).
  void set_segment_end(double end) { segment_end_ = end; }

  // The LCS's z (currents of link diodes, margins of tree diodes) at the parameters s.
  Eigen::VectorXd complementarity_variables(const Eigen::VectorXd& s) const;
  // The parameters for a point near the ideal solution z_ideal at (t, x): conducting pairs keep
  // their current, blocking pairs their margin.
  Eigen::VectorXd parameters_from_ideal(double t, const Eigen::VectorXd& x,
                                        const Eigen::VectorXd& z_ideal) const;

  bool residual(double t, const Eigen::Ref<const Eigen::VectorXd>& y,
                const Eigen::Ref<const Eigen::VectorXd>& yp, Eigen::Ref<Eigen::VectorXd> r) const;
  // dF/dy + cj dF/dy'.
  void jacobian(double t, const Eigen::Ref<const Eigen::VectorXd>& y, double cj,
                Eigen::Ref<Eigen::MatrixXd> J) const;
  // A circuit whose LCS is kept sparse (sparse_lcs.h): the residual reads the sparse A, B, C, D
  // and the Jacobian is sparse, for KLU (smooth_method.cpp): O(nnz) a Jacobian and a residual
  // where the dense ones cost O((n + m)^2) and IDA's dense LU O((n + m)^3).
  bool sparse() const { return sparse_ != nullptr; }
  // The same Jacobian in compressed columns; its pattern (every entry of A, B, C, D and both
  // diagonals, explicit zeros kept) is the same at every call.
  const Eigen::SparseMatrix<double>& sparse_jacobian(const Eigen::Ref<const Eigen::VectorXd>& y, double cj) const;
  Eigen::VectorXd derivative(double t, const Eigen::VectorXd& x, const Eigen::VectorXd& s) const;
  // ds/dt on the solution through (x, s) at t, from differentiating the algebraic rows: IDACalcIC
  // leaves it to the caller, and without it IDA's first step after a start predicts s constant
  // through whatever fast relaxation the circuit begins with.
  Eigen::VectorXd parameter_rates(double t, const Eigen::VectorXd& x, const Eigen::VectorXd& s,
                                  const Eigen::VectorXd& xdot) const;

  // Tolerances: relative `rtol`, absolute `volts` (capacitor voltages; margins), `volts` times
  // ngspice's ABSTOL/VNTOL (1 pA / 1 uV) for inductor currents: an inductor feeding a blocking
  // diode carries -IS - GMIN m, and a tolerance of nanoamperes on it would leave m free by a
  // thousand volts. `voltage_scale`: the largest source voltage of the run (see error_weights).
  void set_tolerances(double rtol, double volts, double voltage_scale);
  // IDA's error weights of y = [x; s]: 1 / (rtol |x_k| + atol_k) for the states. Each diode is
  // weighed by its margin, whether it blocks or conducts: an error ds moves the margin by
  // dm/ds ds, which for a conducting diode is N Vt times the current's relative error. A margin is
  // a difference of node voltages and cannot be known better than rtol times the voltages it is
  // made of (the larger of voltage_scale and the capacitor voltages), however small it is itself;
  // and it must be known to a small fraction of N Vt (an error of N Vt is a factor e in the
  // current, and Newton's method would start decades away): to 1 % of N Vt at most.
  bool error_weights(const Eigen::Ref<const Eigen::VectorXd>& y, Eigen::Ref<Eigen::VectorXd> w) const;

  // s consistent with x at t by Newton's method (damped), from the s given, to well inside the
  // error weights. Returns false (s unchanged) when it does not converge. Counts its iterations
  // in *iterations (may be null).
  bool solve_pairs(double t, const Eigen::VectorXd& x, Eigen::VectorXd& s, long* iterations) const;
  // The smoothed circuit's own DC operating point near the ideal one: y = [x; s] with dx/dt = 0
  // and the pair rows on their curves, by damped Newton from y (as solve_pairs, on the whole
  // system). States marked `held` (set by IC= or .ic) keep their value. A state the DC equations
  // leave free (a capacitor with no DC path) is pulled toward its value in y (see the .cpp), and
  // the pull's error taken out again where the circuit is small enough for a dense polish.
  // Returns false (y unchanged) when Newton's method does not converge. Needs set_tolerances first.
  bool solve_rest_point(double t, Eigen::VectorXd& y, const std::vector<bool>& held, long* iterations) const;
  // The sources at t; at the segment's end their values before it (a jump there is the next
  // segment's).
  Eigen::VectorXd inputs(double t) const;

 private:
  void polish_rest_point(double t, Eigen::VectorXd& y, const std::vector<bool>& held, const Eigen::VectorXd& y0,
                         long* iterations) const;
  using NewtonStep = std::function<Eigen::VectorXd(const Eigen::VectorXd&)>;  // residual -> step
  bool damped_newton(Eigen::VectorXd& y, int max_iterations, long* iterations,
                     const std::function<bool(const Eigen::VectorXd&, Eigen::VectorXd&)>& evaluate,
                     const std::function<NewtonStep(const Eigen::VectorXd&)>& linearise) const;
  static constexpr int kPolishMaxUnknowns = 400;  // dense: O(size^3) an iteration
  // The diodes' part of error_weights, at states x and parameters s.
  void pair_weights(const Eigen::Ref<const Eigen::VectorXd>& x,
                    const Eigen::Ref<const Eigen::VectorXd>& s, Eigen::Ref<Eigen::VectorXd> w) const;
  // z(s), w(s) from the curves, and their derivatives dz/ds, dw/ds (diagonal).
  void on_curves(const Eigen::Ref<const Eigen::VectorXd>& s, Eigen::VectorXd& z, Eigen::VectorXd& w,
                 Eigen::VectorXd* dz, Eigen::VectorXd* dw) const;

  // A x + B z + E u, C x + F u and D z, on the sparse LCS when there is one, else the dense.
  Eigen::VectorXd state_rate(const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::VectorXd& z,
                             const Eigen::VectorXd& u) const;
  Eigen::VectorXd pair_rows(const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::VectorXd& u) const;
  Eigen::VectorXd d_times(const Eigen::VectorXd& z) const;

  const LcsProblem& model_;
  const SparseLcs* sparse_ = nullptr;
  mutable Eigen::SparseMatrix<double> sparse_jacobian_;
  mutable std::vector<Eigen::Triplet<double>> triplets_;
  double segment_end_ = INFINITY;
  int n_ = 0, m_ = 0;
  std::vector<ShockleyCurve> curves_;
  std::vector<bool> voltage_type_;
  mutable Eigen::VectorXd z_, w_, dz_, dw_;
  double rtol_ = 1e-6, margin_atol_ = 1e-9, voltage_scale_ = 0;
  double max_step_ = INFINITY;
  Eigen::VectorXd state_atol_;
  std::vector<bool> capacitor_;
};

}  // namespace lcs
