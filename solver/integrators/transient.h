// A transient run: initial state, the fixed-step loop, output rows, and its summary.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "solver/integrators/method_registry.h"
#include "solver/integrators/output_sink.h"
#include "solver/model/circuit_model.h"

namespace lcs {

struct TransientOptions {
  std::string method = fixed_step_default_method().name;
  MethodOptions method_options;
  double step = 0;     // fixed step h (> 0); for adaptive methods the output spacing (TSTEP)
  // Fixed-step methods: equal steps per output step (rows at multiples of `step` only), so a
  // source faster than TSTEP is resolved while rows stay at TSTEP (cli/source_sampling.h).
  int substeps = 1;
  double tstart = 0;   // no output rows before tstart
  double tstop = 0;    // > tstart
  bool uic = false;    // start from zero state + IC= instead of the operating point
  // Adaptive methods only: more output times besides the multiples of `step` (sorted).
  std::vector<double> extra_output_times;
  // Called now and then (at most every few thousand steps) with the fraction of [0, tstop] done.
  std::function<void(double fraction)> progress;

  bool IsValid(std::string* why) const;
};

struct TransientSummary {
  std::string method;
  long rows = 0;
  StepperStats stepper;
  // Seconds of process CPU time: initial state and method setup; the stepping loop including
  // the output rows (timing each row would cost more than writing it to memory).
  double cpu_setup = 0, cpu_steps = 0;
  std::vector<std::string> warnings;

  std::string BriefReport() const;
};

// Throws NumericalFailure after finishing `sink` with the rows computed so far; `failed`, when
// given, then holds the summary up to the failure (rows, steps and the method's statistics so
// far, CPU time, warnings), so that `--stats` can still report it.
TransientSummary run_transient(const CircuitModel& model, const OutputMap& outputs,
                               const TransientOptions& options, OutputSink& sink,
                               TransientSummary* failed = nullptr);

double process_cpu_seconds();

}  // namespace lcs
