// The theta-method with one LCP per step (8.4): theta = 1 is implicit Euler, 1/2 trapezoidal.
//   x+ = x + h(1-θ)(A x + B z + E u) + hθ(A x+ + B z+ + E u+),   w+ = C x+ + D z+ + F u+
// gives LCP(q, D + hθ C W^-1 B) with W = I - hθ A (DESIGN.md).
#pragma once

#include <map>
#include <memory>

#include "solver/integrators/time_stepper.h"

namespace lcs {

class ThetaMethod : public TimeStepper {
 public:
  ThetaMethod(const LcsProblem& model, double theta);
  ~ThetaMethod() override;
  StepperStats stats() const override;

 protected:
  void DoStart(double t0, double h, const Eigen::VectorXd& x, Eigen::VectorXd& z) override;
  void DoStep(double t, double h, Eigen::VectorXd& x, Eigen::VectorXd& z) override;

 private:
  struct StepFactors;  // everything that depends only on h, prepared once per step size
  StepFactors& factors(double h);

  double theta_;
  std::map<double, std::unique_ptr<StepFactors>> cache_;
  Eigen::VectorXd u0_, u1_, q_;
};

}  // namespace lcs
