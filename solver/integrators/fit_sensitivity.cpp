#include "solver/integrators/fit_sensitivity.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "solver/model/numerical_failure.h"

namespace lcs {

std::map<std::string, DiodeCurrentRanges> lowered_ranges(const std::map<std::string, DiodeCurrentRanges>& fitted,
                                                         double decades) {
  std::map<std::string, DiodeCurrentRanges> out = fitted;
  const double factor = std::pow(10.0, -decades);
  for (auto& [name, ranges] : out)
    for (CurrentRange* r : {&ranges.forward, &ranges.reverse}) {
      if (r->empty()) continue;
      // A junction that conducted throughout (a Zener regulating at 16-45 mA) never passes
      // through a turn-on's currents: its line is refitted down to the least it carried only.
      // Lowered two decades, its voltage moved 50 mV, 27 % of a regulator's 0.18 V output range,
      // and run warned that the answer depended on a curve the circuit never reaches.
      r->lo = r->always_on ? std::min(r->lo, r->least) : std::min(r->lo, r->hi) * factor;
    }
  return out;
}

bool has_fitted_ranges(const ModelOptions& model_options) {
  for (const auto& [name, r] : model_options.diode_ranges)
    if (!r.forward.empty() || !r.reverse.empty()) return true;
  return false;
}

namespace {

// One run of the ideal circuit into memory; the failure's message, or "".
std::string run_into(const Netlist& netlist, const ModelOptions& mo, const TransientOptions& options,
                     const std::vector<Probe>& probes, RecordedRows& rows) {
  const CircuitModel model = CircuitModel::build(netlist, mo);
  TransientOptions quiet = options;
  quiet.progress = nullptr;
  try {
    run_transient(model, model.output_map(probes), quiet, rows);
  } catch (const NumericalFailure& e) {
    return e.what();
  }
  return "";
}

// A probe's scale: its range over the nominal run, or its size where it is constant to 1e-6 of
// that size (as `validate` judges a bias node), or 1 where it is zero throughout.
double scale_of(const RecordedRows& r, size_t column) {
  double lo = INFINITY, hi = -INFINITY, size = 0;
  for (size_t k = 0; k < r.times.size(); ++k) {
    const double v = r.at(k, column);
    lo = std::min(lo, v);
    hi = std::max(hi, v);
    size = std::max(size, std::abs(v));
  }
  if (hi - lo > 1e-6 * size) return hi - lo;
  return size > 0 ? size : 1.0;
}

}  // namespace

std::string run_with_lowered_lines(const Netlist& netlist, const ModelOptions& model_options,
                                   const TransientOptions& options, const std::vector<Probe>& probes,
                                   const FitSensitivityOptions& sensitivity, RecordedRows& rows) {
  ModelOptions lowered = model_options;
  lowered.diode_ranges = lowered_ranges(model_options.diode_ranges, sensitivity.decades);
  const std::string failure = run_into(netlist, lowered, options, probes, rows);
  if (failure.empty()) return "";
  char decades[32];
  std::snprintf(decades, sizeof decades, "%g", sensitivity.decades);
  return std::string("with the lines fitted ") + decades + " decades lower: " + failure;
}

FitSensitivity compare_with_lowered(const RecordedRows& nominal, const RecordedRows& low, double step,
                                    const FitSensitivityOptions& options) {
  FitSensitivity result;
  result.measured = true;
  // At every output time of the lowered run, its distance from the nominal run's values within
  // one output interval of it (a tube in time, as `validate` judges ngspice: an edge that moves
  // by less than a row is not a different answer).
  const double dt = step * (1 + 1e-9);
  const size_t columns = std::min(nominal.names.size(), low.names.size());
  for (size_t c = 0; c < columns; ++c) {
    if (std::find(options.unjudged.begin(), options.unjudged.end(), nominal.names[c]) != options.unjudged.end()) continue;
    const double scale = scale_of(nominal, c);
    size_t first = 0;
    for (size_t k = 0; k < low.times.size(); ++k) {
      const double t = low.times[k];
      while (first < nominal.times.size() && nominal.times[first] < t - dt) ++first;
      double lo = INFINITY, hi = -INFINITY;
      for (size_t j = first; j < nominal.times.size() && nominal.times[j] <= t + dt; ++j) {
        lo = std::min(lo, nominal.at(j, c));
        hi = std::max(hi, nominal.at(j, c));
      }
      if (!(lo <= hi)) continue;
      const double v = low.at(k, c);
      const double moved = std::max({0.0, v - hi, lo - v}) / scale;
      // Ties to rounding keep the earlier time: a probe held off by the same amount for a while
      // (a trigger that has tripped in one run only) is reported where that begins.
      if (moved > result.moved * (1 + 1e-9)) {
        result.moved = moved;
        result.probe = nominal.names[c];
        result.worst_time = t;
      }
    }
  }
  return result;
}

FitSensitivity fit_sensitivity(const Netlist& netlist, const ModelOptions& model_options,
                               const TransientOptions& options, const std::vector<Probe>& probes,
                               const FitSensitivityOptions& sensitivity) {
  if (!has_fitted_ranges(model_options) || probes.empty()) return {};  // nothing to judge
  const double cpu0 = process_cpu_seconds();
  RecordedRows nominal, low;
  FitSensitivity result;
  result.failure = run_into(netlist, model_options, options, probes, nominal);
  if (!result.failure.empty()) result.failure = "with the fitted lines: " + result.failure;
  else result.failure = run_with_lowered_lines(netlist, model_options, options, probes, sensitivity, low);
  if (result.failure.empty()) result = compare_with_lowered(nominal, low, options.step, sensitivity);
  result.cpu_seconds = process_cpu_seconds() - cpu0;
  return result;
}

std::string FitSensitivity::Describe(const FitSensitivityOptions& o) const {
  char decades[32];
  std::snprintf(decades, sizeof decades, "%g", o.decades);
  if (!failure.empty())
    return "not measured: a run of the ideal circuit failed (" + failure + ")";
  char buf[256];
  if (probe.empty())  // nothing moved at all (every fitted junction conducted throughout)
    std::snprintf(buf, sizeof buf, "no probe moves (bound %g %%)", 100 * o.bound);
  else
    std::snprintf(buf, sizeof buf, "%s moves %.3g %% of its range (at t = %.6g s; bound %g %%)", probe.c_str(),
                  100 * moved, worst_time, 100 * o.bound);
  return std::string(buf) + " when the junctions' lines are fitted " + decades +
         " decades below the currents they carry";
}

}  // namespace lcs
