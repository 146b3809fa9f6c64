// Perfectly coupled inductors (`K L1 L2 1`): the windings of an ideal transformer's magnetising
// branch. Their inductance matrix is s s^T (s = [sqrt L1, sqrt L2]), so the state equations
//
//   Mdyn x' = Rx x + Rw [z u du] + Kdu du        (Mdyn = Tc^T C Tc + Tl^T Lf Tl, symmetric >= 0)
//
// have a singular Mdyn. A current pattern N with Mdyn N = 0 carries no flux: it has no dynamics
// of its own (Stewart 1.3.1: circuits of passive elements, transformers included, are of index
// zero or one; 3.2: the index counts the differentiations that determine the algebraic part).
// With x = T xi + N eta (T selects the states that stay), the rows N^T of the equations are the
// algebraic constraint (the transformer's voltage ratio),
//
//   N^T Rx N eta = -N^T (Rx T xi + Rw [z u])      (N^T Mdyn = 0, and N^T Kdu = 0),
//
// solvable for eta when S = N^T Rx N is invertible: the flux-free current sees resistance or
// diodes. The rows T^T are the dynamics of the kept states, T^T Mdyn T xi' = T^T (...), with
// T^T Mdyn T positive definite. Capacitors never take part: C > 0 makes Tc N = 0.
#pragma once

#include <vector>

#include <Eigen/Dense>

namespace lcs {

struct FluxReduction {
  std::vector<int> kept;        // states that stay states (ascending)
  std::vector<int> eliminated;  // states that become algebraic (ascending)
  // n x e, Mdyn N = 0, normalised so that N(eliminated[a], b) = delta_ab: eta = x_eliminated.
  Eigen::MatrixXd N;
  // n x r: column j selects state kept[j]. x = T xi + N eta and xi = x_kept - N_kept x_eliminated.
  Eigen::MatrixXd T;

  bool empty() const { return eliminated.empty(); }
};

// The flux-free patterns of Mdyn (symmetric, positive semidefinite) and which states leave:
// within each group of states that Mdyn couples, the last ones in state order go (so the first
// winding of a transformer keeps the state). `size` is what Mdyn's diagonal would be without
// cancellation (> 0: every state has its own C or L): Mdyn scaled by it counts as singular where
// an eigenvalue is at most kFluxFreeTolerance, so k within about 1e-12 of 1 is k = 1, and two
// equal windings in series opposition with k = 1 leave no state at all. Empty when Mdyn is
// nonsingular. Only groups with a state in `may_be_flux_free` are examined: capacitances are
// positive, so a group of capacitor voltages is never singular (and one that a capacitor loop
// couples can hold every state of a large circuit, whose eigen-decomposition would cost O(n^3)).
FluxReduction flux_reduction(const Eigen::MatrixXd& Mdyn, const Eigen::VectorXd& size,
                             const std::vector<bool>& may_be_flux_free);

constexpr double kFluxFreeTolerance = 1e-12;

// Columns [x | rest] (rest: z, u, du; `n` = x's size) as a linear map of [xi | rest]:
// [x; rest] = Cmap [xi; rest], the eta rows solved from the constraint N^T R [x; rest] = 0.
// R (n x (n + rest)) is Mdyn x' = R [x; rest] without the du columns (which N^T annihilates).
// Returns false when S = N^T Rx N is singular (a higher-index circuit).
bool substitute_flux_free(const FluxReduction& reduction, const Eigen::MatrixXd& R, int n,
                          Eigen::MatrixXd& Cmap);

}  // namespace lcs
