// `--method smooth`: the penalty/smoothing method of Stewart 8.2. Every complementarity pair of
// the circuit's LCS becomes its diode's Shockley law (shockley_dae.h), and the resulting index-1
// DAE is integrated by SUNDIALS IDA (variable-order BDF, dense Jacobian given analytically).
//
// Sources' breakpoints (PULSE and PWL corners, SIN start) are IDA stop times; after each the
// integration restarts from a consistent state (IDAReInit + IDACalcIC), so a jump in a source is
// taken exactly. A switching event is a diode current crossing zero, located by IDA's root finder
// on the curve parameters (shockley_dae.h), which change sign with the currents; a source jump
// that switches a diode is an event at the jump. Output rows take
// the diode variables consistent with the interpolated states. A circuit without states has no
// differential equation: it is a Newton solve per output time, with crossings between output
// times located by regula falsi.
#pragma once

#include <memory>
#include <vector>

#include "solver/integrators/continuous_method.h"
#include "solver/integrators/guarded_method.h"
#include "solver/integrators/method_registry.h"
#include "solver/integrators/shockley_dae.h"

namespace lcs {

class ThetaMethod;

class SmoothMethod : public ContinuousMethod, public GuardedMethod {
 public:
  static constexpr double kDefaultRtol = 1e-6, kDefaultAtol = 1e-9;

  SmoothMethod(const LcsProblem& model, const MethodOptions& options);
  ~SmoothMethod() override;
  StepperStats stats() const override { return stats_; }
  void start_at_operating_point(std::vector<bool> held,
                                std::vector<std::pair<Eigen::VectorXd, Eigen::VectorXd>> other_starts) override {
    StartAtOperatingPoint(std::move(held), std::move(other_starts));
  }
  std::vector<std::string> run_notes() const override { return notes(); }

  // Switches (switched_adaptive.h): the guards are IDA root functions after the pairs', falling
  // through zero only; a root among them ends the segment. Circuits with states only.
  void set_guards(const SwitchGuards& guards) override;
  std::optional<GuardCrossing> RunSegment(const SegmentStart& start, const OutputGrid& grid, const Emit& emit,
                                          const Progress& progress = {}) override;

 protected:
  void DoRun(const Eigen::VectorXd& x0, const OutputGrid& grid, const Emit& emit,
             const Progress& progress) override;

 private:
  struct Schedule;  // output times and restart points
  class IdaRun;     // one run through IDA

  static Schedule make_schedule(const LcsProblem& model, const OutputGrid& grid);
  // Curve parameters s consistent with x at t: Newton from `s`, else from the ideal
  // (complementarity) solution, else from zero. Throws NumericalFailure when none converges.
  void consistent_pairs(double t, const Eigen::VectorXd& x, Eigen::VectorXd& s, double tstep);
  void at_rest(Eigen::VectorXd& s) const;
  bool rest_point(double t, Eigen::VectorXd& x, Eigen::VectorXd& s);
  void check_other_starts(double t, const Eigen::VectorXd& x, const Eigen::VectorXd& s);
  void leave_unstable_rest(double t, double tstop, Eigen::VectorXd& x, Eigen::VectorXd& s);
  static constexpr int kMaxUnstableCheckStates = 200;  // a dense eigenproblem of the states
  static constexpr double kVisibleGrowth = 36;          // e^36 * 1e-16: rounding grown to 0.4
  static constexpr double kDeparture = 1e-6;            // the displacement, of the states' size
  static bool switched(const Eigen::VectorXd& s, const Eigen::VectorXd& s_next);
  // No states: a Newton solve per output time; emit_state(t, s, event).
  void run_algebraic(const Schedule& schedule, Eigen::VectorXd s,
                     const std::function<void(double, const Eigen::VectorXd&, bool)>& emit_state);

  Eigen::VectorXd guard_values(double t, const Eigen::Ref<const Eigen::VectorXd>& y) const;
  std::vector<int> guards_below(double t, const Eigen::Ref<const Eigen::VectorXd>& y) const;

  ShockleyDae dae_;
  SwitchGuards guards_;
  int guard_count_ = 0;
  double rtol_, atol_;  // atol in volts (ShockleyDae::set_tolerances)
  std::unique_ptr<ThetaMethod> ideal_;  // for starting guesses, made when first needed
};

}  // namespace lcs
