// Methods that choose their own steps (event-driven 8.3, smooth 8.2): they integrate the whole
// interval and report the state at every output time and at every switching event (SPEC §3).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "solver/integrators/time_stepper.h"
#include "solver/model/lcs_problem.h"

namespace lcs {

// Output times: every multiple of `tstep` in [0, tstop] (tstop itself included), plus `extra`
// (sorted, inside (0, tstop]; `bench` asks for a reference at another solver's time points).
struct OutputGrid {
  double tstep = 0, tstop = 0;
  std::vector<double> extra;
};

class ContinuousMethod {
 public:
  // t, LCS state x, complementarity variables z (for `smooth`: the smooth diode currents and
  // margins in the same places), and whether t is a switching event rather than a grid time.
  using Emit = std::function<void(double t, const Eigen::VectorXd& x, const Eigen::VectorXd& z,
                                  bool event)>;
  // Called now and then with the time reached, for progress reports.
  using Progress = std::function<void(double t)>;

  explicit ContinuousMethod(const LcsProblem& model) : model_(model) {}
  virtual ~ContinuousMethod() = default;

  // From x0 at t = 0 (before any jump an inconsistent x0 causes) to grid.tstop. Emits t = 0 first
  // (after the jump), then strictly increasing times. Throws NumericalFailure.
  void Run(const Eigen::VectorXd& x0, const OutputGrid& grid, const Emit& emit,
           const Progress& progress = {}) {
    DoRun(x0, grid, emit, progress);
  }
  virtual StepperStats stats() const { return stats_; }
  // The run starts at the circuit's DC operating point (not UIC), x0 the ideal model's; `held`
  // marks the states IC= or .ic set there. A method of the smoothed circuit then starts from that
  // circuit's own operating point (smooth_method.h); the others from x0 as it is.
  // `z` is the operating point's complementarity variables (its mode).
  void StartAtOperatingPoint(std::vector<bool> held,
                             std::vector<std::pair<Eigen::VectorXd, Eigen::VectorXd>> other_starts = {},
                             Eigen::VectorXd z = {}) {
    start_at_rest_ = true;
    held_ = std::move(held);
    other_starts_ = std::move(other_starts);
    start_z_ = std::move(z);
  }
  // What the run's warnings should say about how the method ran.
  const std::vector<std::string>& notes() const { return notes_; }

 protected:
  virtual void DoRun(const Eigen::VectorXd& x0, const OutputGrid& grid, const Emit& emit,
                     const Progress& progress) = 0;
  const LcsProblem& model_;
  StepperStats stats_;
  bool start_at_rest_ = false;
  std::vector<bool> held_;
  std::vector<std::pair<Eigen::VectorXd, Eigen::VectorXd>> other_starts_;  // InitialState::other_starts
  Eigen::VectorXd start_z_;  // InitialState::z, when start_at_rest_
  std::vector<std::string> notes_;
};

}  // namespace lcs
