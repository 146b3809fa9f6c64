// Event-driven exact integration of an LCS (Stewart 8.3): inside a mode the circuit and its
// sources form one linear ODE, integrated exactly by matrix exponentials; switching events
// (a z or w component reaching zero) are located by bisection on cached exponentials; the next
// mode comes from the implicit Euler LCP with a tiny step (the rational complementarity problem
// of 4.5 at large s), checked against the mode's own derivatives; inconsistent states jump by
// the impulse LCP.
//
// Time is kept as exact dyadic fractions of the output step h0 (= TSTEP): every step has length
// h0 / 2^j and starts at a multiple of it, so each mode needs only the exponentials
// exp(M h0 / 2^j), j = 0, 1, ..., computed once per mode and source form and reused by every
// step, every bisection and every later visit (a periodic circuit pays setup once per mode).
#pragma once

#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "solver/integrators/continuous_method.h"
#include "solver/integrators/guarded_method.h"

namespace lcs {

struct EventOptions {
  // Events are located to a bracket of rtol * TSTEP (default 1e-13: close to machine precision).
  double rtol = 1e-13;
  // Consecutive events without progress (more than this at one instant) are reported as
  // chattering (exit 3) rather than looping.
  int max_events_at_one_time = 64;
  // Consecutive events each less than storm_spacing * TSTEP after the one before, more than
  // max_events_in_a_storm of them, are reported as chattering too (exit 3): no circuit switches
  // that often at that pace, but rounding can (a mode held by a 1 GOhm resistor near t = 0, every
  // 1.3e-13 s, which ran without end).
  int max_events_in_a_storm = 10000;
  double storm_spacing = 1e-7;
  // A run whose remaining steps, projected at the pace of its last 2^20 steps to TSTOP, pass this
  // is stopped (exit 3) instead of running for hours: a step is at most 0.5 / omega of the
  // fastest oscillation of the mode and its sources, so a 1 GHz sine over 1000 s is 1.7e13 steps.
  // The pace is the recent one and the bound generous (about half an hour of steps here): a
  // 1 MHz burst of 0.1 s in a 100 s run projects 1.6e9 at its end and then finishes in 1.3e6.
  double max_projected_steps = 1e10;
  // Bytes of exponentials exp(M h0 / 2^j) kept (exponential_cache.h); the least recently used
  // are recomputed past it.
  std::size_t exponential_cache_bytes = std::size_t(256) << 20;
  // Bytes of modes (their dense matrices) kept; past it the least recently used are built again
  // when needed. Not applied with lines (their history reads every mode of the run).
  std::size_t mode_cache_bytes = std::size_t(256) << 20;
  // Line history: each segment's waves as Taylor series (taylor_segment.h) where they converge
  // in a few pieces; false reads every segment through the product of exponentials.
  bool history_series = true;
};

class EventDriven : public ContinuousMethod, public GuardedMethod {
 public:
  EventDriven(const LcsProblem& model, const EventOptions& options);
  ~EventDriven() override;
  StepperStats stats() const override;

  // Guards as rows over the mode's [x; sigma], located by the bisection of a mode change to
  // 2^-stop_level TSTEP; a crossing is the first point of the bracket past the zero. Modes and
  // exponentials are kept from one segment to the next on the same grid.
  void set_guards(const SwitchGuards& guards) override;
  std::optional<GuardCrossing> RunSegment(const SegmentStart& start, const OutputGrid& grid, const Emit& emit,
                                          const Progress& progress = {}) override;

 protected:
  void DoRun(const Eigen::VectorXd& x0, const OutputGrid& grid, const Emit& emit,
             const Progress& progress) override;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  friend Eigen::VectorXd event_mode_z(const LcsProblem&, double, double, const Eigen::VectorXd&,
                                      const Eigen::VectorXd*);
};

// z at t0+ in the mode the event method would start in from the state x (x taken as it is, no
// jump): the switching LCP's mode, checked against its derivatives and index-one constraints,
// and searched around where that fails. For the time-stepping methods' start
// (start_complementarity.h). `op_z` (the operating point's z), where given, is the first guess
// when the switching LCP has no answer. Throws NumericalFailure when no mode fits x.
Eigen::VectorXd event_mode_z(const LcsProblem& model, double t0, double h_run, const Eigen::VectorXd& x,
                             const Eigen::VectorXd* op_z = nullptr);

}  // namespace lcs
