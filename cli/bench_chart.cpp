#include "cli/bench_chart.h"

#include <cmath>
#include <cstdio>
#include <map>
#include <vector>

#include "cli/atomic_file.h"
#include "cli/gnuplot.h"

namespace lcs {

void write_bench_chart(const CircuitStudy& study, const std::string& png) {
  std::map<std::string, std::vector<const BenchPoint*>> lines;
  std::vector<std::string> order;
  for (const BenchPoint& p : study.points) {
    if (!p.failure.empty() || !(p.error > 0) || !(p.cpu_seconds > 0)) continue;
    if (!lines.count(p.method)) order.push_back(p.method);
    lines[p.method].push_back(&p);
  }
  if (order.empty()) return;
  AtomicFile file(png);
  std::string script = bench_chart_preamble(file.temp(), study.circuit, study.title, 70);
  char buf[256];
  for (size_t k = 0; k < order.size(); ++k) {
    script += "$m" + std::to_string(k) + " << EOD\n";
    for (const BenchPoint* p : lines[order[k]]) {
      std::snprintf(buf, sizeof buf, "%.6e %.6e\n", p->cpu_seconds, p->error);
      script += buf;
    }
    script += "EOD\n";
  }
  script += "set xlabel 'CPU time [s] (in-process; ngspice: its own analysis time)'\n";
  const std::string reference = study.ideal_reference_setting.substr(0, study.ideal_reference_setting.find(' '));
  script += "set ylabel 'max |error| / range (vs " + reference +
            " reference; smooth, ngspice: vs smooth reference)'\n";
  script += "set grid\nset key outside right\nset format x '%g'\nset format y '%g'\n";
  script += "plot ";
  for (size_t k = 0; k < order.size(); ++k)
    script += (k ? ", " : "") + std::string("$m") + std::to_string(k) + " using 1:2 with linespoints lw 2 title " +
              gnuplot_string(order[k]);
  script += "\n";
  run_gnuplot(script, "'" + png + "'");
  file.commit();
}

}  // namespace lcs
