// One step size's θ-method step on a circuit's descriptor form (solver/model/sparse_descriptor.h):
// the mixed LCP
//
//   (K0 + hθ K1) y+ + Lz z+ = Sx x + h(1-θ) Sy y + Uin u(t+h),
//   w+ = P y+ + Fw u(t+h),   0 <= w+ ⟂ z+ >= 0,   x+ = X y+,
//
// solved by the sparse active-set method (solver/lcp/sparse_active_set.h: warm start from the
// last mode, block flips, Murty's rule, factorisations cached per mode). Rows are scaled to unit
// size first (capacitor rows hold C ~ 1e-5 next to KCL's ±1); that changes no solution.
//
// Cost per step (N = nodes + branches + pairs unknowns, O(1) nonzeros a row): the right-hand
// side O(nnz); a warm hit in the base mode one pair of KLU triangular solves, O(nnz(LU)); a mode
// k <= 32 pairs from the base those solves plus k columns (each a pair of solves, once per base)
// and O(k N) for the update, and one refinement on the accepted mode; a mode further away, or
// one the warm start found again after an update, one KLU numeric factorisation (the symbolic
// analysis is made once). For a multiplier's chain nnz(LU) grows like N (500 stages: N = 4003,
// nnz(L + U) = 23-24k), so a step costs O(N) times the rounds of its mode search, where the
// dense LCP's costs O(N^2) and its Lemke pivots O(N^2) each. Measured at 500 stages (1000 steps
// of 100 us, `lcspice run --method euler --stats`): 91 % warm hits, 0.20-0.29 ms a step.
//
// θ < 1 needs y at the start of the step: the last step's y+ when (x, z) are what it returned,
// else the circuit solved at that instant with x and z given (Kst, factorised once).
#pragma once

#include <memory>

#include <Eigen/Dense>
#include <Eigen/Sparse>

#include "solver/lcp/sparse_active_set.h"
#include "solver/model/lcs_problem.h"
#include "solver/model/sparse_descriptor.h"

namespace lcs {

class DescriptorStep {
 public:
  DescriptorStep(const SparseDescriptor& d, double h, double theta);
  ~DescriptorStep();
  DescriptorStep(const DescriptorStep&) = delete;
  DescriptorStep& operator=(const DescriptorStep&) = delete;

  // (x, z) at t to t + h. False when the mode search fails or the instant's system is singular
  // (x and z are then untouched: the caller's dense LCP decides the step).
  bool step(const LcsProblem& model, double t, Eigen::VectorXd& x, Eigen::VectorXd& z);
  // The same step, ending at t_end (its inputs read there): a step of length h is taken, but
  // t_end - h + h need not round to t_end when h is large (descriptor_operating_point.h).
  bool step_ending_at(const LcsProblem& model, double t_end, Eigen::VectorXd& x, Eigen::VectorXd& z);
  // The next step's first guess is the mode of the z it is given, not the last step's (another
  // method took the last step: euler_at_switching.h).
  void guess_from_given_mode() { fresh_ = true; }
  const SparseActiveSetStats& stats() const { return lcp_->stats(); }
  const Eigen::VectorXd& last_w() const { return w_; }  // w+ of the last step

 private:
  bool start_values(const LcsProblem& model, double t, const Eigen::VectorXd& x,
                    const Eigen::VectorXd& z);
  bool advance(const LcsProblem& model, double t, double t_end, Eigen::VectorXd& x, Eigen::VectorXd& z);

  const SparseDescriptor& d_;
  double h_, theta_;
  Eigen::VectorXd scale_;  // the rows' scale factors
  std::unique_ptr<SparseActiveSetLcp> lcp_;
  bool fresh_ = true;      // no step yet: its first mode comes from the z it is given
  struct Instant;          // θ < 1: Kst's factorisation, made at the first need
  std::unique_ptr<Instant> instant_;
  Eigen::VectorXd y_, x_last_, z_last_;  // the last y+ and the (x, z) it gave
  Eigen::VectorXd a_, b_, u_, y_next_, z_next_, w_;
};

}  // namespace lcs
