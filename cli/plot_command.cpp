// `lcspice plot CSV [-o PNG]`: the waveforms of a CSV against time, voltages and currents in
// separate panels, drawn by gnuplot (pngcairo). The PNG is written under a temporary name and
// renamed into place, like the CSV.
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "cli/atomic_file.h"
#include "cli/gnuplot.h"
#include "cli/exit_codes.h"

namespace lcs {

namespace {

std::vector<std::string> csv_header(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw CliError(kExitUsage, "error: cannot read '" + path + "'");
  std::string line, data;
  std::getline(in, line);
  if (!std::getline(in, data) || line.rfind("time,", 0) != 0)
    throw CliError(kExitUsage, "error: '" + path + "' is not a waveform CSV (header 'time,...' and rows)");
  std::vector<std::string> fields;
  std::string f;
  bool quoted = false;
  for (char c : line) {
    if (c == '"') quoted = !quoted;
    else if (c == ',' && !quoted) fields.push_back(f), f.clear();
    else f += c;
  }
  fields.push_back(f);
  return fields;
}

}  // namespace

int plot_command(const PlotArgs& args) {
  const std::vector<std::string> header = csv_header(args.csv);
  std::string png = args.output;
  if (png.empty()) {
    png = args.csv;
    const size_t dot = png.rfind('.');
    if (dot != std::string::npos && png.find('/', dot) == std::string::npos) png.resize(dot);
    png += ".png";
  }
  std::vector<std::vector<int>> panels(2);  // voltages, then currents and anything else
  for (size_t c = 1; c < header.size(); ++c) panels[header[c].rfind("v(", 0) == 0 ? 0 : 1].push_back(c + 1);
  const int used = (!panels[0].empty()) + (!panels[1].empty());

  AtomicFile file(png);
  std::string script = "set terminal pngcairo size 1200," + std::to_string(used > 1 ? 900 : 500) +
                       " noenhanced font ',10'\nset output " + gnuplot_string(file.temp()) +
                       "\nset datafile separator comma\nset grid\nset key outside right\n"
                       "set multiplot layout " + std::to_string(used) + ",1 title " +
                       gnuplot_string(args.csv) + "\nset xlabel 'time [s]'\n";
  const char* labels[] = {"voltage [V]", "current [A]"};
  for (int p = 0; p < 2; ++p) {
    if (panels[p].empty()) continue;
    script += std::string("set ylabel '") + labels[p] + "'\nplot ";
    for (size_t k = 0; k < panels[p].size(); ++k)
      script += (k ? ", " : "") + gnuplot_string(args.csv) + " skip 1 using 1:" +
                std::to_string(panels[p][k]) + " with lines lw 1.5 title " +
                gnuplot_string(header[panels[p][k] - 1]);
    script += "\n";
  }
  script += "unset multiplot\nset output\n";

  run_gnuplot(script, "'" + png + "'");
  file.commit();
  std::fprintf(stderr, "lcspice: wrote %s\n", png.c_str());
  return kExitOk;
}

}  // namespace lcs
