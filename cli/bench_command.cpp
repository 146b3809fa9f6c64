// `lcspice bench`: the work-precision study over a suite of circuits, one CSV for all and one
// chart per circuit, and the headline ratio the targets are stated in (event at 1e-6 against
// ngspice at 1e-3, CPU time).
#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>

#include "cli/atomic_file.h"
#include "cli/bench_chart.h"
#include "cli/bench_scale.h"
#include "cli/bench_scaling.h"
#include "cli/bench_study.h"
#include "cli/scale_family.h"
#include "cli/commands.h"
#include "cli/csv_writer.h"
#include "cli/exit_codes.h"
#include "cli/progress.h"
#include "cli/require_ngspice.h"
#include "solver/integrators/method_registry.h"

#ifndef LCSPICE_CIRCUITS_DIR
#define LCSPICE_CIRCUITS_DIR "circuits"
#endif

namespace lcs {

namespace {

struct SuiteEntry {
  std::string netlist, probes;
  std::vector<std::string> ngspice_options;
};

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::stringstream in(s);
  std::string item;
  while (std::getline(in, item, sep))
    if (!item.empty()) out.push_back(item);
  return out;
}

// circuits/bench_suite.tsv, next to the netlists it names.
std::vector<SuiteEntry> default_suite() {
  const std::string dir = LCSPICE_CIRCUITS_DIR;
  const std::string path = dir + "/bench_suite.tsv";
  std::ifstream in(path);
  if (!in) throw CliError(kExitUsage, "error: cannot read the default bench suite " + path + ": " + std::strerror(errno));
  std::vector<SuiteEntry> suite;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    const std::vector<std::string> cols = split(line, '\t');
    if (cols.size() < 3) throw CliError(kExitUsage, "error: " + path + ": a line needs circuit, probes and options");
    SuiteEntry e;
    e.netlist = dir + "/" + cols[0] + ".cir";
    if (cols[1] != "-") e.probes = cols[1];
    if (cols[2] != "-") e.ngspice_options = split(cols[2], ' ');
    suite.push_back(e);
  }
  return suite;
}

std::string stem(const std::string& path) {
  std::string base = path.substr(path.find_last_of('/') + 1);
  const size_t dot = base.rfind('.');
  return dot == std::string::npos ? base : base.substr(0, dot);
}

std::string number(double v) {
  if (std::isnan(v)) return "";
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.6e", v);
  return buf;
}

// The cheapest run of `method` whose error is at most `target`, or nullptr.
const BenchPoint* cheapest(const CircuitStudy& s, const std::string& method, double target) {
  const BenchPoint* best = nullptr;
  for (const BenchPoint& p : s.points)
    if (p.method == method && p.failure.empty() && p.error <= target && (!best || p.cpu_seconds < best->cpu_seconds))
      best = &p;
  return best;
}

void print_study(const CircuitStudy& s) {
  std::printf("\n%s\n  reference: %s: %.2e\n", s.circuit.c_str(), s.ideal_reference_setting.c_str(),
              s.ideal_reference_check);
  if (!std::isnan(s.smooth_reference_check))
    std::printf("  smooth reference (Shockley diodes, N = %g): smooth, rtol 1e-10 (check against 1e-11: %.2e)\n",
                s.emission, s.smooth_reference_check);
  std::printf("  %-8s %-14s %-7s %12s %12s %12s %9s %9s\n", "method", "setting", "ref", "max err", "vs ideal",
              "CPU [s]", "steps", "events");
  for (const BenchPoint& p : s.points) {
    if (!p.failure.empty()) {
      std::printf("  %-8s %-14s failed: %s\n", p.method.c_str(), p.setting.c_str(), p.failure.c_str());
      continue;
    }
    std::printf("  %-8s %-14s %-7s %12.3e %12.3e %12.3e %9ld %9ld\n", p.method.c_str(), p.setting.c_str(),
                p.reference.c_str(), p.error, p.error_vs_ideal, p.cpu_seconds, p.steps, p.events);
  }
  const BenchPoint* ev = cheapest(s, exact_reference_method().name, 1e-6);
  const BenchPoint* ng = cheapest(s, "ngspice", 1e-3);
  if (ev && ng)
    std::printf("  headline: event reaches 1e-6 in %.3e s CPU, ngspice needs %.3e s for 1e-3 (%s): %.0fx\n",
                ev->cpu_seconds, ng->cpu_seconds, ng->setting.c_str(), ng->cpu_seconds / ev->cpu_seconds);
  else if (ev)
    std::printf("  headline: event reaches 1e-6 in %.3e s CPU; no ngspice run reached 1e-3\n", ev->cpu_seconds);
  std::fflush(stdout);
}

