// One function per subcommand; each returns the process exit code or throws CliError.
#pragma once

#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace lcs {

struct RunArgs {
  std::string netlist, output, method, probes, diode;  // diode "": follows the method
  std::optional<double> theta, step, tstop, rtol, atol, emission;
  bool stats = false;
  bool euler_at_switching = false;
};
int run_command(const RunArgs& args);

struct OpArgs {
  std::string netlist;
  bool all = false;
};
int op_command(const OpArgs& args);

struct AnalyzeArgs {
  std::string netlist;
  bool json = false;
};
int analyze_command(const AnalyzeArgs& args);

struct ValidateArgs {
  std::string netlist, report, probes, method;
  double tol = 0.02;          // relative to each probe's range
  double emission = 0.05;     // N of the Shockley diodes standing in for ideal ones
  double timeout = 600;       // seconds of wall time for ngspice
  std::optional<double> step, max_step;
  std::vector<std::string> ngspice_options;  // extra `.options` words for the ngspice deck
  bool print_deck = false;
  bool converge = false;      // ngspice again at N/2, N/4, ...: the rate the disagreement shrinks
};
int validate_command(const ValidateArgs& args);
// Faults put into the ngspice deck only (never from the command line): tests show with them
// that the comparison fails (exit 4) on a wrong witness.
struct NgspiceDeckFaults {
  std::set<std::string> reversed_diodes, open_diodes;  // swapped / left out
  std::map<std::string, double> ron_factor;            // a diode's RON scaled
};
int validate_with_faults(const ValidateArgs& args, const NgspiceDeckFaults& faults);

struct BenchArgs {
  std::vector<std::string> netlists;  // empty: the suite in circuits/bench_suite.tsv
  std::string output_dir = "bench-results";
  std::string methods, probes;        // comma-separated; empty: every method / the netlist's
  std::vector<std::string> ngspice_options;
  double ngspice_timeout = 300;
  bool quick = false, no_ngspice = false;
  bool no_smooth_reference = false;  // BenchSettings::smooth_reference
  std::string reference = "event";   // BenchSettings::ideal_reference
  // --scaling: CPU against the number of steps instead (cli/bench_scaling.h).
  bool scaling = false;
  std::optional<double> tstop;  // the first run's TSTOP (default: the netlist's)
  int scaling_max = 0;          // longest run / first run (0: from the netlist's TSTOP/TSTEP)
  // --scale FAMILY: CPU and peak memory against circuit size instead (cli/bench_scale.h).
  std::string scale;            // cw, ladder or rectifiers; empty: not this study
  std::string sizes;            // comma-separated N (empty: the family's defaults)
  double run_timeout = 120;     // wall-clock seconds per run
  int fit_from = 100;           // the growth exponents are fitted over runs with this many diodes
};
int bench_command(const BenchArgs& args);

struct PlotArgs {
  std::string csv, output;
};
int plot_command(const PlotArgs& args);

}  // namespace lcs
