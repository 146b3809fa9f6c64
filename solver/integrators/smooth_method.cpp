#include "solver/integrators/smooth_method.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <string>

#include "solver/integrators/full_newton.h"
#include "solver/integrators/sundials_handles.h"
#include "solver/integrators/theta_method.h"
#include "solver/model/numerical_failure.h"

namespace lcs {

// Output times (0 first, strictly increasing) and the points where the integration stops and
// restarts: every source breakpoint inside the run, then the end.
struct SmoothMethod::Schedule {
  std::vector<double> outputs;
  std::vector<double> stops;
  double tstep = 0;
  double merge = 0;  // breakpoints closer than this are one restart
};

namespace {

// Steps IDA may take between two output times before it reports IDA_TOO_MUCH_WORK.
constexpr long kMaxStepsPerOutput = 100000;
constexpr long kMaxStalledSteps = 100;  // consecutive IDA steps that leave t where it was
// restart_after_failure's per advance() (to the next output time, or to a root before it),
// before the failure stands.
constexpr long kMaxRestartsPerOutput = 100;

// What IDA's callbacks see: the DAE, and the switch guards (GuardedMethod) as root functions
// after the pairs'.
struct IdaUserData {
  ShockleyDae* dae = nullptr;
  int guard_count = 0;
  std::function<void(double t, const Eigen::VectorXd& y, double* g)> guards;
};

const ShockleyDae& dae_of(void* user_data) { return *static_cast<const IdaUserData*>(user_data)->dae; }

// IDA callbacks; user_data is an IdaUserData.
int residual_fn(realtype t, N_Vector yy, N_Vector yp, N_Vector rr, void* user_data) {
  const auto& dae = dae_of(user_data);
  const int n = dae.size();
  Eigen::Map<Eigen::VectorXd> r(N_VGetArrayPointer(rr), n);
  const bool finite = dae.residual(t, Eigen::Map<const Eigen::VectorXd>(N_VGetArrayPointer(yy), n),
                                   Eigen::Map<const Eigen::VectorXd>(N_VGetArrayPointer(yp), n), r);
  return finite ? 0 : 1;  // 1: recoverable, IDA retries with a smaller step
}

int jacobian_fn(realtype t, realtype cj, N_Vector yy, N_Vector, N_Vector, SUNMatrix J,
                void* user_data, N_Vector, N_Vector, N_Vector) {
  const auto& dae = dae_of(user_data);
  const int n = dae.size();
  if (dae.sparse()) {  // compressed columns, as Eigen's default SparseMatrix
    const Eigen::SparseMatrix<double>& S =
        dae.sparse_jacobian(Eigen::Map<const Eigen::VectorXd>(N_VGetArrayPointer(yy), n), cj);
    const sunindextype nnz = S.nonZeros();
    if (SUNSparseMatrix_NNZ(J) < nnz && SUNSparseMatrix_Reallocate(J, nnz) != SUNMAT_SUCCESS) return -1;
    sunindextype* columns = SUNSparseMatrix_IndexPointers(J);
    sunindextype* rows = SUNSparseMatrix_IndexValues(J);
    double* values = SUNSparseMatrix_Data(J);
    for (int c = 0; c <= n; ++c) columns[c] = S.outerIndexPtr()[c];
    for (sunindextype k = 0; k < nnz; ++k) {
      rows[k] = S.innerIndexPtr()[k];
      values[k] = S.valuePtr()[k];
    }
    return Eigen::Map<const Eigen::VectorXd>(values, nnz).allFinite() ? 0 : 1;
  }
  // SUNDIALS' dense matrix is column-major, like Eigen's default.
  Eigen::Map<Eigen::MatrixXd> jac(SUNDenseMatrix_Data(J), n, n);
  dae.jacobian(t, Eigen::Map<const Eigen::VectorXd>(N_VGetArrayPointer(yy), n), cj, jac);
  return jac.allFinite() ? 0 : 1;
}

// The root functions are the curve parameters themselves: s_k has the sign of diode k's margin
// and of its current, so it crosses zero exactly where the current does. The switch guards follow.
int crossings_fn(realtype t, N_Vector yy, N_Vector, realtype* gout, void* user_data) {
  const auto& data = *static_cast<const IdaUserData*>(user_data);
  const ShockleyDae& dae = *data.dae;
  const double* y = N_VGetArrayPointer(yy);
  std::copy(y + dae.states(), y + dae.size(), gout);
  if (data.guard_count > 0)
    data.guards(t, Eigen::Map<const Eigen::VectorXd>(y, dae.size()), gout + dae.pairs());
  return 0;
}

// user_data: the ShockleyDae (the Newton solver's weights).
int weights_fn(N_Vector yy, N_Vector ewt, void* user_data) {
  const auto& dae = *static_cast<const ShockleyDae*>(user_data);
  Eigen::Map<Eigen::VectorXd> w(N_VGetArrayPointer(ewt), dae.size());
  return dae.error_weights(Eigen::Map<const Eigen::VectorXd>(N_VGetArrayPointer(yy), dae.size()), w) ? 0 : -1;
}

int ida_weights_fn(N_Vector yy, N_Vector ewt, void* user_data) {
  return weights_fn(yy, ewt, static_cast<IdaUserData*>(user_data)->dae);
}

void error_fn(int, const char*, const char* function, char* msg, void* user_data) {
  *static_cast<std::string*>(user_data) = std::string(function) + ": " + msg;
}

}  // namespace

// One IDA integrator for the DAE, restarted at breakpoints.
class SmoothMethod::IdaRun {
 public:
  // IDA's counters are added to `stats` at each re-initialisation (which resets them) and at
  // flush_stats().
  IdaRun(ShockleyDae& dae, StepperStats& stats, int guard_count = 0,
         std::function<void(double, const Eigen::VectorXd&, double*)> guards = {})
      : dae_(dae),
        stats_(stats),
        ctx_(sundials::make_context()),
        y_(sundials::checked(N_VNew_Serial(dae.size(), ctx_.get()))),
        yp_(sundials::checked(N_VNew_Serial(dae.size(), ctx_.get()))),
        id_(sundials::checked(N_VNew_Serial(dae.size(), ctx_.get()))),
        sample_(sundials::checked(N_VNew_Serial(dae.size(), ctx_.get()))),
        matrix_(make_matrix(dae, ctx_.get())),
        solver_(sundials::checked(dae.sparse() ? SUNLinSol_KLU(y_.get(), matrix_.get(), ctx_.get())
                                               : SUNLinSol_Dense(y_.get(), matrix_.get(), ctx_.get()))),
        newton_(sundials::make_full_newton(y_.get(), ctx_.get(), weights_fn, &dae)),
        mem_(sundials::checked(IDACreate(ctx_.get()))) {
    Eigen::Map<Eigen::VectorXd> id(N_VGetArrayPointer(id_.get()), dae.size());
    id.head(dae.states()).setOnes();
    id.tail(dae.pairs()).setZero();
    N_VConst(0.0, y_.get());
    N_VConst(0.0, yp_.get());
    user_.dae = &dae;
    user_.guard_count = guard_count;
    user_.guards = std::move(guards);
  }