// `bench --scaling`: one cost-scaling study per netlist given.
int scaling_command(const BenchArgs& args) {
  if (args.netlists.empty()) throw CliError(kExitUsage, "error: --scaling needs one or more netlists");
  if (args.quick) throw CliError(kExitUsage, "error: --quick is for the work-precision study, not --scaling");
  ScalingSettings settings;
  if (!args.methods.empty()) settings.methods = split(args.methods, ',');
  settings.ngspice = !args.no_ngspice;
  settings.ngspice_timeout = args.ngspice_timeout;
  settings.ngspice_options = args.ngspice_options;
  if (args.tstop) {
    if (!(*args.tstop > 0)) throw CliError(kExitUsage, "error: --tstop must be positive");
    settings.base_tstop = *args.tstop;
  }
  if (args.scaling_max != 0 && args.scaling_max < 2)
    throw CliError(kExitUsage, "error: --scaling-max must be at least 2");
  settings.max_multiple = args.scaling_max;
  if (!(args.ngspice_timeout > 0)) throw CliError(kExitUsage, "error: --ngspice-timeout must be positive");
  if (settings.ngspice) require_ngspice("bench needs ngspice (--no-ngspice runs without it)");
  if (mkdir(args.output_dir.c_str(), 0777) != 0 && errno != EEXIST)
    throw CliError(kExitUsage, "error: cannot create " + args.output_dir + ": " + std::strerror(errno));
  for (const std::string& netlist : args.netlists) {
    ScalingStudy study;
    {
      ProgressLine line("bench --scaling " + stem(netlist));
      study = study_scaling(netlist, args.probes, settings,
                            [&](const std::string& what, double f) { line.update(f, what); });
    }
    const std::string base = args.output_dir + "/" + stem(netlist) + "_scaling";
    write_scaling_csv(study, base + ".csv");
    write_scaling_chart(study, base + ".png");
    print_scaling(study);
    std::printf("wrote %s.csv and %s.png\n", base.c_str(), base.c_str());
  }
  return kExitOk;
}

// `bench --scale FAMILY`: one circuit-size study of a generated family.
int scale_command(const BenchArgs& args) {
  const std::optional<ScaleFamily> family = find_scale_family(args.scale);
  if (!family)
    throw CliError(kExitUsage, "error: unknown circuit family '" + args.scale + "' (known: " + scale_family_names() + ")");
  if (!args.netlists.empty()) throw CliError(kExitUsage, "error: --scale generates its circuits: give no netlists");
  if (args.scaling || args.quick || args.scaling_max != 0)
    throw CliError(kExitUsage, "error: --scale goes with none of --scaling, --quick, --scaling-max");
  ScaleSettings settings;
  if (!args.methods.empty()) settings.methods = split(args.methods, ',');
  settings.ngspice = !args.no_ngspice;
  settings.ngspice_options = args.ngspice_options;
  for (const std::string& n : split(args.sizes, ',')) {
    char* end = nullptr;
    const long v = std::strtol(n.c_str(), &end, 10);
    if (end == n.c_str() || *end != '\0') throw CliError(kExitUsage, "error: --sizes: '" + n + "' is not a whole number");
    settings.sizes.push_back(static_cast<int>(std::clamp(v, -1L, 1000000L)));
  }
  settings.timeout_seconds = args.run_timeout;
  settings.fit_min_diodes = args.fit_from;
  if (args.tstop) {
    if (!(*args.tstop > 0)) throw CliError(kExitUsage, "error: --tstop must be positive");
    settings.tstop = *args.tstop;
  }
  std::string why;
  if (!settings.IsValid(&why)) throw CliError(kExitUsage, "error: " + why);
  if (mkdir(args.output_dir.c_str(), 0777) != 0 && errno != EEXIST)
    throw CliError(kExitUsage, "error: cannot create " + args.output_dir + ": " + std::strerror(errno));
  ScaleStudy study;
  {
    ProgressLine line(std::string("bench --scale ") + scale_family_name(*family));
    study = study_scale(*family, settings, [&](const std::string& what, double f) { line.update(f, what); });
  }
  const std::string base = args.output_dir + "/scale_" + scale_family_name(*family);
  write_scale_csv(study, base + ".csv");
  write_scale_chart(study, base + ".png");
  // The decks themselves, so that any run can be repeated (`lcspice run`) or studied for accuracy
  // (`lcspice bench DECK`).
  const std::vector<int> sizes = settings.sizes.empty() ? default_scale_sizes(*family) : settings.sizes;
  for (int n : sizes)
    write_text_file(args.output_dir + "/" + scale_family_deck_name(*family, n), scale_family_netlist(*family, n));
  print_scale(study);
  std::printf("wrote %s.csv, %s.png and the decks %s/%s_N.cir\n", base.c_str(), base.c_str(),
              args.output_dir.c_str(), scale_family_name(*family));
  return kExitOk;
}

}  // namespace

