// The work-precision chart of one circuit: error against CPU time, log-log, one line per method
// (ngspice included), drawn by gnuplot into a PNG written atomically.
#pragma once

#include <string>

#include "cli/bench_study.h"

namespace lcs {

void write_bench_chart(const CircuitStudy& study, const std::string& png_path);

}  // namespace lcs
