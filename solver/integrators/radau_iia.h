// Radau IIA time-stepping for an LCS (8.4.1, Figure 8.2): s = 2 (order 3) or s = 3 (order 5)
// stages, all stages complementary, one LCP of size s*m per step. With X the stacked stage
// states, Z the stage complementarity variables and U_j = u(t + c_j h):
//   X = 1 ⊗ x + h(𝒜 ⊗ A) X + h(𝒜 ⊗ B) Z + h(𝒜 ⊗ E) U,   W_j = C X_j + D Z_j + F U_j,
//   0 <= W ⟂ Z >= 0,
// and, the method being stiffly accurate (b^T is the last row of 𝒜), x+ = X_s and z+ = Z_s.
// Eliminating X with N = I - h 𝒜 ⊗ A gives LCP(q, I⊗D + (I⊗C) N^-1 h(𝒜⊗B)).
// Radau IIA meets (RK1)-(RK4) of 8.4.1, under which 8.4.2 shows the stage system solvable for
// small h and 8.4.3 gives at least the stage order s on smooth stretches; inside one mode the
// LCS is a linear DAE and x reaches the classical order 2s - 1 (radau_iia_test measures it).
// A step across a switching instant is first order, as for any method that does not locate it.
#pragma once

#include <map>
#include <memory>

#include "solver/integrators/time_stepper.h"

namespace lcs {

// The Butcher tableau: c the nodes, a the stage matrix (b^T = its last row).
struct ButcherTableau {
  Eigen::VectorXd c;
  Eigen::MatrixXd a;
};

// Radau IIA with 2 or 3 stages, exact coefficients (Figure 8.2; Hairer & Wanner IV.5, Table
// 5.6). Throws std::invalid_argument for other stage counts.
ButcherTableau radau_iia_tableau(int stages);

class RadauIIA : public TimeStepper {
 public:
  RadauIIA(const LcsProblem& model, int stages);
  ~RadauIIA() override;
  StepperStats stats() const override;
  int stages() const { return static_cast<int>(tableau_.c.size()); }

 protected:
  // z at t0+ from consistent_start_z; Radau's steps do not use it, the t0 output row does.
  void DoStart(double t0, double h, const Eigen::VectorXd& x, Eigen::VectorXd& z) override;
  void DoStep(double t, double h, Eigen::VectorXd& x, Eigen::VectorXd& z) override;

 private:
  struct StepFactors;  // everything that depends only on h, prepared once per step size
  StepFactors& factors(double h);
  // The stage LCP has several solutions and the previous mode ended: solve it again from the
  // mode implicit Euler's step LCP chooses (its only stable solution).
  const LcpSolution& mode_from_euler(StepFactors& f, double t, double h, const Eigen::VectorXd& x,
                                     const Eigen::VectorXd& z);

  ButcherTableau tableau_;
  std::map<double, std::unique_ptr<StepFactors>> cache_;
  // Stacked stage inputs, the LCP's q, the end state: preallocated, DoStep does not allocate.
  Eigen::VectorXd U_, q_, x_next_;
};

}  // namespace lcs
