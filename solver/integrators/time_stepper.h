// Fixed-step time-stepping methods for an LCS (Stewart 8.4): one LCP per step.
#pragma once

#include <memory>
#include <string>

#include <Eigen/Dense>

#include "solver/integrators/multistability.h"
#include "solver/lcp/lcp.h"
#include "solver/lcp/sparse_active_set.h"
#include "solver/model/lcs_problem.h"

namespace lcs {

// What a run cost, for `--stats` and `bench`. Fields a method does not use stay 0.
struct StepperStats {
  long steps = 0;           // accepted steps (internal steps for adaptive methods)
  LcpWarmStats lcp;         // summed over the cached LCP matrices
  int factorisations = 0;   // distinct step sizes (time-stepping) or mode/step pairs (event) prepared
  long events = 0;          // located switching events (event, smooth)
  long mode_switches = 0;   // active-set changes (event)
  int modes = 0;            // distinct modes visited (event)
  long rejected_steps = 0;  // error-test or convergence failures (smooth)
  long restarts = 0;        // fresh starts after IDA failed a step repeatedly (smooth)
  long residual_evals = 0;  // DAE residual evaluations (smooth)
  long jacobian_evals = 0;  // Jacobian evaluations (smooth)
  long newton_iterations = 0;
  SparseActiveSetStats sparse;  // time-stepping on the sparse system (large circuits)
  long sparse_fallbacks = 0;    // steps the sparse active-set search left to Lemke
  long switching_steps_by_euler = 0;  // theta < 1: steps taken by implicit Euler at stiff mode changes
  int descriptor_unknowns = 0;  // > 0: steps solved on the descriptor form, of this many unknowns
  long cache_budget_bytes = 0;  // event: the exponential cache's budget (0: no cache)
  long cache_peak_bytes = 0;    // and the most it held
  long cache_evictions = 0;     // exponentials dropped for the budget
  long exponential_actions = 0;  // event: steps taken by the exponential's action instead
  long action_products = 0;      // and the matrix-vector products they took
  long mode_cache_budget_bytes = 0;  // event: the modes' budget (0: not bounded, lines)
  long mode_cache_peak_bytes = 0;    // and the most they held
  long mode_evictions = 0;           // modes dropped for the budget
  long mode_rebuilds = 0;            // and built again
  long taylor_segments = 0;     // event with lines: history segments kept as Taylor series
  long exact_segments = 0;      // and those kept as exact products (taylor_segment.h)
};

// Advances (x, z) of a circuit's LCS. Step() is the non-virtual entry point (Drake style).
class TimeStepper {
 public:
  explicit TimeStepper(const LcsProblem& model) : model_(model) {}
  virtual ~TimeStepper() = default;

  // z at t0+ consistent with x at t0, for a run with step h (methods that reuse z_n need it).
  // On entry z may hold the operating point's z (else zeros): where the start's LCP has several
  // solutions, the one with its active set is kept.
  void Start(double t0, double h, const Eigen::VectorXd& x, Eigen::VectorXd& z) {
    DoStart(t0, h, x, z);
  }
  // From (x, z) at t to t + h. Throws NumericalFailure when the step's LCP has no solution.
  void Step(double t, double h, Eigen::VectorXd& x, Eigen::VectorXd& z) {
    DoStep(t, h, x, z);
    ++stats_.steps;
  }
  virtual StepperStats stats() const { return stats_; }
  // What the user is told once (several solutions of a step's LCP, kept continuous).
  const std::vector<std::string>& notes() const { return multistability_.notes(); }

 protected:
  virtual void DoStart(double t0, double h, const Eigen::VectorXd& x, Eigen::VectorXd& z) = 0;
  virtual void DoStep(double t, double h, Eigen::VectorXd& x, Eigen::VectorXd& z) = 0;
  const LcsProblem& model_;
  StepperStats stats_;
  MultistabilityNotes multistability_;
};

}  // namespace lcs
