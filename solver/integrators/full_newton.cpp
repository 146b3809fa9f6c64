#include "solver/integrators/full_newton.h"

#include <initializer_list>
#include <new>

namespace lcs::sundials {

namespace {

struct Content {
  SUNNonlinSolSysFn sys = nullptr;
  SUNNonlinSolLSetupFn lsetup = nullptr;
  SUNNonlinSolLSolveFn lsolve = nullptr;
  SUNNonlinSolConvTestFn ctest = nullptr;
  void* ctest_data = nullptr;
  N_Vector delta = nullptr, y = nullptr, w = nullptr;
  WeightFn weights = nullptr;
  void* weights_data = nullptr;
  int max_iters = 3;
  int cur_iter = 0;
  long iters = 0, conv_fails = 0;
  booleantype jcur = SUNFALSE;
};

Content& content(SUNNonlinearSolver nls) { return *static_cast<Content*>(nls->content); }

SUNNonlinearSolver_Type get_type(SUNNonlinearSolver) { return SUNNONLINEARSOLVER_ROOTFIND; }

int initialize(SUNNonlinearSolver nls) {
  Content& c = content(nls);
  if (!c.sys || !c.lsetup || !c.lsolve || !c.ctest) return SUN_NLS_MEM_NULL;
  c.iters = c.conv_fails = 0;
  c.jcur = SUNFALSE;
  return SUN_NLS_SUCCESS;
}

// y0 is IDA's predictor and ycor the correction to it; Sys evaluates the residual at y0 + ycor
// and records that iterate, so LSetup right after Sys factorises the Jacobian there.
int solve(SUNNonlinearSolver nls, N_Vector y0, N_Vector ycor, N_Vector w, realtype tol,
          booleantype, void* mem) {
  Content& c = content(nls);
  c.iters = c.conv_fails = 0;  // per solve: IDA adds them up
  int flag = c.sys(ycor, c.delta, mem);
  for (c.cur_iter = 0; flag == SUN_NLS_SUCCESS;) {
    flag = c.lsetup(c.cur_iter > 0, &c.jcur, mem);
    if (flag != SUN_NLS_SUCCESS) break;
    ++c.iters;
    N_VScale(-1.0, c.delta, c.delta);
    flag = c.lsolve(c.delta, mem);
    if (flag != SUN_NLS_SUCCESS) break;
    N_VLinearSum(1.0, ycor, 1.0, c.delta, ycor);
    flag = c.ctest(nls, ycor, c.delta, tol, w, c.ctest_data);
    if (flag == SUN_NLS_SUCCESS) {
      N_VLinearSum(1.0, y0, 1.0, ycor, c.y);
      if (c.weights(c.y, c.w, c.weights_data) != 0 || N_VWrmsNorm(c.delta, c.w) > tol)
        flag = SUN_NLS_CONTINUE;
    }
    if (flag == SUN_NLS_SUCCESS) return SUN_NLS_SUCCESS;
    if (flag != SUN_NLS_CONTINUE) break;
    if (++c.cur_iter >= c.max_iters) {
      flag = SUN_NLS_CONV_RECVR;
      break;
    }
    flag = c.sys(ycor, c.delta, mem);
  }
  ++c.conv_fails;
  return flag;
}

int free_solver(SUNNonlinearSolver nls) {
  if (!nls) return SUN_NLS_SUCCESS;
  if (nls->content) {
    Content* c = static_cast<Content*>(nls->content);
    for (N_Vector v : {c->delta, c->y, c->w})
      if (v) N_VDestroy(v);
    delete c;
    nls->content = nullptr;
  }
  SUNNonlinSolFreeEmpty(nls);
  return SUN_NLS_SUCCESS;
}

int set_sys(SUNNonlinearSolver nls, SUNNonlinSolSysFn f) {
  content(nls).sys = f;
  return SUN_NLS_SUCCESS;
}
int set_lsetup(SUNNonlinearSolver nls, SUNNonlinSolLSetupFn f) {
  content(nls).lsetup = f;
  return SUN_NLS_SUCCESS;
}
int set_lsolve(SUNNonlinearSolver nls, SUNNonlinSolLSolveFn f) {
  content(nls).lsolve = f;
  return SUN_NLS_SUCCESS;
}
int set_ctest(SUNNonlinearSolver nls, SUNNonlinSolConvTestFn f, void* data) {
  content(nls).ctest = f;
  content(nls).ctest_data = data;
  return SUN_NLS_SUCCESS;
}
int set_max_iters(SUNNonlinearSolver nls, int n) {
  if (n < 1) return SUN_NLS_ILL_INPUT;
  content(nls).max_iters = n;
  return SUN_NLS_SUCCESS;
}
int get_num_iters(SUNNonlinearSolver nls, long* n) {
  *n = content(nls).iters;
  return SUN_NLS_SUCCESS;
}
int get_cur_iter(SUNNonlinearSolver nls, int* n) {
  *n = content(nls).cur_iter;
  return SUN_NLS_SUCCESS;
}
int get_num_conv_fails(SUNNonlinearSolver nls, long* n) {
  *n = content(nls).conv_fails;
  return SUN_NLS_SUCCESS;
}

}  // namespace

SUNNonlinearSolver make_full_newton(N_Vector template_vector, SUNContext context, WeightFn weights,
                                    void* weights_data) {
  SUNNonlinearSolver nls = SUNNonlinSolNewEmpty(context);
  if (!nls) throw std::bad_alloc();
  nls->ops->gettype = get_type;
  nls->ops->initialize = initialize;
  nls->ops->solve = solve;
  nls->ops->free = free_solver;
  nls->ops->setsysfn = set_sys;
  nls->ops->setlsetupfn = set_lsetup;
  nls->ops->setlsolvefn = set_lsolve;
  nls->ops->setctestfn = set_ctest;
  nls->ops->setmaxiters = set_max_iters;
  nls->ops->getnumiters = get_num_iters;
  nls->ops->getcuriter = get_cur_iter;
  nls->ops->getnumconvfails = get_num_conv_fails;
  auto* c = new Content;
  nls->content = c;
  c->weights = weights;
  c->weights_data = weights_data;
  c->delta = N_VClone(template_vector);
  c->y = N_VClone(template_vector);
  c->w = N_VClone(template_vector);
  if (!c->delta || !c->y || !c->w) {
    free_solver(nls);
    throw std::bad_alloc();
  }
  return nls;
}

}  // namespace lcs::sundials
