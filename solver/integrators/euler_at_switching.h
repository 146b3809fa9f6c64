// Steps in which the mode changes, checked against implicit Euler's step from the same start, for
// the methods that are not monotone (the θ-method with θ < 1, Radau IIA). A mode change can start
// the new mode's fast components far from their slow manifold. The trapezoidal rule then rings
// them (R(∞) = -1 for θ = 1/2, near -1 above it) and Radau's stage LCP (not a P-matrix even for
// diodes: 𝒜 is not positive definite, 8.4.2) can end a step beyond where the mode would have
// ended it; complementarity then holds what the step overshot (a diode that turns off at the top
// of an overshoot keeps its capacitor there for the rest of the run). Implicit Euler is L-stable
// and monotone on RC circuits (8.4: R(z) = 1/(1 - z) in (0, 1) for z < 0).
//
// Euler's step is taken instead where (a) it ends in another mode, or (b) the two steps diverge:
// |x - x_E| > 3/4 (|x - x_0| + |x_E - x_0|) (max norms; by the triangle inequality the ratio is
// at most 1, reached when they move in opposite directions). Elsewhere the method's own step is
// kept, and with it its order: where a switching does not excite fast components the two differ
// by Euler's O(h^2) error against steps of O(h) (the LC-tank bridge, whose diodes switch every
// half period, stays at the trapezoidal rule's 2.4e-3 and Radau's third and fifth order; taking
// every switching step by Euler made the tank's error 5.3e-3 and a 200-rectifier bank's 5 times
// the trapezoidal rule's). Measured ratios at the steps (b) took: 0.77-1 on the multiplier below
// and the peak detectors; a RON = 0 bridge's turn-on from zero current, where both steps barely
// move, 0.67 (taking Euler's there made radau5's error 1.2e-7 A instead of 1.9e-8 A), hence 3/4.
// SPICE takes the step after every breakpoint by backward Euler for the same reason.
//   Peak detector, 1 uF, RON 0.05 (τ = 50 ns), 10 V from rest, h = 0.5 us: the trapezoidal rule
//   turns on to 7.75 V with 31 A, then ends the next step at 15.5 V with the diode off and stays
//   there; Euler's step from 7.75 V ends at 9.16 V conducting (a), is taken, and the steps after
//   reach 9.3 V (exact) from below. A two-stage multiplier on a ±10 V square wave with 0.5 us
//   edges at h = 1 us reached 99.8 V with (a) alone (its bound is 37.2 V), 35.77 V with (b).
// The θ-method reads z at the start of its step, and after an index-one pair's switching (a
// capacitor clamped by a diode with RON = 0) Euler's z is the step's average current, not the
// current after it; so after a replaced step the θ-method takes one more step by Euler (in one
// mode, it ends with z consistent with x), as SPICE's backward Euler step after a breakpoint.
#pragma once

#include <memory>

#include <Eigen/Dense>

#include "solver/integrators/time_stepper.h"

namespace lcs {

class ThetaMethod;

// A pair conducts when its z is above this fraction of the largest z of the two compared: a z at
// rounding level is not a conducting diode (KLU and SparseLU leave different ones at degenerate
// steps, descriptor_step_test).
constexpr double kConductingFraction = 1e-9;
// True when some pair conducts in one of z_a, z_b and not in the other.
bool mode_changed(const Eigen::Ref<const Eigen::VectorXd>& z_a, const Eigen::Ref<const Eigen::VectorXd>& z_b);
// (b) above: the two steps from x0 to x and to x_euler diverge (apart by more than kDivergence of
// their combined motion).
constexpr double kDivergence = 0.75;
bool steps_diverge(const Eigen::VectorXd& x0, const Eigen::VectorXd& x, const Eigen::VectorXd& x_euler);

class EulerAtSwitching {
 public:
  // `sparse` as ThetaMethod's: large circuits step on the sparse system. `step_after`: after a
  // replaced step, the next one is Euler's too (the θ-method, which reads z).
  EulerAtSwitching(const LcsProblem& model, bool sparse, bool step_after);
  ~EulerAtSwitching();

  // Before a step of the main method: where it starts.
  void remember(const Eigen::VectorXd& x, const Eigen::VectorXd& z);
  // After it: where the mode at the end differs from the mode at the start, or `switched_inside`
  // (a collocation stage's mode differs from the start's), implicit Euler steps from the
  // remembered (x, z); where its mode differs or the steps diverge, its (x, z) replaces the
  // step's and true is returned.
  bool replace_switching_step(double t, double h, Eigen::VectorXd& x, Eigen::VectorXd& z,
                              bool switched_inside = false);
  // The step after a replaced one, when `step_after`: takes it by implicit Euler and returns true
  // (the main method does not step); false when none is due.
  bool euler_step_if_due(double t, double h, Eigen::VectorXd& x, Eigen::VectorXd& z);

  // Adds what the implicit Euler steps cost (LCP solves, factorisations) and how many were taken
  // to the main method's statistics.
  void add_cost_to(StepperStats& s) const;

 private:
  std::unique_ptr<ThetaMethod> euler_;
  bool step_after_;
  Eigen::VectorXd x_before_, z_before_, x_euler_, z_euler_;
  long taken_ = 0;
  bool step_after_due_ = false;
};

}  // namespace lcs
