#include "cli/bench_scaling.h"

#include <algorithm>
#include <cmath>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <limits>

#include "cli/atomic_file.h"
#include "cli/exit_codes.h"
#include "cli/gnuplot.h"
#include "cli/repeat_for_timing.h"
#include "cli/load_circuit.h"
#include "ngspice/deck_translation.h"
#include "ngspice/ngspice_session.h"
#include "solver/integrators/method_registry.h"
#include "solver/integrators/transient.h"
#include "solver/model/numerical_failure.h"

namespace lcs {

namespace {

constexpr double kMaxSteps = 4e4;  // the default longest run, in steps

// Rows are computed (their cost is part of a run) but not kept: memory stays flat with N.
class DiscardSink : public OutputSink {
 public:
  void begin(const std::vector<std::string>&) override {}
  void row(double, const Eigen::VectorXd&) override {}
  void finish() override {}
};

// A method's run at TSTOP `tstop`, repeated for timing (repeat_for_timing.h).
ScalingPoint run_lcspice(const CircuitModel& model, const OutputMap& outputs, const std::string& method,
                         double h, double tstop, bool uic, double min_seconds) {
  TransientOptions o;
  o.method = method;
  o.step = h;
  o.tstop = tstop;
  o.uic = uic;
  ScalingPoint p;
  p.who = method;
  p.tstop = tstop;
  p.cpu_seconds = least_cpu_of_repeats(min_seconds, [&](int) {
    DiscardSink sink;
    const TransientSummary s = run_transient(model, outputs, o, sink);
    p.steps = s.stepper.steps;
    return s.cpu_setup + s.cpu_steps;
  });
  return p;
}

// ngspice at TSTOP `tstop`, maximum step h: its analysis CPU (best of up to three while they
// are short) and its number of time points.
ScalingPoint run_ngspice(const CircuitModel& model, const std::vector<Probe>& probes, double h, double tstop,
                         const ScalingSettings& settings) {
  TranslationOptions topt;
  topt.max_step = h;
  topt.tstop = tstop;
  topt.options = settings.ngspice_options;
  NgspiceRun nr;
  nr.deck = translate_to_ngspice(model, probes, topt).lines;
  nr.timeout_seconds = settings.ngspice_timeout;
  ScalingPoint p;
  p.who = "ngspice";
  p.tstop = tstop;
  p.cpu_seconds = std::numeric_limits<double>::infinity();
  double spent = 0;
  for (int k = 0; k < 3 && (k == 0 || spent < 1.0); ++k) {
    const NgspiceResult r = run_ngspice_transient(nr);
    spent += r.analysis_cpu_seconds;
    p.cpu_seconds = std::min(p.cpu_seconds, r.analysis_cpu_seconds);
    p.steps = static_cast<long>(r.time.size());
  }
  return p;
}

ScalingPoint failed(const std::string& who, double tstop, const std::string& why) {
  ScalingPoint p;
  p.who = who;
  p.tstop = tstop;
  p.cpu_seconds = std::numeric_limits<double>::quiet_NaN();
  p.failure = why;
  return p;
}

bool usable(const ScalingPoint& p) { return p.failure.empty() && p.steps > 0 && p.cpu_seconds > 0; }

}  // namespace

int default_max_multiple(double base_steps) {
  int m = 64;
  while (m > 4 && base_steps * m > kMaxSteps) m /= 2;
  return m;
}

ScalingStudy study_scaling(const std::string& path, const std::string& probe_list,
                           const ScalingSettings& settings, const ScalingProgress& progress) {
  for (const std::string& m : settings.methods) {
    const MethodEntry* e = find_method(m);
    if (!e) throw CliError(kExitUsage, "error: unknown method '" + m + "' (known: " + method_names() + ")");
    if (!e->fixed_step() || e->smooth_model)
      throw CliError(kExitUsage, "error: --scaling needs a fixed-step method; '" + m + "' is not one");
  }
  ScalingStudy study;
  study.circuit = path;
  const Netlist netlist = load_netlist(path);
  study.title = netlist.title;
  if (!netlist.tran) throw CliError(kExitNetlist, path + ": error: no .tran card: nothing to benchmark");
  const TranSpec& tran = *netlist.tran;
  const double h = tran.tmax > 0 ? std::min(tran.tstep, tran.tmax) : tran.tstep;
  study.step = h;
  const double base = settings.base_tstop > 0 ? settings.base_tstop : tran.tstop;
  if (!(base > tran.tstart) || !(h > 0) || !std::isfinite(base))
    throw CliError(kExitUsage, "error: --scaling needs TSTOP > TSTART and TSTEP > 0");
  const int multiple = settings.max_multiple > 0 ? settings.max_multiple : default_max_multiple(base / h);
  if (multiple < 2) throw CliError(kExitUsage, "error: --scaling-max must be at least 2");
  std::vector<double> tstops;
  for (int m = 1; m <= multiple; m *= 2) tstops.push_back(base * m);

  // One model for every run, formed over the longest (sources checked, line kernels fitted).
  const CircuitModel model = build_model(netlist, 0.0, tstops.back());
  const std::vector<Probe> probes = probes_for(netlist, model, probe_list);
  const OutputMap outputs = output_map_or_exit(model, probes);

  const size_t total = tstops.size() * (settings.methods.size() + (settings.ngspice ? 1 : 0));
  size_t done = 0;
  auto report = [&](const std::string& who, double tstop) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "%s tstop=%.3g", who.c_str(), tstop);
    if (progress) progress(buf, static_cast<double>(done++) / total);
  };
  for (const std::string& m : settings.methods) {
    for (double t : tstops) {
      report(m, t);
      try {
        study.points.push_back(run_lcspice(model, outputs, m, h, t, tran.uic, settings.min_timing_seconds));
      } catch (const NumericalFailure& e) {
        study.points.push_back(failed(m, t, e.what()));
        break;
      }
    }
  }
  if (settings.ngspice) {
    for (double t : tstops) {
      report("ngspice", t);
      try {
        study.points.push_back(run_ngspice(model, probes, h, t, settings));
      } catch (const NgspiceError& e) {
        study.points.push_back(failed("ngspice", t, std::string("ngspice ") + to_string(e.kind()) + ": " + e.what()));
        break;
      }
    }
  }
  if (progress) progress("done", 1);
  return study;
}