  // A circuit with a sparse LCS (ShockleyDae::sparse) gets a sparse Jacobian and KLU: on 200
  // rectifiers IDA's dense LU and its matrix were 80 % of the run (one Jacobian per Newton
  // iteration, full_newton.h).
  static SUNMatrix make_matrix(const ShockleyDae& dae, SUNContext ctx) {
    if (!dae.sparse()) return sundials::checked(SUNDenseMatrix(dae.size(), dae.size(), ctx));
    const sunindextype nnz = dae.sparse_jacobian(Eigen::VectorXd::Zero(dae.size()), 1.0).nonZeros();
    return sundials::checked(SUNSparseMatrix(dae.size(), dae.size(), nnz, CSC_MAT, ctx));
  }

  Eigen::Map<Eigen::VectorXd> y() { return {N_VGetArrayPointer(y_.get()), dae_.size()}; }
  Eigen::Map<Eigen::VectorXd> yp() { return {N_VGetArrayPointer(yp_.get()), dae_.size()}; }

  // From a consistent y at t: y' from the ODE and the differentiated algebraic rows, then
  // IDACalcIC to confirm (and polish) s and x'. `t_next` is the first time asked for.
  void start(double t, double t_next) {
    const int n = dae_.states(), m = dae_.pairs();
    const Eigen::VectorXd x = y().head(n), s = y().tail(m);
    const Eigen::VectorXd xdot = dae_.derivative(t, x, s);
    yp().head(n) = xdot;
    yp().tail(m) = dae_.parameter_rates(t, x, s, xdot);
    void* mem = mem_.get();
    if (!initialised_) {
      check(IDAInit(mem, residual_fn, t, y_.get(), yp_.get()), t, "IDAInit");
      check(IDASetUserData(mem, &user_), t, "IDASetUserData");
      check(IDASetErrHandlerFn(mem, error_fn, &last_error_), t, "IDASetErrHandlerFn");
      check(IDAWFtolerances(mem, ida_weights_fn), t, "IDAWFtolerances");
      check(IDASetLinearSolver(mem, solver_.get(), matrix_.get()), t, "IDASetLinearSolver");
      check(IDASetJacFn(mem, jacobian_fn), t, "IDASetJacFn");
      check(IDASetNonlinearSolver(mem, newton_.get()), t, "IDASetNonlinearSolver");
      check(IDASetId(mem, id_.get()), t, "IDASetId");
      check(IDASetMaxNumSteps(mem, kMaxStepsPerOutput), t, "IDASetMaxNumSteps");
      if (std::isfinite(dae_.max_step())) check(IDASetMaxStep(mem, dae_.max_step()), t, "IDASetMaxStep");
      const int roots = m + user_.guard_count;
      if (roots > 0) check(IDARootInit(mem, roots, crossings_fn), t, "IDARootInit");
      if (user_.guard_count > 0) {
        // A guard ends the segment only falling through zero (it starts positive, or just
        // below within rounding of its threshold, and rising).
        std::vector<int> direction(roots, 0);
        std::fill(direction.begin() + m, direction.end(), -1);
        check(IDASetRootDirection(mem, direction.data()), t, "IDASetRootDirection");
      }
      initialised_ = true;
    } else {
      flush_stats();
      check(IDAReInit(mem, t, y_.get(), yp_.get()), t, "IDAReInit");
      counted_ = {};  // IDA's counters restart at 0 (its Jacobian count at IDACalcIC below)
    }
    t0_ = t;
    reported_ = t;
    sampled_ = std::max(sampled_, t);
    check(IDACalcIC(mem, IDA_YA_YDP_INIT, t_next), t, "IDACalcIC");
    check(IDAGetConsistentIC(mem, y_.get(), yp_.get()), t, "IDAGetConsistentIC");
  }

