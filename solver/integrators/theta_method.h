// The theta-method with one LCP per step (8.4): theta = 1 is implicit Euler, 1/2 trapezoidal.
//   x+ = x + h(1-θ)(A x + B z + E u) + hθ(A x+ + B z+ + E u+),   w+ = C x+ + D z+ + F u+
// gives LCP(q, D + hθ C W^-1 B) with W = I - hθ A (DESIGN.md). Circuits with many pairs and a
// sparse LCS solve the step on the sparse system instead, never forming W^-1 (ThetaMethod::
// SparseStep); circuits with many pairs whose LCS is dense but whose circuit is sparse (a
// multiplier) step on the circuit's descriptor form instead (descriptor_step.h). Both fall back
// to Lemke on the dense LCP for a step whose mode search fails. For theta < 1 a step whose mode
// changes and is stiff is checked against implicit Euler's (euler_at_switching.h).
#pragma once

#include <map>
#include <memory>

#include "solver/integrators/descriptor_step.h"
#include "solver/integrators/euler_at_switching.h"
#include "solver/integrators/time_stepper.h"
#include "solver/model/sparse_descriptor.h"
#include "solver/model/sparse_lcs.h"

namespace lcs {

class ThetaMethod : public TimeStepper {
 public:
  // `sparse`: large circuits with a sparse LCS step on the sparse system (else always dense).
  // A circuit with a descriptor form (sparse_descriptor.h) steps on it from `descriptor_pairs`
  // pairs on (tests lower it to compare the paths on smaller circuits).
  // `euler_at_switching`: stiff switching steps checked against implicit Euler's
  // (euler_at_switching.h); false, every step is the θ-method's.
  ThetaMethod(const LcsProblem& model, double theta, bool sparse = true,
              int descriptor_pairs = kDescriptorPairs, bool euler_at_switching = false);
  ~ThetaMethod() override;
  StepperStats stats() const override;
  // The next step's first guess of the mode is the z it is given (another method took the
  // last step: euler_at_switching.h).
  void guess_from_given_mode() { resume_ = true; }

 protected:
  void DoStart(double t0, double h, const Eigen::VectorXd& x, Eigen::VectorXd& z) override;
  void DoStep(double t, double h, Eigen::VectorXd& x, Eigen::VectorXd& z) override;

 private:
  void theta_step(double t, double h, Eigen::VectorXd& x, Eigen::VectorXd& z);
  struct StepFactors;  // everything that depends only on h, prepared once per step size
  StepFactors& factors(double h);
  // Large circuits: the step's LCP solved on the sparse system (sparse_active_set.h), per h.
  struct SparseStep;
  SparseStep* sparse_step(double h);
  std::shared_ptr<const SparseLcs> sparse_lcs_;  // null: the dense path (small or dense LCS)
  std::shared_ptr<const SparseDescriptor> descriptor_;  // null: no descriptor path
  std::map<double, std::unique_ptr<DescriptorStep>> descriptor_cache_;

  double theta_;
  std::unique_ptr<EulerAtSwitching> switching_;  // theta < 1 only
  bool resume_ = false;  // the next step's first guess is the mode of its z
  std::map<double, std::unique_ptr<StepFactors>> cache_;
  std::map<double, std::unique_ptr<SparseStep>> sparse_cache_;
  Eigen::VectorXd u0_, u1_, q_, a_, b_, y_, zs_, w_;
};

}  // namespace lcs
