// The LCS inside one mode (a fixed active set α, Stewart 8.3.1–8.3.2): with w_α = 0 and z_β = 0
// the system is a linear ODE
//   z_α = Kx x + Ku u + Kd u',    dx/dt = Ax x + Eu u + Ed u',    w_β = Wx x + Wu u + Wd u'.
// Index-zero rows of w_α = 0 (the range of D_αα) give z_α directly; index-one rows (N, the left
// null space of D_αα: N^T (C_α x + F_α u) = 0 constrains the state) are differentiated once,
// N^T C_α (A x + B_α z_α + E u) + N^T F_α u' = 0, and the drift that rounding leaves in the
// constraint itself is removed by projecting x along the impulse directions B_α N.
#pragma once

#include <vector>

#include <Eigen/Dense>

#include "solver/model/lcs_problem.h"

namespace lcs {

struct ModeDynamics {
  std::vector<int> active, inactive;  // pair indices
  bool well_posed = false;            // z_α is determined (the stacked system is nonsingular)
  double rcond = 1;                   // its reciprocal condition (FullPivLU estimate; 1 with no active pair)
  // Nonzero: D_αα's largest singular value counted zero (below 1e-13 of the largest,
  // `unresolved_beside`) while far above rounding: a resistance the mode cannot tell from zero.
  double unresolved = 0, unresolved_beside = 0;
  Eigen::MatrixXd Kx, Ku, Kd;         // |α| rows
  Eigen::MatrixXd Ax, Eu, Ed;         // n rows
  Eigen::MatrixXd Wx, Wu, Wd;         // |β| rows
  Eigen::MatrixXd Cc, Fc;             // index-one constraints Cc x + Fc u = 0 (k rows)
  Eigen::MatrixXd project;            // x -= project * (Cc x + Fc u) restores them (n × k)

  static ModeDynamics build(const Lcs& lcs, const std::vector<bool>& is_active);
};

}  // namespace lcs