  // The grid on which advance() also records the history between IDA's steps (0: steps only).
  void set_sample_step(double h) { sample_step_ = h; }

  void set_stop(double t) { check(IDASetStopTime(mem_.get(), t), t, "IDASetStopTime"); }

  // After a root: the switch guards among the root functions that crossed.
  std::vector<int> guards_crossed() {
    const int m = dae_.pairs(), roots = m + user_.guard_count;
    std::vector<int> found(roots, 0), out;
    if (user_.guard_count == 0) return out;
    check(IDAGetRootInfo(mem_.get(), found.data()), t0_, "IDAGetRootInfo");
    for (int k = m; k < roots; ++k)
      if (found[k] != 0) out.push_back(k - m);
    return out;
  }

  // Integrates towards tout; true when it stopped earlier at a root (t is then the root's time).
  // With `on_step`, IDA goes one internal step at a time and reports each (and each root) to it,
  // y() included: devices with history see every step IDA accepts. y() at tout is then IDA's
  // interpolant there, as IDA_NORMAL would return it.
  bool advance(double tout, double& t,
               const std::function<void(double, const Eigen::VectorXd&)>& on_step = {}) {
    long steps = 0;
    IDAGetNumSteps(mem_.get(), &steps);
    restarts_since_output_ = 0;
    // IDA refuses a first step to a time within rounding of the start.
    if (steps == 0 && std::abs(tout - t0_) <= 4 * DBL_EPSILON * (std::abs(t0_) + std::abs(tout))) {
      t = tout;
      return false;
    }
    realtype tret = 0;
    if (!on_step) {
      int flag = IDASolve(mem_.get(), tout, &tret, y_.get(), yp_.get(), IDA_NORMAL);
      while (restart_after_failure(flag, tout)) flag = IDASolve(mem_.get(), tout, &tret, y_.get(), yp_.get(), IDA_NORMAL);
      check(flag, tret, "IDASolve");
      t = tret;
      return flag == IDA_ROOT_RETURN;
    }
    // IDA_ONE_STEP counts its step limit per call: the limits of IDA_NORMAL, kept here. A step
    // below the rounding of t is "accepted" without moving t; IDA then never gets past a
    // discontinuity of its inputs (it warns, it does not fail), so that is a failure too.
    long taken = 0, stalled = 0;
    for (;;) {
      realtype now = 0;
      IDAGetCurrentTime(mem_.get(), &now);
      if (now >= tout && reported_ >= now) break;  // an earlier step passed tout: interpolate
      const int flag = IDASolve(mem_.get(), tout, &tret, y_.get(), yp_.get(), IDA_ONE_STEP);
      if (restart_after_failure(flag, tout)) continue;
      check(flag, tret, "IDASolve");
      if (++taken > kMaxStepsPerOutput)
        throw NumericalFailure(tret, "the smooth method failed: more than " + std::to_string(kMaxStepsPerOutput) +
                                         " steps before the next output time (IDA_TOO_MUCH_WORK)");
      stalled = tret > now ? 0 : stalled + 1;
      if (stalled > kMaxStalledSteps)
        throw NumericalFailure(tret, "the smooth method failed: IDA's step fell below the rounding of t (" +
                                         std::to_string(kMaxStalledSteps) +
                                         " steps did not move t; a discontinuity of the equations there)");
      // A root's y is IDA's interpolant between two steps, not a step: recorded, it would sit
      // within rounding of a step's own sample and the history's interpolants through both
      // (DelayHistory::wave, degree 4) would divide by their tiny distance.
      if (flag != IDA_ROOT_RETURN) {
        // The waves a line port sends change where its far end's waves arrive, whether or not the
        // states move then (a plateau at one end while an edge leaves the other): IDA's steps,
        // sized by the states, would undersample them. So the history also gets IDA's
        // interpolant on the sample grid inside the step, in time order, then the step itself.
        if (sample_step_ > 0) {
          // IDA interpolates inside its last step only (a restart begins a new one).
          realtype hu = 0;
          IDAGetLastStep(mem_.get(), &hu);
          const double from = std::max(sampled_, tret - hu);
          for (double k = std::floor(from / sample_step_) + 1;; k += 1) {
            const double ts = k * sample_step_;
            if (ts >= tret) break;
            if (ts <= from) continue;
            check(IDAGetDky(mem_.get(), ts, 0, sample_.get()), ts, "IDAGetDky");
            on_step(ts, Eigen::Map<Eigen::VectorXd>(N_VGetArrayPointer(sample_.get()), dae_.size()));
          }
        }
        on_step(tret, y());
        sampled_ = tret;
      }
      reported_ = tret;
      if (flag == IDA_ROOT_RETURN) {
        t = tret;
        return true;
      }
      if (tret >= tout) break;
    }
    if (reported_ != tout) {
      check(IDAGetDky(mem_.get(), tout, 0, y_.get()), tout, "IDAGetDky");
      check(IDAGetDky(mem_.get(), tout, 1, yp_.get()), tout, "IDAGetDky");
    }
    t = tout;
    return false;
  }