int bench_command(const BenchArgs& args) {
  if ((args.scaling || !args.scale.empty()) && args.no_smooth_reference)
    throw CliError(kExitUsage, "error: --no-smooth-reference belongs to the work-precision study");
  if ((args.scaling || !args.scale.empty()) && args.reference != "event")
    throw CliError(kExitUsage, "error: --reference belongs to the work-precision study");
  if (!args.scale.empty()) return scale_command(args);
  if (!args.sizes.empty() || args.run_timeout != 120 || args.fit_from != 100)
    throw CliError(kExitUsage, "error: --sizes, --run-timeout and --fit-from belong to --scale");
  if (args.scaling) return scaling_command(args);
  if (args.tstop || args.scaling_max != 0)
    throw CliError(kExitUsage, "error: --tstop and --scaling-max belong to --scaling");
  std::vector<SuiteEntry> suite;
  if (args.netlists.empty()) {
    suite = default_suite();
  } else {
    for (const std::string& n : args.netlists) suite.push_back({n, args.probes, {}});
  }
  BenchSettings settings;
  settings.quick = args.quick;
  settings.ngspice = !args.no_ngspice;
  settings.ngspice_timeout = args.ngspice_timeout;
  settings.ngspice_options = args.ngspice_options;
  settings.methods = split(args.methods, ',');
  settings.smooth_reference = !args.no_smooth_reference;
  settings.ideal_reference = args.reference;
  if (args.reference != "event" && args.reference != "euler")
    throw CliError(kExitUsage, "error: --reference: '" + args.reference + "' (known: event, euler)");
  if (args.quick) settings.min_timing_seconds = 0.005;
  for (const std::string& m : settings.methods)
    if (!find_method(m)) throw CliError(kExitUsage, "error: unknown method '" + m + "' (known: " + method_names() + ")");
  if (!(args.ngspice_timeout > 0)) throw CliError(kExitUsage, "error: --ngspice-timeout must be positive");
  if (settings.ngspice) require_ngspice("bench needs ngspice (--no-ngspice runs without it)");
  if (mkdir(args.output_dir.c_str(), 0777) != 0 && errno != EEXIST)
    throw CliError(kExitUsage, "error: cannot create " + args.output_dir + ": " + std::strerror(errno));

  std::vector<CircuitStudy> studies;
  for (size_t k = 0; k < suite.size(); ++k) {
    ProgressLine line("bench " + stem(suite[k].netlist));
    auto progress = [&](const std::string& what, double f) {
      line.update((k + f) / suite.size(), what);
    };
    studies.push_back(study_circuit(suite[k].netlist, suite[k].probes, suite[k].ngspice_options, settings, progress));
  }

  const std::string csv = args.output_dir + "/bench.csv";
  {
    AtomicFile file(csv);
    std::FILE* out = std::fopen(file.temp().c_str(), "w");
    if (!out) throw CliError(kExitUsage, "error: cannot write " + csv + ": " + std::strerror(errno));
    std::fprintf(out, "circuit,method,setting,parameter,reference,max_rel_error,max_rel_error_vs_ideal,"
                      "cpu_seconds,steps,lcp_solves,events,rows,failure\n");
    for (const CircuitStudy& s : studies) {
      std::fprintf(out, "%s,reference-check,%s,,ideal,%s,,,,,,,\n", csv_quote(s.circuit).c_str(),
                   csv_quote(s.ideal_reference_setting).c_str(), number(s.ideal_reference_check).c_str());
      if (!std::isnan(s.smooth_reference_check))
        std::fprintf(out, "%s,reference-check,smooth rtol=1e-10 vs 1e-11,,smooth,%s,,,,,,,\n",
                     csv_quote(s.circuit).c_str(), number(s.smooth_reference_check).c_str());
      for (const BenchPoint& p : s.points)
        std::fprintf(out, "%s,%s,%s,%s,%s,%s,%s,%s,%ld,%ld,%ld,%ld,%s\n", csv_quote(s.circuit).c_str(),
                     p.method.c_str(), p.setting.c_str(), number(p.parameter).c_str(), p.reference.c_str(),
                     number(p.error).c_str(), number(p.error_vs_ideal).c_str(), number(p.cpu_seconds).c_str(),
                     p.steps, p.lcp_solves, p.events, p.rows, csv_quote(p.failure).c_str());
    }
    if (std::fclose(out) != 0) throw CliError(kExitUsage, "error: cannot write " + csv);
    file.commit();
  }
  for (const CircuitStudy& s : studies) {
    print_study(s);
    write_bench_chart(s, args.output_dir + "/" + stem(s.circuit) + ".png");
  }
  std::printf("\nwrote %s and one PNG per circuit in %s\n", csv.c_str(), args.output_dir.c_str());
  return kExitOk;
}

}  // namespace lcs
