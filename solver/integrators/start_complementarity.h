// z at t0+ consistent with a state x at t0, for methods that start from (x, z).
#pragma once

#include <Eigen/Dense>

#include "solver/integrators/time_stepper.h"
#include "solver/model/lcs_problem.h"

namespace lcs {

// The rational complementarity problem of 4.5 at large s: one implicit Euler LCP from x with a
// step tiny against both h_run and the circuit's fastest rate. Its LCP counts in `stats` (one
// factorisation, the solve in stats.lcp). Throws NumericalFailure when the LCP has no solution,
// or several and none with the active set of `prefer` (the operating point's z; empty or zeros:
// none known). `notes` hears of several solutions kept continuous.
Eigen::VectorXd consistent_start_z(const LcsProblem& model, double t0, double h_run,
                                   const Eigen::VectorXd& x, StepperStats& stats,
                                   const Eigen::VectorXd& prefer = Eigen::VectorXd(),
                                   MultistabilityNotes* notes = nullptr);

}  // namespace lcs