  // IDA's error test or corrector failed repeatedly at its step from tcur: start afresh at tcur
  // (order 1, y' from the curves) from the last step it took, once per step it took. A pair's
  // parameter s is its current scaled by 1/g0 on the forward side (about -1e11 V per A at
  // N = 0.05) and its margin on the reverse side: across a turn-off it moves from -1e8 to
  // millivolts within nanoseconds, and IDA's history, extrapolating that slope, failed the error
  // test down to h = 1e-14 (measured: a half-wave rectifier at --rtol 1e-5, the lossy-line
  // rectifier at 1e-3 to 1e-5; local error estimate 2.5e3 V on the margin at h = 2.5e-14).
  bool restart_after_failure(int flag, double tout) {
    if (flag != IDA_ERR_FAIL && flag != IDA_CONV_FAIL) return false;
    realtype tcur = 0;
    IDAGetCurrentTime(mem_.get(), &tcur);
    if (!(tcur > t0_)) return false;  // no step since the last start: starting again is the same
    if (++restarts_since_output_ > kMaxRestartsPerOutput) return false;  // failing at every step
    check(IDAGetDky(mem_.get(), tcur, 0, y_.get()), tcur, "IDAGetDky");
    ++stats_.restarts;
    start(tcur, tout);
    last_error_.clear();
    return true;
  }

  // Adds to the run's stats IDA's counters not yet added (IDAReInit resets them).
  void flush_stats() {
    void* mem = mem_.get();
    StepperStats now;
    long netf = 0, ncfn = 0;
    IDAGetNumSteps(mem, &now.steps);
    IDAGetNumResEvals(mem, &now.residual_evals);
    IDAGetNumJacEvals(mem, &now.jacobian_evals);
    IDAGetNumNonlinSolvIters(mem, &now.newton_iterations);
    IDAGetNumErrTestFails(mem, &netf);
    IDAGetNumNonlinSolvConvFails(mem, &ncfn);
    now.rejected_steps = netf + ncfn;
    stats_.steps += now.steps - counted_.steps;
    stats_.residual_evals += now.residual_evals - counted_.residual_evals;
    stats_.jacobian_evals += now.jacobian_evals - counted_.jacobian_evals;
    stats_.newton_iterations += now.newton_iterations - counted_.newton_iterations;
    stats_.rejected_steps += now.rejected_steps - counted_.rejected_steps;
    counted_ = now;
  }

 private:
  void check(int flag, double t, const char* what) {
    if (flag >= 0) return;
    realtype now = t;
    if (initialised_) IDAGetCurrentTime(mem_.get(), &now);
    char* name = IDAGetReturnFlagName(flag);  // malloc'd by SUNDIALS
    std::string message = std::string("the smooth method failed: ") + what + " returned " +
                          (name ? name : std::to_string(flag));
    std::free(name);
    if (!last_error_.empty()) message += " (" + last_error_ + ")";
    throw NumericalFailure(now, message);
  }

