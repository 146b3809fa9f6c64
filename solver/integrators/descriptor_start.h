// The start's complementarity state z at t0 on a circuit's descriptor form (sparse_descriptor.h),
// for the circuits whose θ-steps are solved there: the dense start (start_complementarity.h)
// forms the dense LCS's W^-1, W^-1 B and C W^-1 B, O(n^3) (1.1 s of a 1000-diode multiplier's
// 2.7 s run), where this costs one sparse mode search.
//
// The dense start solves the implicit Euler step's LCP for a step h tiny against the circuit's
// rates; this solves its limit h -> 0, the circuit at the instant t0 with the states x given
// (Kst y = Xst x + Uin u - Lz z, w = P y + Fw u, 0 <= w ⟂ z >= 0), by the sparse active set.
// Where that solution is strictly complementary (every pair has z or w above 1e-9 of its sizes)
// and its mode's matrix is regular, the step's LCP for small h has the nearby solution of the
// same mode (the implicit function theorem), so both give the same z to O(h) (the dense start's
// h is 1e-8 of the run's step or less). Pairs at z = w = 0 (degenerate: what the dense start
// hands to the event method's mode selection) are accepted when the mode that holds them on
// with the conducting pairs is regular: then the solution is isolated (the pairs' rows and
// columns are independent), the step's LCP for small h has solutions within O(h) of it whichever
// way those pairs go, and their z, zero at t0, is continuous. Where that mode is singular (a
// diode to a node nothing else reaches: its potential is free, z not determined) the answer is
// taken when no free direction (the mode's null space, found from the solution's own mode by a
// k x k problem, SparseActiveSetLcp::mode_null_space) moves what a step reads of the instant's
// unknowns (the storage rows' Sy y; the states are given): the dense start's tiny-step LCP is as
// undetermined along it, and only unknowns no step reads keep the value found. Otherwise (an
// ideal diode across a capacitor at its threshold: the current is free at the instant, and the
// capacitor's row reads it) the answer is refused and the dense start decides.
#pragma once

#include <Eigen/Dense>

#include "solver/integrators/time_stepper.h"
#include "solver/model/lcs_problem.h"
#include "solver/model/sparse_descriptor.h"

namespace lcs {

// z at t0+ for the states x; `z` holds the preferred first mode on entry (any size). False when
// the answer is refused (then z is untouched).
bool descriptor_start_z(const LcsProblem& model, const SparseDescriptor& d, double t0,
                        const Eigen::VectorXd& x, StepperStats& stats, Eigen::VectorXd& z);

}  // namespace lcs
