// Owning handles for the SUNDIALS 6 objects the smooth method uses, freed in reverse order of
// creation by declaring them in order of creation.
#pragma once

#include <memory>
#include <stdexcept>
#include <type_traits>

#include <idas/idas.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sundials/sundials_nonlinearsolver.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunlinsol/sunlinsol_klu.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>

namespace lcs::sundials {

struct ContextDeleter {
  void operator()(SUNContext c) const { SUNContext_Free(&c); }
};
struct VectorDeleter {
  void operator()(N_Vector v) const { N_VDestroy(v); }
};
struct MatrixDeleter {
  void operator()(SUNMatrix m) const { SUNMatDestroy(m); }
};
struct LinearSolverDeleter {
  void operator()(SUNLinearSolver s) const { SUNLinSolFree(s); }
};
struct NonlinearSolverDeleter {
  void operator()(SUNNonlinearSolver s) const { SUNNonlinSolFree(s); }
};
struct IdaDeleter {
  void operator()(void* mem) const { IDAFree(&mem); }
};

using Context = std::unique_ptr<std::remove_pointer_t<SUNContext>, ContextDeleter>;
using Vector = std::unique_ptr<std::remove_pointer_t<N_Vector>, VectorDeleter>;
using Matrix = std::unique_ptr<std::remove_pointer_t<SUNMatrix>, MatrixDeleter>;
using LinearSolver = std::unique_ptr<std::remove_pointer_t<SUNLinearSolver>, LinearSolverDeleter>;
using NonlinearSolver =
    std::unique_ptr<std::remove_pointer_t<SUNNonlinearSolver>, NonlinearSolverDeleter>;
using Ida = std::unique_ptr<void, IdaDeleter>;

inline Context make_context() {
  SUNContext c = nullptr;
  if (SUNContext_Create(nullptr, &c) != 0 || !c) throw std::bad_alloc();
  return Context(c);
}

// Checks a constructor's result (SUNDIALS returns null when out of memory).
template <class Handle>
Handle checked(Handle h) {
  if (!h) throw std::bad_alloc();
  return h;
}

}  // namespace lcs::sundials
