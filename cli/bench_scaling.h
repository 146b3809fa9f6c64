// The cost-scaling study behind `lcspice bench --scaling`: for one circuit, a fixed-step method
// at the netlist's step h over TSTOP, 2 TSTOP, 4 TSTOP, ... (the number of steps N doubling),
// and ngspice on the same deck at the same TSTOP values with its maximum step h; CPU time
// against N for each, and the least-squares slope of log CPU against log N (1: cost linear in
// the run's length, as recursive convolutions give; 2: a direct convolution's quadratic cost).
//
// The model is formed once for the longest run (a lossy line's kernel is fitted over the whole
// band) and every run reads it; only TSTOP changes, so the sources run on as written.
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace lcs {

struct ScalingSettings {
  std::vector<std::string> methods = {"euler"};  // fixed-step methods, one series each
  bool ngspice = true;
  double ngspice_timeout = 300;                  // wall-clock seconds per ngspice run
  std::vector<std::string> ngspice_options;      // extra `.options` words for every ngspice run
  double base_tstop = 0;                         // the first run's TSTOP; 0: the netlist's
  int max_multiple = 0;                          // longest run / first run (2^K); 0: default_max_multiple
  double min_timing_seconds = 0.05;              // repeat fast runs until this much CPU, keep the best
};

struct ScalingPoint {
  std::string who;          // method name, or "ngspice"
  double tstop = 0;
  long steps = 0;           // lcspice: steps taken; ngspice: its time points
  double cpu_seconds = 0;   // in-process CPU (ngspice: its own analysis time), best of the repeats
  std::string failure;      // non-empty: the run failed (steps and cpu are then meaningless)
};

struct ScalingStudy {
  std::string circuit;  // the netlist path
  std::string title;
  double step = 0;      // h: lcspice's step and ngspice's maximum step
  std::vector<ScalingPoint> points;
};

using ScalingProgress = std::function<void(const std::string& what, double fraction)>;

// 2^K for a first run of `base_steps` steps: the largest of 64, 32, ..., 4 whose longest run
// stays within about 4e4 steps (N from ~1e3 to ~3e4 for a typical netlist).
int default_max_multiple(double base_steps);

// Throws CliError for netlist errors (exit 2) and bad settings (exit 1). Failed runs are
// recorded as points with a failure; after one, that series stops (longer runs fail too).
ScalingStudy study_scaling(const std::string& netlist_path, const std::string& probes,
                           const ScalingSettings& settings, const ScalingProgress& progress);

// Least-squares slope of log(cpu) against log(steps) over `who`'s successful points; NaN with
// fewer than two.
double scaling_slope(const ScalingStudy& study, const std::string& who);
// The series in the order they first appear.
std::vector<std::string> scaling_series(const ScalingStudy& study);

void print_scaling(const ScalingStudy& study);
// CSV columns who, tstop, steps, cpu_seconds (successful runs only); written atomically.
void write_scaling_csv(const ScalingStudy& study, const std::string& csv_path);
// CPU against N, log-log, one line per series and a slope-1 guide through the first point.
void write_scaling_chart(const ScalingStudy& study, const std::string& png_path);

}  // namespace lcs
