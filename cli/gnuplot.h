// Drawing PNGs with gnuplot (pngcairo): quoting for its scripts, and running one.
#pragma once

#include <cstdio>
#include <string>

#include "cli/exit_codes.h"

namespace lcs {

// A gnuplot single-quoted string: quotes inside are doubled.
inline std::string gnuplot_string(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("''") : std::string(1, c);
  return out + "'";
}

// The start of a `bench` chart's script: a 900x640 PNG written to `path` (an AtomicFile's
// temporary), on logarithmic axes, titled "circuit file: its title" (the title shortened to
// `width` characters) and `suffix`.
inline std::string bench_chart_preamble(const std::string& path, const std::string& circuit,
                                        const std::string& title, size_t width, const std::string& suffix = "") {
  const std::string shown = title.size() > width ? title.substr(0, width - 3) + "..." : title;
  const std::string name = circuit.substr(circuit.find_last_of('/') + 1);
  return "set terminal pngcairo size 900,640 noenhanced font ',10'\nset output " + gnuplot_string(path) +
         "\nset title " + gnuplot_string(name + ": " + shown + suffix) + "\nset logscale xy\n";
}

// Runs `script` through gnuplot; throws CliError (exit 1) naming `what` when it fails.
inline void run_gnuplot(const std::string& script, const std::string& what) {
  std::FILE* gp = popen("gnuplot 2>&1", "w");
  if (!gp) throw CliError(kExitUsage, "error: cannot start gnuplot (install gnuplot-nox)");
  std::fputs(script.c_str(), gp);
  if (pclose(gp) != 0) throw CliError(kExitUsage, "error: gnuplot could not draw " + what);
}

}  // namespace lcs
