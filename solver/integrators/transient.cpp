#include "solver/integrators/transient.h"

#include <cmath>
#include <cstdio>
#include <ctime>

#include "solver/model/initial_state.h"
#include "solver/model/numerical_failure.h"

namespace lcs {

double process_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

bool TransientOptions::IsValid(std::string* why) const {
  auto fail = [why](const std::string& m) {
    if (why) *why = m;
    return false;
  };
  if (!find_method(method)) return fail("unknown method '" + method + "' (known: " + method_names() + ")");
  if (!(step > 0) || !std::isfinite(step)) return fail("the step must be positive");
  if (!(tstop > 0) || !std::isfinite(tstop)) return fail("TSTOP must be positive");
  if (!(tstart >= 0) || tstart >= tstop) return fail("TSTART must be in [0, TSTOP)");
  if (method == "theta" && !(method_options.theta >= 0 && method_options.theta <= 1))
    return fail("--theta must be in [0, 1]");
  if (tstop / step > 2e9) return fail("TSTOP/step is too large (more than 2e9 steps)");
  return true;
}

std::string TransientSummary::BriefReport() const {
  char buf[512];
  const double hit_rate =
      stepper.lcp.solves > 0 ? 100.0 * stepper.lcp.warm_hits / stepper.lcp.solves : 0.0;
  std::snprintf(buf, sizeof buf,
                "method %s: %ld steps, %ld rows, %ld LCP solves (%.1f%% warm-start hits, %ld Lemke "
                "calls, %ld pivots), %d step-size factorisations\n"
                "CPU time: setup %.6f s, steps %.6f s (%.3f us/step), output %.6f s",
                method.c_str(), stepper.steps, rows, stepper.lcp.solves, hit_rate,
                stepper.lcp.lemke_calls, stepper.lcp.lemke_pivots, stepper.factorisations,
                cpu_setup, cpu_steps, stepper.steps > 0 ? 1e6 * cpu_steps / stepper.steps : 0.0,
                cpu_output);
  return buf;
}

TransientSummary run_transient(const CircuitModel& model, const OutputMap& outputs,
                               const TransientOptions& options, OutputSink& sink) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument(why);
  TransientSummary summary;
  summary.method = options.method;
  const double cpu0 = process_cpu_seconds();

  std::unique_ptr<TimeStepper> stepper =
      find_method(options.method)->make(model, options.method_options);
  sink.begin(outputs.names);  // a failure from here on still leaves a (header-only) file
  Eigen::VectorXd x, z(model.lcs().pairs());
  try {
    InitialState init = initial_state(model, options.uic, 0.0);
    summary.warnings = init.warnings;
    x = init.x;
    stepper->Start(0.0, options.step, x, z);
  } catch (const NumericalFailure&) {
    sink.finish();
    throw;
  }
  summary.cpu_setup = process_cpu_seconds() - cpu0;

  Eigen::VectorXd y(outputs.names.size());
  auto emit = [&](double t) {
    const double c0 = process_cpu_seconds();
    y = outputs.G * x + outputs.H * z + outputs.J * model.input_values(t) +
        outputs.K * model.input_derivatives(t);
    sink.row(t, y);
    ++summary.rows;
    summary.cpu_output += process_cpu_seconds() - c0;
  };

  // Step k ends at k*h (no accumulated rounding); a last shorter step lands on tstop.
  const double h = options.step;
  const long full_steps = static_cast<long>(std::floor(options.tstop / h * (1 + 1e-12)));
  const bool partial = options.tstop - full_steps * h > 1e-9 * h;
  const long total = full_steps + (partial ? 1 : 0);
  const double loop0 = process_cpu_seconds();
  try {
    if (options.tstart <= 0) emit(0.0);
    double t = 0.0;
    for (long k = 1; k <= total; ++k) {
      // Full steps use h itself: k*h - (k-1)*h differs from h in the last bits, and every
      // distinct step size costs a factorisation and a cold warm start.
      const double t_next = k <= full_steps ? k * h : options.tstop;
      stepper->Step(t, k <= full_steps ? h : t_next - t, x, z);
      t = t_next;
      if (t >= options.tstart * (1 - 1e-12)) emit(t);
    }
  } catch (const NumericalFailure&) {
    sink.finish();
    throw;
  }
  summary.cpu_steps = process_cpu_seconds() - loop0 - summary.cpu_output;
  summary.stepper = stepper->stats();
  sink.finish();
  return summary;
}

}  // namespace lcs
