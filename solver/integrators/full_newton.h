// A SUNDIALS nonlinear solver for IDA: Newton's method that factorises the Jacobian at every
// iterate. IDA's own (SUNNonlinSol_Newton) keeps the Jacobian of an earlier iterate, often of an
// earlier step. That is cheap and right for mildly nonlinear problems, but a conducting diode's
// margin is a logarithm of its current: once the current has grown a hundredfold since the
// Jacobian was formed, its slope is off a hundredfold, the correction comes out a hundred times
// too small, and IDA's test (which looks only at the correction) calls an inconsistent state
// converged. The DAE is small (states + diodes), so a dense factorisation per iterate costs little.
#pragma once

#include <sundials/sundials_nonlinearsolver.h>

namespace lcs::sundials {

// Error weights at a point y, as IDA's (IDAWFtolerances); returns 0 on success.
using WeightFn = int (*)(N_Vector y, N_Vector w, void* data);

// Owned by the caller (free with SUNNonlinSolFree after the IDA memory that uses it).
// Convergence needs IDA's test (the correction's weighted norm, times the contraction rate seen,
// below the tolerance, with the weights of the step's start) and also the last correction below
// the tolerance in the weights at the iterate it reached: a diode that crosses from conduction to
// blocking within a step changes scale by many decades, and old weights can call a large
// correction small.
SUNNonlinearSolver make_full_newton(N_Vector template_vector, SUNContext context, WeightFn weights,
                                    void* weights_data);

}  // namespace lcs::sundials
