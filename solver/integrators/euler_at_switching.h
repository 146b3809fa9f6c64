// The θ-method's stiff switching steps, checked against implicit Euler's step from the same start.
// With θ < 1 the method is not L-stable: its stability function R(z) = (1 + (1-θ)z)/(1 - θz) is
// negative for z < -1/(1-θ) (z = hλ; -2 for the trapezoidal rule) and tends to -(1-θ)/θ. A mode
// change whose new fast components have h|λ| beyond that starts them far from their slow
// manifold, the method rings them, and complementarity holds what a ring overshot: a diode that
// turns off at the top of an overshoot keeps its capacitor there for the rest of the run. Implicit
// Euler is L-stable and monotone on RC circuits (8.4: R(z) = 1/(1 - z) in (0, 1) for z < 0).
//
// So at a step whose mode changes (a pair conducts at one end and not at the other) and which is
// stiff for a pair conducting at either end (h r_i > 1/(1-θ), r_i = Σ_j |(CB)_ij| / D_ii the rate
// at which conduction through pair i moves the state: 1/(RON C) for a diode charging C through
// RON, infinite for an index-one pair), implicit Euler also steps from the same start, and its
// step is taken where (a) it ends in another mode, or (b) the two steps diverge: some state moves
// |x_i - x_E,i| > 3/4 (|x_i - x_0,i| + |x_E,i - x_0,i|) (by the triangle inequality the ratio is
// at most 1, reached when they move in opposite directions), by more than 1e-3 of its size (a
// state at a turning point, an inductor current at its peak, moves O(h^2) either way). The
// step after a replaced one is Euler's too: the θ-method reads z at the start of its step, and
// after an index-one pair's switching (a capacitor clamped with RON = 0) Euler's z is the step's
// average current, not the current after it. SPICE takes the step after a breakpoint by backward
// Euler for the same reason.
//   Peak detector, 1 uF, RON 0.05 (τ = 50 ns), 10 V from rest, h = 0.5 us (h r = 10): the
//   trapezoidal rule turns on to 7.75 V with 31 A, then ends the next step at 15.5 V with the
//   diode off and stayed there; Euler's step from 7.75 V ends at 9.16 V conducting (a), is
//   taken, and the run reaches 9.3 V (exact) from below. A two-stage multiplier on a ±10 V
//   square wave with 0.5 us edges at h = 1 us reached 260 V (bound 37.2 V), 99.8 V with (a)
//   alone; with (b), 35.77 V (implicit Euler 35.76, event 36.29).
// Where switchings are not stiff (h r below the bound: a clamp behind 10 ohm, a rectifier's RC
// load) no step is checked and the method keeps its order: a reviewer measured the check without
// this gate (and on Radau, which no longer has it) making a clamp's and a half-wave rectifier's
// errors 5-70 times larger, for (b) also fires at ordinary turn-offs inside a step.
#pragma once

#include <memory>

#include <Eigen/Dense>

#include "solver/integrators/time_stepper.h"

namespace lcs {

class ThetaMethod;

// A pair conducts when its z is above this fraction of the largest z of the two compared (and
// above 0): a z at rounding level is not a conducting diode (KLU and SparseLU leave different
// ones at degenerate steps, descriptor_step_test).
constexpr double kConductingFraction = 1e-9;
// True when some pair conducts in one of z_a, z_b and not in the other.
bool mode_changed(const Eigen::VectorXd& z_a, const Eigen::VectorXd& z_b);
// (b) above: the two steps from x0 to x and to x_euler diverge in some state.
constexpr double kDivergence = 0.75;
bool steps_diverge(const Eigen::VectorXd& x0, const Eigen::VectorXd& x, const Eigen::VectorXd& x_euler);
// r_i above for every pair (conduction_rates.h; tree diodes 0); empty when the circuit's LCS is neither
// sparse nor formed dense (then every switching step is checked).
Eigen::VectorXd pair_rates(const LcsProblem& model);

class EulerAtSwitching {
 public:
  // `sparse` as ThetaMethod's: large circuits step on the sparse system.
  EulerAtSwitching(const LcsProblem& model, double theta, bool sparse);
  ~EulerAtSwitching();

  // Before a step of the θ-method: where it starts.
  void remember(const Eigen::VectorXd& x, const Eigen::VectorXd& z);
  // After it: at a stiff step whose mode changed, implicit Euler steps from the remembered
  // (x, z); where (a) or (b) holds its (x, z) replaces the step's and true is returned.
  bool replace_switching_step(double t, double h, Eigen::VectorXd& x, Eigen::VectorXd& z);
  // The step after a replaced one: takes it by implicit Euler and returns true (the θ-method
  // does not step); false when none is due.
  bool euler_step_if_due(double t, double h, Eigen::VectorXd& x, Eigen::VectorXd& z);

  // Adds what the implicit Euler steps cost (LCP solves, factorisations) and how many were taken
  // (replaced steps and the steps after them) to the θ-method's statistics.
  void add_cost_to(StepperStats& s) const;

 private:
  bool stiff(double h, const Eigen::VectorXd& z) const;
  std::unique_ptr<ThetaMethod> euler_;
  double stiff_bound_;     // 1/(1-θ): R(z) < 0 below -stiff_bound_
  Eigen::VectorXd rates_;  // pair_rates
  Eigen::VectorXd x_before_, z_before_, x_euler_, z_euler_;
  long taken_ = 0;
  bool step_after_due_ = false;
};

}  // namespace lcs
