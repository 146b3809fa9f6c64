// Adaptive methods that integrate one configuration of a circuit's switches at a time
// (switched_adaptive.h): they watch the switches' controls as guards and end a run segment where
// one crosses its threshold, so that the next configuration's model continues from there.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "solver/integrators/continuous_method.h"
#include "solver/integrators/dyadic_time.h"
#include "solver/integrators/time_stepper.h"

namespace lcs {

// Ideal switches (S, W) as guards of an adaptive method (switched_adaptive.h): guard k is
// sign_k (control_k - threshold_k), the control a linear output G x + H z + J u + K u' of one
// configuration's model, and stays positive while switch k keeps its state (off: VT + VH -
// control; on: control - (VT - VH)). A guard falling below zero is an event, located as the
// method locates its own, that ends the run segment: the configuration changes there.
struct SwitchGuards {
  Eigen::MatrixXd G, H, J, K;
  Eigen::VectorXd threshold, sign;
};

// Where a run segment starts: a time of the event method's dyadic grid (of the output step h0;
// other methods read `t`) and its value in seconds, the state x, and the sources' state the
// segment before reached there (the event method's sigma of `signature`; empty: read from the
// waveforms at t).
struct SegmentStart {
  DyadicTime at;
  double t = 0;
  Eigen::VectorXd x;
  std::string signature;
  Eigen::VectorXd sigma;
  // At the run's start (not UIC): the operating point's z. Its mode is the first tried, so a
  // circuit with several modes consistent with x (a monostable's capacitor state fits both of its
  // states) starts in the one its operating point has. Empty: none.
  Eigen::VectorXd op_z;
};

// Where a segment ended: the first point located past a guard's zero, the state and sources
// there, and the guards that crossed.
struct GuardCrossing {
  SegmentStart at;
  std::vector<int> crossed;
};

class GuardedMethod {
 public:
  virtual ~GuardedMethod() = default;
  // The switch guards of the configuration this model is (before the first segment).
  virtual void set_guards(const SwitchGuards& guards) = 0;
  // From `start` to grid.tstop, or to the first guard crossing (returned; no row is emitted
  // there, the next configuration's segment writes it). A guard already below zero at the
  // start (beyond rounding) is a crossing at the start itself.
  virtual std::optional<GuardCrossing> RunSegment(const SegmentStart& start, const OutputGrid& grid,
                                                  const ContinuousMethod::Emit& emit,
                                                  const ContinuousMethod::Progress& progress) = 0;
  virtual StepperStats stats() const = 0;
  // The first segment starts at the circuit's DC operating point (not UIC); `held` marks the
  // states IC= or .ic set (ContinuousMethod::StartAtOperatingPoint). Methods of the ideal
  // circuit start from the state they are given.
  virtual void start_at_operating_point(std::vector<bool> /*held*/,
                                        std::vector<std::pair<Eigen::VectorXd, Eigen::VectorXd>> /*other_starts*/) {}
  // What the run's warnings should say about how the method ran.
  virtual std::vector<std::string> run_notes() const { return {}; }
};

}  // namespace lcs
