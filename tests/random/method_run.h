// Running a netlist string through one registered method in-process, the way `lcspice run` does
// (smoothed circuit for smooth-model methods, the netlist's probes else SPEC §3's defaults).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Dense>

#include "solver/integrators/method_registry.h"

namespace lcs::random_circuit {

struct MethodRun {
  std::string method;
  double step = 0;                      // the fixed step, or the output step of an adaptive method
  std::vector<std::string> names;       // probe names, as the CSV header writes them
  std::vector<double> times;
  std::vector<Eigen::VectorXd> rows;
  std::string failure;                  // a NumericalFailure's message (SPEC §4, exit 3); empty: none
  double tstop = 0, tstep = 0;          // from the .tran card
};

// Parses and forms the model (ideal and smoothed); "" when both succeed, else the
// NetlistError/TopologyError message. Any other exception propagates (it is a finding).
std::string formation_error(const std::string& text);

struct RunSettings {
  // The step TSTOP / divisions; 0: the .tran step (fixed-step methods: the step; adaptive ones:
  // the output step).
  long divisions = 0;
  bool all_probes = false;  // SPEC §3's default probes and the netlist's .print ones, not only those
};

// NumericalFailure is caught into `failure` with the rows computed so far; other exceptions
// propagate.
MethodRun run_method(const std::string& text, const MethodEntry& entry, const RunSettings& settings = {});

// SPEC §3 on the rows of a run: every value finite, times strictly increasing from 0, and (when
// the run did not fail) ending at TSTOP. "" when well formed, else what is wrong.
std::string malformation(const MethodRun& run);

}  // namespace lcs::random_circuit
