// Does the ideal answer depend on the part of a junction's curve that its line cannot follow?
// (issue 13: `--diode auto`)
//
// A fitted line serves the currents a junction carries (diode_refit.h). On its way to them, as
// it turns on and off, the junction also passes through smaller currents, decades of them,
// where no line follows the exponential: the line is off below VON while the curve already
// conducts. Whether that matters is a property of the circuit, not of the fit: a rectifier's
// output hardly notices when within a cycle its diode starts to conduct, while an
// emitter-coupled pair trips where its loop gain reaches one, i.e. where the exponential's
// transconductance I / (N Vt) has grown enough; the line's is 1 / RON as soon as it conducts
// (a Schmitt trigger's 70 ns late trip), and a junction capacitance discharges through the
// curve's slow tail, not through RON.
//
// So the circuit is asked: every fitted line is refitted over its range extended `decades`
// lower (the currents of the turn-on: two decades are 4.6 N Vt, 120 mV of the curve at N = 1;
// a junction that conducted throughout is extended only to the least current it carried),
// the ideal circuit is run with those lines and with the nominal ones, and each probe's largest
// difference between the two runs (within one output interval in time) is measured against the
// probe's range. Both lines are fits of the same curve to currents the junction does pass
// through; an answer that moves by more than the bound between them is the line's guess.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "netlist/netlist.h"
#include "solver/integrators/output_sink.h"
#include "solver/integrators/transient.h"
#include "solver/model/circuit_model.h"

namespace lcs {

struct FitSensitivityOptions {
  double decades = 2;    // how far below its range each fitted line is refitted
  double bound = 0.02;   // of a probe's range: validate's default tolerance
  // Probes not compared: the potential of a node the circuit leaves free while no junction around
  // it conducts (a Darlington's middle node), which any line puts somewhere else (run warns of it
  // on its own).
  std::vector<std::string> unjudged;
};

struct FitSensitivity {
  bool measured = false;   // false: no fitted junction carried current, or a run failed
  std::string probe;       // the probe that moved most (relative to its range)
  double moved = 0;        // its largest difference over its range
  double worst_time = 0;   // where
  std::string failure;     // the run that failed (numerical failure): nothing measured
  double cpu_seconds = 0;
  bool exceeds(const FitSensitivityOptions& o) const { return measured && moved > o.bound; }
  std::string Describe(const FitSensitivityOptions& o) const;
};

// A run's rows kept compactly (one flat array), for the comparison; a sink of its own or beside
// the CSV's (RowTee).
class RecordedRows : public OutputSink {
 public:
  void begin(const std::vector<std::string>& n) override { names = n; }
  void row(double t, const Eigen::VectorXd& v) override {
    times.push_back(t);
    values.insert(values.end(), v.data(), v.data() + v.size());
  }
  void finish() override {}
  double at(size_t row, size_t column) const { return values[row * names.size() + column]; }
  std::vector<std::string> names;
  std::vector<double> times, values;
};

// Every row to two sinks.
class RowTee : public OutputSink {
 public:
  RowTee(OutputSink& a, OutputSink& b) : a_(a), b_(b) {}
  void begin(const std::vector<std::string>& n) override { a_.begin(n), b_.begin(n); }
  void row(double t, const Eigen::VectorXd& v) override { a_.row(t, v), b_.row(t, v); }
  void finish() override { a_.finish(), b_.finish(); }

 private:
  OutputSink &a_, &b_;
};

// The ideal circuit with every fitted line refitted `decades` below its range, into `rows`;
// the numerical failure's message, or "". Throws what CircuitModel::build throws.
std::string run_with_lowered_lines(const Netlist& netlist, const ModelOptions& model_options,
                                   const TransientOptions& options, const std::vector<Probe>& probes,
                                   const FitSensitivityOptions& sensitivity, RecordedRows& rows);

// The comparison of a nominal run with the lowered one (step: the output interval, the tube's
// half-width in time).
FitSensitivity compare_with_lowered(const RecordedRows& nominal, const RecordedRows& lowered, double step,
                                    const FitSensitivityOptions& options = {});

// Whether any fitted junction carried current (else there is nothing to judge).
bool has_fitted_ranges(const ModelOptions& model_options);

// The ranges of `fitted` with every nonempty range's low end moved `decades` lower.
std::map<std::string, DiodeCurrentRanges> lowered_ranges(const std::map<std::string, DiodeCurrentRanges>& fitted,
                                                         double decades);

// Runs the ideal circuit with `model_options.diode_ranges` (the circuit's fitted ranges) and
// with those ranges lowered, and compares `probes`. Throws what CircuitModel::build throws.
FitSensitivity fit_sensitivity(const Netlist& netlist, const ModelOptions& model_options,
                               const TransientOptions& options, const std::vector<Probe>& probes,
                               const FitSensitivityOptions& sensitivity = {});

}  // namespace lcs
