// The switching LCP reduced to the pairs at zero (Stewart 4.5, the rational complementarity
// problem at a large s = 1/eta, restricted as in 8.3.3 to the pairs whose mode the state leaves
// open). With M(eta) z + q(eta) the implicit Euler LCP of a tiny step eta, the pairs at zero
// (index set I) have q_I = O(eta) -- their values vanish at the event, what is left is eta
// times their derivatives -- while the other pairs' entries are O(1). Solved whole, Lemke's
// tolerances (relative to |q|) cannot tell the O(eta) entries from zero: a Cockcroft-Walton
// multiplier's 11 pumping diodes, reaching VON together, came back all off. Holding the pairs
// with z > 0 on (w_α = 0 gives z_α) and leaving the others off, the LCP on I alone is the
// Schur complement
//   M_II - M_Iα M_αα^{-1} M_αI,    q_I - M_Iα M_αα^{-1} q_α,
// in which only the derivative terms remain; its solution says which pairs at zero turn on,
// whatever their number. The reduced q is w_I after the step with z_I = 0: w_I (zero at the
// event, up to how far past it the bisection stopped) + eta w_I' + O(eta^2). Where the caller
// knows w_I and its derivatives in the mode with I off, it passes
//   q_I = w_I + eta w_I' + eta^2 w_I'' + ...,  each term zero where it is zero within tolerance,
// instead (`derivatives`): the lexicographic order of 8.3.3 without the residual of w_I, which
// outweighs eta^2 w_I'' where w_I' = 0 (a clamp releasing at its source's peak).
// The answer is Lemke's final basis, not {z > 0}: a degenerate pair (z = w = 0) whose w = 0 row
// the basis needs is held on. Read as {z > 0}, a diode at zero current feeding a node that is
// otherwise reached only through a reverse-biased junction came back off, and the mode left the
// node floating (not well posed).
#pragma once

#include <optional>
#include <vector>

#include <Eigen/Dense>

namespace lcs {

// The pairs held on (active, not in `at_zero`) that have to join the reduced problem for
// M_αα to be nonsingular: those whose z the other held pairs leave undetermined (a junction at a
// node that floats unless a pair at zero conducts: its row and column in M_αα are zero). Kept
// greedily in pair order, a pair is held on if M over the held ones stays nonsingular.
std::vector<int> undetermined_held_pairs(const Eigen::MatrixXd& M, const std::vector<bool>& active,
                                         const std::vector<int>& at_zero);

// The active set: `active` outside `at_zero`, the reduced LCP's {z > 0} on it. Empty when the
// reduction is singular (M_αα) or the reduced LCP has no solution.
std::optional<std::vector<bool>> pairs_at_zero_lcp(const Eigen::MatrixXd& M, const Eigen::VectorXd& q,
                                                   const std::vector<bool>& active,
                                                   const std::vector<int>& at_zero,
                                                   const Eigen::VectorXd* derivatives = nullptr);

}  // namespace lcs
