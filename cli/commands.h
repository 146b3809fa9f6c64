// One function per subcommand; each returns the process exit code or throws CliError.
#pragma once

#include <optional>
#include <string>

namespace lcs {

struct RunArgs {
  std::string netlist, output, method, probes, diode = "ideal";
  std::optional<double> theta, step, tstop;
  bool stats = false;
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

struct PlotArgs {
  std::string csv, output;
};
int plot_command(const PlotArgs& args);

}  // namespace lcs