std::vector<std::string> scaling_series(const ScalingStudy& study) {
  std::vector<std::string> out;
  for (const ScalingPoint& p : study.points)
    if (std::find(out.begin(), out.end(), p.who) == out.end()) out.push_back(p.who);
  return out;
}

double scaling_slope(const ScalingStudy& study, const std::string& who) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int n = 0;
  for (const ScalingPoint& p : study.points) {
    if (p.who != who || !usable(p)) continue;
    const double x = std::log(static_cast<double>(p.steps)), y = std::log(p.cpu_seconds);
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
    ++n;
  }
  const double d = n * sxx - sx * sx;
  if (n < 2 || !(d > 0)) return std::numeric_limits<double>::quiet_NaN();
  return (n * sxy - sx * sy) / d;
}

void print_scaling(const ScalingStudy& study) {
  std::printf("\n%s (scaling: step h = %.4g s)\n", study.circuit.c_str(), study.step);
  std::printf("  %-8s %12s %9s %12s %14s\n", "who", "TSTOP [s]", "steps", "CPU [s]", "CPU/step [s]");
  for (const ScalingPoint& p : study.points) {
    if (!p.failure.empty()) {
      std::printf("  %-8s %12.4g failed: %s\n", p.who.c_str(), p.tstop, p.failure.c_str());
      continue;
    }
    std::printf("  %-8s %12.4g %9ld %12.4e %14.4e\n", p.who.c_str(), p.tstop, p.steps, p.cpu_seconds,
                p.steps > 0 ? p.cpu_seconds / p.steps : 0.0);
  }
  for (const std::string& who : scaling_series(study))
    std::printf("  slope %s: %.3f (least squares of log CPU against log steps)\n", who.c_str(),
                scaling_slope(study, who));
  std::fflush(stdout);
}

void write_scaling_csv(const ScalingStudy& study, const std::string& csv) {
  AtomicFile file(csv);
  std::FILE* out = std::fopen(file.temp().c_str(), "w");
  if (!out) throw CliError(kExitUsage, "error: cannot write " + csv + ": " + std::strerror(errno));
  std::fprintf(out, "who,tstop,steps,cpu_seconds\n");
  for (const ScalingPoint& p : study.points)
    if (usable(p)) std::fprintf(out, "%s,%.9e,%ld,%.6e\n", p.who.c_str(), p.tstop, p.steps, p.cpu_seconds);
  if (std::fclose(out) != 0) throw CliError(kExitUsage, "error: cannot write " + csv);
  file.commit();
}

void write_scaling_chart(const ScalingStudy& study, const std::string& png) {
  const std::vector<std::string> series = scaling_series(study);
  const ScalingPoint* first = nullptr;  // the guide line's anchor: the first series' first point
  for (const ScalingPoint& p : study.points)
    if (usable(p)) {
      first = &p;
      break;
    }
  if (!first) return;
  AtomicFile file(png);
  std::string script = bench_chart_preamble(file.temp(), study.circuit, study.title, 60, " (cost scaling)");
  char buf[256];
  for (size_t k = 0; k < series.size(); ++k) {
    script += "$s" + std::to_string(k) + " << EOD\n";
    for (const ScalingPoint& p : study.points)
      if (p.who == series[k] && usable(p)) {
        std::snprintf(buf, sizeof buf, "%ld %.6e\n", p.steps, p.cpu_seconds);
        script += buf;
      }
    script += "EOD\n";
  }
  script += "set xlabel 'steps N (lcspice: fixed steps; ngspice: time points, max step h)'\n";
  script += "set ylabel 'CPU time [s] (in-process; ngspice: its own analysis time)'\n";
  script += "set grid\nset key top left\nset format x '%g'\nset format y '%g'\n";
  std::snprintf(buf, sizeof buf, "guide(x) = %.6e * x / %ld.0\n", first->cpu_seconds, first->steps);
  script += buf;
  script += "plot ";
  for (size_t k = 0; k < series.size(); ++k) {
    std::snprintf(buf, sizeof buf, " (slope %.2f)", scaling_slope(study, series[k]));
    script += "$s" + std::to_string(k) + " using 1:2 with linespoints lw 2 pt 7 title " +
              gnuplot_string(series[k] + buf) + ", ";
  }
  script += "guide(x) with lines dt 2 lc rgb 'gray40' title 'slope 1 (cost linear in N)'\n";
  run_gnuplot(script, "'" + png + "'");
  file.commit();
}

}  // namespace lcs
