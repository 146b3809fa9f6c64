// The circuit-size study behind `lcspice bench --scale FAMILY`: one family of generated circuits
// (cli/scale_family.h) at growing sizes, each run by lcspice's methods and by ngspice, CPU per
// simulated second and peak memory against the number of diodes, and the growth exponents
// (least-squares slopes on log-log axes) over the larger sizes.
//
// Every run is a separate child process (cli/isolated_run.h): its peak resident set is its own,
// and a run over the wall-clock limit is killed. A failed, killed or skipped run ends its series
// (larger circuits would fare no better). A run is skipped when the series' last two runs predict
// that it would take more than twice the limit.
//
// CPU of an lcspice run: parsing, forming the model and the transient (the best of repeats when
// it is short, cli/repeat_for_timing.h); forming alone is reported too. ngspice: its own analysis
// CPU on the translated deck (Shockley diodes, N = 0.05), maximum step the netlist's TSTEP.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "cli/scale_family.h"

namespace lcs {

struct ScaleSettings {
  std::vector<std::string> methods = {"euler"};  // lcspice methods, one series each
  bool ngspice = true;
  std::vector<std::string> ngspice_options;      // extra `.options` words for every ngspice run
  std::vector<int> sizes;                        // N, ascending; empty: default_scale_sizes
  double timeout_seconds = 120;                  // wall clock per run, then the child is killed
  int fit_min_diodes = 100;                      // the exponents are fitted over runs this large
  double tstop = 0;                              // 0: the family's five periods
  double min_timing_seconds = 0.05;              // repeat short runs until this much CPU
  int min_repeats = 3;                           // and every run under 2 s at least this often (repeat_for_timing.h)

  bool IsValid(std::string* why) const;
};

struct ScalePoint {
  std::string who;  // method name, or "ngspice"
  int size = 0;     // N of the family
  int diodes = 0;
  double tstop = 0;
  // "ok", or why the series stopped here: "failed" (the simulator gave up or the netlist was
  // refused), "timeout", "crashed", "skipped" (predicted over the limit, not run).
  std::string status = "ok";
  std::string failure;              // the message, for anything but "ok"
  long steps = 0;                   // lcspice: steps taken; ngspice: its time points
  double cpu_seconds = 0;           // see the file comment
  double formation_cpu_seconds = 0; // lcspice: forming the model (NaN for ngspice)
  double peak_rss_mb = 0;           // the child's peak resident set (also for failed runs)
  double wall_seconds = 0;          // the child's whole life, repeats included

  bool ok() const { return status == "ok"; }
  double cpu_per_simulated_second() const { return cpu_seconds / tstop; }
};

struct ScaleStudy {
  ScaleFamily family = ScaleFamily::Rectifiers;
  double baseline_rss_mb = 0;  // the peak of a child that does nothing: in every point's peak
  int fit_min_diodes = 100;
  std::vector<ScalePoint> points;
};

// Least-squares slopes of log(CPU per simulated second) and log(peak memory above the baseline)
// against log(diodes) over one series' successful runs with at least fit_min_diodes diodes;
// NaN with fewer than two such runs.
struct GrowthExponents {
  double cpu = 0, memory = 0;
  int runs = 0;  // how many runs the fit is over
};
GrowthExponents growth_exponents(const ScaleStudy& study, const std::string& who);
std::vector<std::string> scale_series(const ScaleStudy& study);  // in order of first appearance

using ScaleProgress = std::function<void(const std::string& what, double fraction)>;

// Throws CliError (exit 1) for bad settings or an unknown method.
ScaleStudy study_scale(ScaleFamily family, const ScaleSettings& settings, const ScaleProgress& progress);

void print_scale(const ScaleStudy& study);
// Every point, failures included (their numbers empty); written atomically.
void write_scale_csv(const ScaleStudy& study, const std::string& csv_path);
// Two log-log panels against diodes: CPU per simulated second, and peak memory.
void write_scale_chart(const ScaleStudy& study, const std::string& png_path);

}  // namespace lcs
