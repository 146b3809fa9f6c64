// Fitting each diode's ideal law to the currents it carries in this very circuit (issue 13).
//
// A card with IS/N/RS and no VON/RON gets a line through its Shockley curve (junction_fit.h).
// Fitted between 1 mA and 100 mA it is far off in a circuit that runs at microamperes (a
// detector at 5 uA: VON 0.624 V where the curve gives 0.48 V). So the circuit is run, each such
// diode's forward (and breakdown) currents are collected, the line is refitted over them, and
// the run repeats until the fits stop moving:
//
//   pass 1: the default fit (the ifit decade pair); pass k + 1: each diode's least-max-error
//   line over [the 10 % quantile, the max] of the currents it carried in pass k while
//   conducting (samples above 1e-6 of its peak; its off phases carry exactly 0 A);
//   stop when no refitted law moves by more than 1 mV in VON and 2 % in RON, or after
//   max_passes transients, or when a pass fails.
//
// Unless the fits converged, the result is the ranges the last pass that ran to TSTOP was built
// with: the final run repeats a model that ran (a pass that fails, or the ranges of a last refit
// that never ran, could leave a model without an operating point: a TTL adder's fourth pass).
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "netlist/netlist.h"
#include "solver/integrators/transient.h"
#include "solver/model/circuit_model.h"

namespace lcs {

struct DiodeRefitOptions {
  int max_passes = 4;            // transients spent on fitting (the final run not counted)
  double von_tolerance = 1e-3;   // V
  double ron_tolerance = 0.02;   // relative
  double low_quantile = 0.1;     // the range's low end among the conducting samples
  // A pass that fails with the run's method runs again with these (the default method's euler
  // fallback, as the final run falls back); none: the failure stops the refit.
  std::optional<TransientOptions> fallback;
};

struct DiodeRefitResult {
  std::map<std::string, DiodeCurrentRanges> ranges;  // for ModelOptions::diode_ranges
  int passes = 0;           // transients run (0: no diode to refit)
  bool converged = false;   // else max_passes was reached (or a pass failed)
  std::string failure;      // a pass's numerical failure, which stopped the refit
  int fallbacks = 0;        // passes run by DiodeRefitOptions::fallback after the method failed
  double cpu_seconds = 0;   // process CPU time of the passes
  std::string BriefReport() const;
};

// Throws what CircuitModel::build throws (the netlist is expected to have built once already).
DiodeRefitResult refit_diodes(const Netlist& netlist, const ModelOptions& model_options,
                              const TransientOptions& options, const DiodeRefitOptions& refit = {});

// The current range [A] of one diode's conducting samples: [quantile, max] of the samples above
// 1e-6 of the largest (and above 1e-13 A); empty when there are none.
CurrentRange conducting_range(std::vector<double> samples, double low_quantile);

// Poor fits: a circuit-fitted pair whose worst voltage error over its range exceeds
// kPoorFitFraction of the junction's voltage there. One sentence naming them, or "".
constexpr double kPoorFitFraction = 0.05;
std::vector<std::string> poorly_fitted_pairs(const CircuitModel& model);
std::string poor_fit_message(const CircuitModel& model);

}  // namespace lcs
