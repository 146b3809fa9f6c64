// `.meas tran` measures evaluated on the waveform `run` computed (netlist/measure_card.h parses
// them). ngspice's definitions (com_measure2.c, ngspice 39): the waveform is linear between the
// rows; AVG is its trapezoid integral over the window divided by the window's length, INTEG the
// trapezoid integral, RMS the square root of the exact integral of its square (a segment from a
// to b over dt: dt (a^2 + a b + b^2) / 3) over that length (ngspice uses Simpson's rule over equal
// steps, not the trapezoid); MIN/MAX (and _AT) take the last extreme when it repeats; a crossing is
// located by linear interpolation and counted as ngspice 39.3 counts RISE=, FALL= and CROSS=
// (crossing_time in measure.cpp: a waveform on the level changes side on every row, and a
// crossing asked for between two rows on the level fails, as ngspice's 0/0 does). One deliberate
// difference: a window's ends (FROM=, TO=, TD=) are interpolated points of the waveform, where
// ngspice's AVG, MIN, MAX and crossings start and stop at the nearest rows inside the window.
#pragma once

#include <map>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "netlist/netlist.h"
#include "solver/integrators/output_sink.h"

namespace lcs {

// The run's output times (strictly increasing) and the columns measures read, by probe name.
struct MeasureWaveforms {
  std::vector<double> times;
  std::map<std::string, std::vector<double>> columns;  // Probe::name() -> one value per time
};

struct MeasureResult {
  std::string name;
  std::optional<double> value;  // none: the measure could not be computed
  std::string failure;          // why, when `value` is none
};

// One measure of the waveforms (a PARAM fails: it needs the others' results).
MeasureResult evaluate_measure(const Measure& measure, const MeasureWaveforms& waveforms);
// All of them, in card order; a PARAM reads the results of the others and of the PARAMs above it
// (ngspice 39's order), and fails naming a measure it reads that failed.
std::vector<MeasureResult> evaluate_measures(const std::vector<Measure>& measures, const MeasureWaveforms& waveforms);

// The probes the measures read, each once (by name), in the order they are first used.
std::vector<Probe> measure_probes(const std::vector<Measure>& measures);

// `name = 2.197224577e-04` per result, in order; a failed one as
// `lcspice: warning: .meas NAME failed: REASON`.
void report_measures(const std::vector<MeasureResult>& results, std::ostream& out);

// Between the integrator and the CSV: passes the first `visible` columns on (the CSV keeps the
// columns it had without measures) and records the columns named in `needed` for the measures,
// visible or hidden.
class MeasureTap : public OutputSink {
 public:
  MeasureTap(OutputSink& next, std::size_t visible, std::vector<std::string> needed);
  void begin(const std::vector<std::string>& names) override;
  void row(double t, const Eigen::VectorXd& values) override;
  void finish() override { next_.finish(); }
  const MeasureWaveforms& waveforms() const { return waveforms_; }

 private:
  OutputSink& next_;
  std::size_t visible_;
  std::vector<std::string> needed_;
  std::vector<std::pair<std::size_t, std::vector<double>*>> taps_;  // column -> its recording
  Eigen::VectorXd shown_;                                          // the visible part of a row
  MeasureWaveforms waveforms_;
};

}  // namespace lcs
