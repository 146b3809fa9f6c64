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

// Runs `script` through gnuplot; throws CliError (exit 1) naming `what` when it fails.
inline void run_gnuplot(const std::string& script, const std::string& what) {
  std::FILE* gp = popen("gnuplot 2>&1", "w");
  if (!gp) throw CliError(kExitUsage, "error: cannot start gnuplot (install gnuplot-nox)");
  std::fputs(script.c_str(), gp);
  if (pclose(gp) != 0) throw CliError(kExitUsage, "error: gnuplot could not draw " + what);
}

}  // namespace lcs