  ShockleyDae& dae_;
  StepperStats& stats_;
  StepperStats counted_;  // IDA's counters since its last (re)initialisation, already in stats_
  IdaUserData user_;
  // Declared in order of creation, so destroyed in reverse: IDA first, the context last.
  sundials::Context ctx_;
  sundials::Vector y_, yp_, id_, sample_;
  sundials::Matrix matrix_;
  sundials::LinearSolver solver_;
  sundials::NonlinearSolver newton_;
  sundials::Ida mem_;
  bool initialised_ = false;
  double t0_ = 0;
  double reported_ = -INFINITY;  // the last time IDA_ONE_STEP returned
  double sampled_ = -INFINITY;   // the last time on_step saw
  double sample_step_ = 0;       // history samples between steps: every multiple of it
  long restarts_since_output_ = 0;  // restart_after_failure's within this advance()
  std::string last_error_;
};

SmoothMethod::Schedule SmoothMethod::make_schedule(const LcsProblem& model,
                                                   const OutputGrid& grid) {
  Schedule s;
  s.tstep = grid.tstep;
  // Multiples of TSTEP computed as k * tstep, not accumulated (as the fixed-step loop does).
  const long full = static_cast<long>(std::floor(grid.tstop / grid.tstep * (1 + 1e-12)));
  for (long k = 0; k <= full; ++k) s.outputs.push_back(k * grid.tstep);
  if (grid.tstop - full * grid.tstep > 1e-9 * grid.tstep) s.outputs.push_back(grid.tstop);
  for (double t : grid.extra)
    if (t > 0 && t <= grid.tstop) s.outputs.push_back(t);
  std::sort(s.outputs.begin(), s.outputs.end());
  s.outputs.erase(std::unique(s.outputs.begin(), s.outputs.end()), s.outputs.end());
  const double end = s.outputs.back();

  // Breakpoints closer than this are one restart (the later one: every jump is then behind it).
  const double merge = s.merge = 1e-13 * end;
  const std::vector<double> bps = model.inputs().breakpoints(0, end);
  for (size_t k = 0; k < bps.size(); ++k) {
    if (bps[k] <= merge || bps[k] >= end - merge) continue;
    if (k + 1 < bps.size() && bps[k + 1] - bps[k] <= merge) continue;
    s.stops.push_back(bps[k]);
  }
  s.stops.push_back(end);
  return s;
}

SmoothMethod::SmoothMethod(const LcsProblem& model, const MethodOptions& options)
    : ContinuousMethod(model),
      dae_(model, options.sparse),
      rtol_(options.rtol > 0 ? options.rtol : kDefaultRtol),
      atol_(options.atol > 0 ? options.atol : kDefaultAtol) {
  dae_.set_max_step(options.max_step);
}

SmoothMethod::~SmoothMethod() = default;

void SmoothMethod::consistent_pairs(double t, const Eigen::VectorXd& x, Eigen::VectorXd& s,
                                    double tstep) {
  const int m = dae_.pairs();
  if (m == 0) return;
  long* its = &stats_.newton_iterations;
  Eigen::VectorXd trial = s;
  if (dae_.solve_pairs(t, x, trial, its)) {
    s = trial;
    return;
  }
  try {
    if (!ideal_) ideal_ = std::make_unique<ThetaMethod>(model_, 1.0);
    Eigen::VectorXd z_ideal(m);
    ideal_->Start(t, tstep, x, z_ideal);
    trial = dae_.parameters_from_ideal(t, x, z_ideal);
    if (dae_.solve_pairs(t, x, trial, its)) {
      s = trial;
      return;
    }
  } catch (const NumericalFailure&) {
    // no ideal solution to start from; try zero below
  }
  trial.setZero();
  if (dae_.solve_pairs(t, x, trial, its)) {
    s = trial;
    return;
  }
  throw NumericalFailure(t, "the smooth method found no diode currents consistent with the state "
                            "(Newton's method did not converge)");
}

// Whether some diode current changes sign from s to s_next (leaving zero does not count).
bool SmoothMethod::switched(const Eigen::VectorXd& s, const Eigen::VectorXd& s_next) {
  for (Eigen::Index k = 0; k < s.size(); ++k)
    if ((s(k) > 0 && s_next(k) <= 0) || (s(k) < 0 && s_next(k) >= 0)) return true;
  return false;
}

// A diode found at zero current when the integration (re)starts, as the ideal operating point
// leaves a blocking one, is set exactly there: IDA's root finder then takes its departure from
// zero (into the smooth diode's leakage) for what it is, not for a switching event.
void SmoothMethod::at_rest(Eigen::VectorXd& s) const {
  for (Eigen::Index k = 0; k < s.size(); ++k)
    if (std::abs(s(k)) <= atol_) s(k) = 0.0;
}

// The run starts at the circuit's DC operating point: the smoothed circuit's own, not the ideal
// diodes' (whose VON/RON put the nodes tens of millivolts elsewhere, and the run would begin with
// that difference relaxing, where ngspice, from its own operating point, begins at rest).
bool SmoothMethod::rest_point(double t, Eigen::VectorXd& x, Eigen::VectorXd& s) {
  const int n = dae_.states(), m = dae_.pairs();
  Eigen::VectorXd y(n + m);
  y << x, s;
  if (dae_.solve_rest_point(t, y, held_, &stats_.newton_iterations)) {
    x = y.head(n);
    s = y.tail(m);
    return true;
  }
  notes_.push_back("the smoothed circuit's own operating point was not found (Newton's method did not "
                   "converge from the ideal diodes' one): the run starts from the ideal diodes' operating point");
  return false;
}

// The smoothed circuit's ideal start had several points (InitialState::other_starts): the Shockley
// operating point sought from each of the others must be the one found from the first, to
// rounding of the states and of the pair currents, or the circuit itself has several (a flip-flop:
// Newton from the first point landed on the balanced saddle, from the others on the two latch
// states) and the run stops, as the ideal methods do, for .ic or .nodeset to choose.
void SmoothMethod::check_other_starts(double t, const Eigen::VectorXd& x, const Eigen::VectorXd& s) {
  const int n = dae_.states(), m = dae_.pairs();
  const Eigen::VectorXd currents = dae_.complementarity_variables(s);
  const double x_scale = std::max(x.cwiseAbs().maxCoeff(), 1.0), i_scale = currents.cwiseAbs().maxCoeff();
  bool differs = false;
  for (const auto& [x_other, z_other] : other_starts_) {
    if (x_other.size() != n || z_other.size() != m) continue;
    Eigen::VectorXd y(n + m);
    y << x_other, dae_.parameters_from_ideal(t, x_other, z_other);
    if (!dae_.solve_rest_point(t, y, held_, &stats_.newton_iterations)) continue;
    const Eigen::VectorXd other_currents = dae_.complementarity_variables(y.tail(m));
    const bool same_states = (y.head(n) - x).cwiseAbs().maxCoeff() <= 1e-6 * x_scale;
    const bool same_currents = (other_currents - currents).cwiseAbs().maxCoeff() <= 1e-6 * i_scale + 1e-12;
    differs = !(same_states && same_currents);
    if (differs) break;
  }
  if (differs)
    throw NumericalFailure(t, "the operating point is not unique: the Shockley junctions' operating point sought "
                              "from the " + std::to_string(other_starts_.size() + 1) +
                              " points of the smoothed circuit's ideal start differs between them; choose one "
                              "with .ic or .nodeset node voltages");
}

// A rest point can be an unstable equilibrium (an astable multivibrator with both transistors
// saturated: its loop gain above one). Exactly there the circuit stays forever, and IDA's implicit
// steps, long once nothing moves, damp any rounding that would start it (BDF is stable for
// h Re(lambda) > 2); ngspice leaves by its own Newton tolerance and its trapezoidal ringing, at a
// time and in a direction that are arbitrary. The linearisation at the rest point (the states'
// rates with the pairs on their curves: A_eff = -(J_xx - J_xs J_ss^-1 J_sx), J the residual's
// Jacobian at cj = 0) shows such a point; the run is started 1e-6 of the states' size along its
// fastest-growing direction (its largest component positive), and says so.
void SmoothMethod::leave_unstable_rest(double t, double tstop, Eigen::VectorXd& x, Eigen::VectorXd& s) {
  const int n = dae_.states(), m = dae_.pairs();
  if (n == 0 || n > kMaxUnstableCheckStates || n + m > 2 * kMaxUnstableCheckStates) return;
  Eigen::VectorXd y(n + m);
  y << x, s;
  Eigen::MatrixXd J(n + m, n + m);
  if (dae_.sparse())
    J = Eigen::MatrixXd(dae_.sparse_jacobian(y, 0.0));
  else
    dae_.jacobian(t, y, 0.0, J);
  Eigen::MatrixXd rates = -J.topLeftCorner(n, n);
  if (m > 0) {
    const Eigen::FullPivLU<Eigen::MatrixXd> pairs(J.bottomRightCorner(m, m));
    if (!pairs.isInvertible()) return;
    rates += J.topRightCorner(n, m) * pairs.solve(J.bottomLeftCorner(m, n));
  }
  if (!rates.allFinite()) return;
  const Eigen::EigenSolver<Eigen::MatrixXd> eigen(rates);
  if (eigen.info() != Eigen::Success) return;
  Eigen::Index fastest = 0;
  eigen.eigenvalues().real().maxCoeff(&fastest);
  const double growth = eigen.eigenvalues()(fastest).real();
  if (!(growth * (tstop - t) > kVisibleGrowth)) return;
  Eigen::VectorXd direction = eigen.eigenvectors().col(fastest).real();
  if (direction.cwiseAbs().maxCoeff() == 0) direction = eigen.eigenvectors().col(fastest).imag();
  Eigen::Index largest = 0;
  const double size = direction.cwiseAbs().maxCoeff(&largest);
  if (!(size > 0)) return;
  direction *= (direction(largest) > 0 ? 1.0 : -1.0) / size;
  x += (kDeparture * std::max(x.cwiseAbs().maxCoeff(), 1.0)) * direction;
  dae_.solve_pairs(t, x, s, &stats_.newton_iterations);
  char rate[32];
  std::snprintf(rate, sizeof rate, "%.3g", growth);
  notes_.push_back(std::string("the operating point is an unstable equilibrium of the Shockley junctions (a deviation "
                               "grows at ") + rate + "/s): the run starts from it displaced by 1e-6 of the states' "
                               "size along the growing direction, as rounding would in another simulator (which way "
                               "is arbitrary); give .ic values that start the circuit for a reproducible answer");
}

void SmoothMethod::set_guards(const SwitchGuards& guards) {
  guards_ = guards;
  guard_count_ = static_cast<int>(guards.threshold.size());
}

// Guard k = sign_k (control_k - threshold_k), the control read from x, the pairs' smooth
// variables z(s) and the sources.
Eigen::VectorXd SmoothMethod::guard_values(double t, const Eigen::Ref<const Eigen::VectorXd>& y) const {
  const int n = dae_.states(), m = dae_.pairs();
  Eigen::VectorXd c = guards_.J * dae_.inputs(t) + guards_.K * model_.input_derivatives(t);
  if (n > 0) c += guards_.G * y.head(n);
  if (m > 0) c += guards_.H * dae_.complementarity_variables(y.tail(m));
  return guards_.sign.cwiseProduct(c - guards_.threshold);
}

// The guards below zero beyond 1e-9 of the control's threshold (IDA puts a root within rounding
// of it, on either side).
std::vector<int> SmoothMethod::guards_below(double t, const Eigen::Ref<const Eigen::VectorXd>& y) const {
  std::vector<int> out;
  if (guard_count_ == 0) return out;
  const Eigen::VectorXd g = guard_values(t, y);
  for (int k = 0; k < guard_count_; ++k)
    if (g(k) < -1e-9 * (std::abs(guards_.threshold(k)) + std::abs(g(k) * guards_.sign(k) + guards_.threshold(k))) - 1e-300)
      out.push_back(k);
  return out;
}

void SmoothMethod::DoRun(const Eigen::VectorXd& x0, const OutputGrid& grid, const Emit& emit,
                         const Progress& progress) {
  SegmentStart start;
  start.x = x0;
  RunSegment(start, grid, emit, progress);
}

std::optional<GuardCrossing> SmoothMethod::RunSegment(const SegmentStart& start, const OutputGrid& grid,
                                                      const Emit& emit, const Progress& progress) {
  if (start.t == 0) stats_ = {};  // a later segment of the same configuration adds to its counts
  Eigen::VectorXd x0 = start.x;
  const Schedule schedule = make_schedule(model_, grid);
  const int n = dae_.states(), m = dae_.pairs();
  const std::vector<double>& outs = schedule.outputs;
  const std::vector<double>& stops = schedule.stops;
  // A switch turned by a source's zero-width edge is located by IDA's root finder within rounding
  // before the edge's breakpoint: the segment starts at the breakpoint, with the sources' values
  // after the jump (IDA cannot start a segment shorter than its rounding: IDACalcIC's "tout1 too
  // close to t0"; x is continuous across the 1e-19 s).
  double t0 = start.t;
  for (double b : stops)
    if (b > t0 && b - t0 <= schedule.merge) t0 = b;
  size_t first = 0;  // the first stop after the segment's start
  while (first + 1 < stops.size() && stops[first] <= t0) ++first;
  auto crossing = [&](double t, const Eigen::VectorXd& y, std::vector<int> crossed) {
    GuardCrossing c;
    c.at.t = t;
    c.at.at = DyadicTime::from(t, grid.tstep);
    c.at.x = y.head(n);
    c.crossed = std::move(crossed);
    ++stats_.events;
    return c;
  };

  double voltage_scale = 0;
  for (const InputSignal& in : model_.inputs().signals()) {
    if (in.quantity != InputSignal::Quantity::Voltage) continue;
    const auto [lo, hi] = in.waveform.range(0, stops.back());
    voltage_scale = std::max({voltage_scale, std::abs(lo), std::abs(hi)});
  }
  dae_.set_tolerances(rtol_, atol_, voltage_scale);
  dae_.set_segment_end(stops[first]);
  Eigen::VectorXd s = Eigen::VectorXd::Zero(m);
  if (m > 0) {
    // The ideal solution is the better first guess: zero currents are far from a conducting diode.
    try {
      ideal_ = std::make_unique<ThetaMethod>(model_, 1.0);
      Eigen::VectorXd z_ideal(m);
      ideal_->Start(t0, schedule.tstep, x0, z_ideal);
      s = dae_.parameters_from_ideal(t0, x0, z_ideal);
    } catch (const NumericalFailure&) {
      s.setZero();
    }
    consistent_pairs(t0, x0, s, schedule.tstep);
    if (t0 == 0 && start_at_rest_ && n > 0 && rest_point(t0, x0, s)) {
      if (!other_starts_.empty()) check_other_starts(t0, x0, s);
      leave_unstable_rest(t0, stops.back(), x0, s);
    }
    at_rest(s);
  }

  double last = -1, last_progress = 0, last_accepted = -1;
  Eigen::VectorXd s_out;
  // Between IDA's steps s is the interpolating polynomial's, controlled only to the margin
  // tolerance; rows (and devices with history) get the s consistent with the states instead.
  auto consistent_z = [&](double t, const Eigen::VectorXd& y) {
    s_out = y.tail(m);
    if (n > 0 && m > 0) dae_.solve_pairs(t, y.head(n), s_out, &stats_.newton_iterations);
    return dae_.complementarity_variables(s_out);
  };
  auto accept_step = [&](double t, const Eigen::VectorXd& y) {
    if (t <= last_accepted) return;
    model_.accept(t, y.head(n), consistent_z(t, y));
    last_accepted = t;
  };
  std::function<void(double, const Eigen::VectorXd&)> on_step;
  if (model_.has_history()) on_step = accept_step;
  auto emit_state = [&](double t, const Eigen::VectorXd& y, bool event) {
    if (t <= last) return;
    const Eigen::VectorXd z_out = consistent_z(t, y);
    // No IDA (n = 0): the rows are the steps; and the start is the history's first sample.
    if ((n == 0 || t == 0) && model_.has_history()) accept_step(t, y);
    emit(t, y.head(n), z_out, event);
    last = t;
    if (progress && t - last_progress >= 0.005 * stops.back()) {
      progress(t);
      last_progress = t;
    }
  };
  Eigen::VectorXd y(n + m);
  y << x0, s;
  if (std::vector<int> crossed = guards_below(t0, y); !crossed.empty()) return crossing(t0, y, std::move(crossed));
  emit_state(t0, y, t0 > 0);
  if (n == 0) {  // switches need states here (the registry's `applies`)
    run_algebraic(schedule, s, emit_state);
    return std::nullopt;
  }

  IdaRun ida(dae_, stats_, guard_count_, [this](double t, const Eigen::VectorXd& yy, double* g) {
    const Eigen::VectorXd v = guard_values(t, yy);
    std::copy(v.data(), v.data() + v.size(), g);
  });
  ida.y() = y;
  if (model_.has_history()) ida.set_sample_step(schedule.tstep);
  ida.start(t0, stops[first]);
  size_t out = 0;
  while (out < outs.size() && outs[out] <= t0) ++out;
  for (size_t k = first; k < stops.size(); ++k) {
    const double b = stops[k];
    dae_.set_segment_end(b);
    ida.set_stop(b);
    for (;;) {
      const double target = out < outs.size() && outs[out] < b ? outs[out] : b;
      double t = 0;
      if (ida.advance(target, t, on_step)) {
        if (std::vector<int> crossed = ida.guards_crossed(); !crossed.empty()) {
          ida.flush_stats();
          return crossing(t, ida.y(), std::move(crossed));
        }
        ++stats_.events;
        emit_state(t, ida.y(), true);
        continue;
      }
      if (target == b) break;
      emit_state(target, ida.y(), false);
      ++out;
    }
    if (k + 1 < stops.size()) {
      // Restart: a source may jump at b; x is continuous, s follows the new source values.
      dae_.set_segment_end(stops[k + 1]);
      y = ida.y();
      const Eigen::VectorXd x = y.head(n), s_before = y.tail(m);
      Eigen::VectorXd sb = s_before;
      consistent_pairs(b, x, sb, schedule.tstep);
      at_rest(sb);
      y.tail(m) = sb;
      // A source jump that puts a switch's control past its threshold: a crossing at b.
      if (std::vector<int> crossed = guards_below(b, y); !crossed.empty()) {
        ida.flush_stats();
        return crossing(b, y, std::move(crossed));
      }
      if (switched(s_before, sb)) {  // a source jump switched a diode: an event at b itself
        ++stats_.events;
        emit_state(b, y, true);
      }
      if (out < outs.size() && outs[out] == b) {
        emit_state(b, y, false);
        ++out;
      }
      ida.y() = y;
      ida.start(b, stops[k + 1]);
    } else if (out < outs.size() && outs[out] == b) {
      emit_state(b, ida.y(), false);
      ++out;
    }
  }
  ida.flush_stats();
  return std::nullopt;
}

void SmoothMethod::run_algebraic(const Schedule& schedule, Eigen::VectorXd s,
                                 const std::function<void(double, const Eigen::VectorXd&, bool)>& emit_state) {
  const Eigen::VectorXd x(0);
  const std::vector<double>& outs = schedule.outputs;
  const std::vector<double>& stops = schedule.stops;
  auto solve = [&](double t, Eigen::VectorXd& ss) {
    consistent_pairs(t, x, ss, schedule.tstep);
    ++stats_.steps;
  };
  auto crosses = [](double a, double b) { return (a > 0 && b <= 0) || (a < 0 && b >= 0); };
  // The first time after pair k's crossing in (ta, tb], by the Illinois variant of regula falsi,
  // to about the time resolution of IDA's root finder (100 ulps).
  auto locate = [&](int k, double ta, const Eigen::VectorXd& sa, double tb,
                    const Eigen::VectorXd& sb, Eigen::VectorXd& s_at) {
    double lo = ta, hi = tb, glo = sa(k), ghi = sb(k);
    Eigen::VectorXd slo = sa;
    s_at = sb;
    for (int it = 0; it < 200 && hi - lo > 100 * DBL_EPSILON * std::max(std::abs(hi), tb - ta); ++it) {
      double tm = hi - ghi * (hi - lo) / (ghi - glo);
      if (!(tm > lo && tm < hi)) tm = 0.5 * (lo + hi);
      Eigen::VectorXd sm = slo + (s_at - slo) * ((tm - lo) / (hi - lo));
      solve(tm, sm);
      if (crosses(glo, sm(k))) {
        hi = tm;
        ghi = sm(k);
        s_at = sm;
        glo *= 0.5;
      } else {
        lo = tm;
        glo = sm(k);
        slo = sm;
        ghi *= 0.5;
      }
    }
    return hi;
  };

  size_t out = 1;
  double ta = 0;
  for (size_t k = 0; k < stops.size(); ++k) {
    const double b = stops[k];
    dae_.set_segment_end(b);  // the sample at b is the left limit of the sources there
    for (;;) {
      const double tb = out < outs.size() && outs[out] < b ? outs[out] : b;
      Eigen::VectorXd sb = s;
      solve(tb, sb);
      std::vector<std::pair<double, Eigen::VectorXd>> events;
      for (int p = 0; p < s.size(); ++p)
        if (crosses(s(p), sb(p))) {
          Eigen::VectorXd s_at;
          const double te = locate(p, ta, s, tb, sb, s_at);
          events.emplace_back(te, s_at);
        }
      std::sort(events.begin(), events.end(),
                [](const auto& e, const auto& f) { return e.first < f.first; });
      for (const auto& [te, se] : events) {
        ++stats_.events;
        emit_state(te, se, true);
      }
      ta = tb;
      s = sb;
      if (tb == b) break;
      emit_state(tb, s, false);
      ++out;
    }
    if (k + 1 < stops.size()) {
      dae_.set_segment_end(stops[k + 1]);
      const Eigen::VectorXd s_before = s;
      solve(b, s);  // after the jump
      if (switched(s_before, s)) {
        ++stats_.events;
        emit_state(b, s, true);
      }
    }
    if (out < outs.size() && outs[out] == b) {
      emit_state(b, s, false);
      ++out;
    }
  }
}

}  // namespace lcs
