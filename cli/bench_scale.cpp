#include "cli/bench_scale.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>

#include "cli/atomic_file.h"
#include "cli/exit_codes.h"
#include "cli/gnuplot.h"
#include "cli/isolated_run.h"
#include "cli/repeat_for_timing.h"
#include "ngspice/deck_translation.h"
#include "ngspice/ngspice_session.h"
#include "solver/devices/device_registry.h"
#include "solver/integrators/method_registry.h"
#include "solver/integrators/transient.h"
#include "solver/model/circuit_model.h"
#include "solver/model/smooth_netlist.h"

namespace lcs {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr const char* kNgspice = "ngspice";

// Rows are computed (their cost is part of a run) but not kept.
class DiscardSink : public OutputSink {
 public:
  void begin(const std::vector<std::string>&) override {}
  void row(double, const Eigen::VectorXd&) override {}
  void finish() override {}
};

// What a child reports for a finished run: "ok CPU FORMATION STEPS".
std::string ok_report(double cpu, double formation, long steps) {
  char buf[128];
  std::snprintf(buf, sizeof buf, "ok %.9e %.9e %ld", cpu, formation, steps);
  return buf;
}

struct Circuit {
  Netlist netlist;
  double step = 0, tstop = 0;
};

Circuit parse_circuit(const std::string& text, const std::string& file, double tstop_override, bool smooth) {
  Circuit c;
  c.netlist = parse_netlist_string(text, file);
  if (smooth) c.netlist = smooth_netlist(c.netlist, SmoothingOptions{});
  c.step = c.netlist.tran->tstep;
  c.tstop = tstop_override > 0 ? tstop_override : c.netlist.tran->tstop;
  return c;
}

CircuitModel form_model(const Circuit& c) {
  ModelOptions options;
  options.t1 = c.tstop;
  return CircuitModel::build(c.netlist, options);
}

// In the child: parse, form and run with `method`, repeated while short; the best repeat.
std::string run_lcspice(const std::string& text, const std::string& file, const MethodEntry& method,
                        const ScaleSettings& settings) {
  double best = 0, best_formation = 0;
  long steps = 0;
  const double cpu = least_cpu_of_repeats(settings.min_timing_seconds, [&](int k) {
    const double t0 = process_cpu_seconds();
    const Circuit c = parse_circuit(text, file, settings.tstop, method.smooth_model);
    const CircuitModel model = form_model(c);
    const double t1 = process_cpu_seconds();
    TransientOptions o;
    o.method = method.name;
    o.step = c.step;
    o.tstop = c.tstop;
    o.uic = c.netlist.tran->uic;
    DiscardSink sink;
    const TransientSummary s = run_transient(model, model.output_map(c.netlist.probes), o, sink);
    const double total = process_cpu_seconds() - t0;
    if (k == 0 || total < best) {
      best = total;
      best_formation = t1 - t0;
      steps = s.stepper.steps;
    }
    return total;
  }, settings.min_repeats);
  return ok_report(cpu, best_formation, steps);
}

// In the child: the translated deck in libngspice, maximum step TSTEP; its analysis CPU. The
// deck is written from the devices alone: no lcspice model is formed (its cost is not ngspice's).
std::string run_ngspice(const std::string& text, const std::string& file, const ScaleSettings& settings) {
  const Circuit c = parse_circuit(text, file, settings.tstop, false);
  DeviceOptions device_options;  // the families' netlists carry no .options
  device_options.tstop = c.tstop;
  device_options.tstep = c.step;
  TranslationOptions topt;
  topt.max_step = c.step;
  topt.tstop = c.tstop;
  topt.options = settings.ngspice_options;
  NgspiceRun run;
  run.deck = translate_to_ngspice(c.netlist, make_devices(c.netlist, device_options), c.netlist.probes, topt).lines;
  run.timeout_seconds = 2 * settings.timeout_seconds;  // the parent kills the child first
  long steps = 0;
  try {
    const double cpu = least_cpu_of_repeats(settings.min_timing_seconds, [&](int) {
      const NgspiceResult r = run_ngspice_transient(run);
      steps = static_cast<long>(r.time.size());
      return r.analysis_cpu_seconds;
    }, settings.min_repeats);
    return ok_report(cpu, kNaN, steps);
  } catch (const NgspiceError& e) {
    return std::string("error: ngspice ") + to_string(e.kind()) + ": " + e.what();
  }
}

// A point from what the child did.
ScalePoint point_from(const IsolatedRun& run, ScalePoint p) {
  p.wall_seconds = run.wall_seconds;
  p.peak_rss_mb = run.peak_rss_mb;
  p.cpu_seconds = p.formation_cpu_seconds = kNaN;
  if (run.outcome == IsolatedRun::Outcome::TimedOut) {
    p.status = "timeout";
    p.failure = run.why;
  } else if (run.outcome == IsolatedRun::Outcome::Crashed) {
    p.status = "crashed";
    p.failure = run.why;
  } else if (run.report.rfind("ok ", 0) == 0 &&
             std::sscanf(run.report.c_str() + 3, "%lf %lf %ld", &p.cpu_seconds, &p.formation_cpu_seconds,
                         &p.steps) == 3) {
    p.status = "ok";
  } else {
    p.status = "failed";
    p.failure = run.report.rfind("error: ", 0) == 0 ? run.report.substr(7) : run.report;
  }
  return p;
}

// Whether the series' last two successful runs (a power law through their wall times, at least
// linear) predict more than twice the limit at `diodes`; the prediction in *seconds.
bool predicted_too_long(const std::vector<ScalePoint>& done, int diodes, double limit, double* seconds) {
  if (done.size() < 2) return false;
  const ScalePoint& a = done[done.size() - 2];
  const ScalePoint& b = done.back();
  if (!(a.wall_seconds > 0) || !(b.wall_seconds > 0) || b.diodes <= a.diodes) return false;
  const double slope =
      std::max(1.0, std::log(b.wall_seconds / a.wall_seconds) / std::log(static_cast<double>(b.diodes) / a.diodes));
  *seconds = b.wall_seconds * std::pow(static_cast<double>(diodes) / b.diodes, slope);
  return *seconds > 2 * limit;
}

double slope(const std::vector<double>& x, const std::vector<double>& y) {
  const size_t n = x.size();
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (size_t k = 0; k < n; ++k) {
    sx += x[k];
    sy += y[k];
    sxx += x[k] * x[k];
    sxy += x[k] * y[k];
  }
  const double d = n * sxx - sx * sx;
  if (n < 2 || !(d > 0)) return kNaN;
  return (n * sxy - sx * sy) / d;
}

std::string number(double v) {
  if (!std::isfinite(v)) return "";
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.6e", v);
  return buf;
}

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c == '\n' ? ' ' : c);
  return out + "\"";
}

}  // namespace

bool ScaleSettings::IsValid(std::string* why) const {
  auto fail = [why](const std::string& m) {
    if (why) *why = m;
    return false;
  };
  if (methods.empty() && !ngspice) return fail("nothing to run: no method and no ngspice");
  for (size_t k = 0; k < sizes.size(); ++k) {
    if (sizes[k] < 1 || sizes[k] > 100000) return fail("--sizes must be between 1 and 100000");
    if (k > 0 && sizes[k] <= sizes[k - 1]) return fail("--sizes must be increasing");
  }
  if (!(timeout_seconds > 0) || !std::isfinite(timeout_seconds)) return fail("--run-timeout must be positive");
  if (fit_min_diodes < 1) return fail("--fit-from must be at least 1");
  if (!(tstop >= 0) || !std::isfinite(tstop)) return fail("--tstop must be positive");
  return true;
}

ScaleStudy study_scale(ScaleFamily family, const ScaleSettings& settings, const ScaleProgress& progress) {
  std::string why;
  if (!settings.IsValid(&why)) throw CliError(kExitUsage, "error: " + why);
  std::vector<const MethodEntry*> methods;
  for (const std::string& m : settings.methods) {
    const MethodEntry* e = find_method(m);
    if (!e) throw CliError(kExitUsage, "error: unknown method '" + m + "' (known: " + method_names() + ")");
    methods.push_back(e);
  }
  const std::vector<int> sizes = settings.sizes.empty() ? default_scale_sizes(family) : settings.sizes;

  ScaleStudy study;
  study.family = family;
  study.fit_min_diodes = settings.fit_min_diodes;
  study.baseline_rss_mb = run_isolated([] { return std::string("ok"); }, 30).peak_rss_mb;

  std::vector<std::string> series;
  for (const MethodEntry* e : methods) series.push_back(e->name);
  if (settings.ngspice) series.push_back(kNgspice);
  const double total = static_cast<double>(series.size() * sizes.size());
  size_t done = 0;
  for (size_t s = 0; s < series.size(); ++s) {
    const std::string& who = series[s];
    std::vector<ScalePoint> finished;  // this series' successful runs
    for (int n : sizes) {
      ScalePoint p;
      p.who = who;
      p.size = n;
      p.diodes = scale_family_diodes(family, n);
      const std::string file = scale_family_deck_name(family, n);
      const std::string text = scale_family_netlist(family, n);
      p.tstop = settings.tstop > 0 ? settings.tstop : parse_netlist_string(text, file).tran->tstop;
      if (progress) progress(who + " N=" + std::to_string(n), done++ / total);
      double predicted = 0;
      if (predicted_too_long(finished, p.diodes, settings.timeout_seconds, &predicted)) {
        char buf[160];  // the status says it was not run
        std::snprintf(buf, sizeof buf, "the last two runs predict about %.0f s of wall clock, over twice the %.0f s limit",
                      predicted, settings.timeout_seconds);
        p.status = "skipped";
        p.failure = buf;
        p.cpu_seconds = p.formation_cpu_seconds = p.peak_rss_mb = p.wall_seconds = kNaN;
        study.points.push_back(p);
        break;
      }
      const MethodEntry* method = s < methods.size() ? methods[s] : nullptr;
      const IsolatedRun run = run_isolated(
          [&] { return method ? run_lcspice(text, file, *method, settings) : run_ngspice(text, file, settings); },
          settings.timeout_seconds);
      study.points.push_back(point_from(run, p));
      if (!study.points.back().ok()) break;
      finished.push_back(study.points.back());
    }
    done = (s + 1) * sizes.size();
  }
  if (progress) progress("done", 1);
  return study;
}

std::vector<std::string> scale_series(const ScaleStudy& study) {
  std::vector<std::string> out;
  for (const ScalePoint& p : study.points)
    if (std::find(out.begin(), out.end(), p.who) == out.end()) out.push_back(p.who);
  return out;
}

GrowthExponents growth_exponents(const ScaleStudy& study, const std::string& who) {
  std::vector<double> x, cpu, xm, memory;
  for (const ScalePoint& p : study.points) {
    if (p.who != who || !p.ok() || p.diodes < study.fit_min_diodes || !(p.cpu_seconds > 0)) continue;
    x.push_back(std::log(static_cast<double>(p.diodes)));
    cpu.push_back(std::log(p.cpu_per_simulated_second()));
    const double above = p.peak_rss_mb - study.baseline_rss_mb;
    if (above > 0) {
      xm.push_back(x.back());
      memory.push_back(std::log(above));
    }
  }
  GrowthExponents g;
  g.runs = static_cast<int>(x.size());
  g.cpu = slope(x, cpu);
  g.memory = slope(xm, memory);
  return g;
}

void print_scale(const ScaleStudy& study) {
  std::printf("\nbench --scale %s: CPU per simulated second and peak memory against the number of diodes\n",
              scale_family_name(study.family));
  std::printf("  every run in its own process; an idle child's peak (in every peak below): %.1f MB\n",
              study.baseline_rss_mb);
  std::printf("  %-8s %6s %7s %8s %11s %11s %11s %10s %9s\n", "who", "N", "diodes", "steps", "CPU [s]",
              "CPU/sim-s", "forming [s]", "peak [MB]", "wall [s]");
  for (const ScalePoint& p : study.points) {
    if (!p.ok()) {
      std::printf("  %-8s %6d %7d %s: %s\n", p.who.c_str(), p.size, p.diodes, p.status.c_str(), p.failure.c_str());
      continue;
    }
    char forming[32] = "-";
    if (std::isfinite(p.formation_cpu_seconds)) std::snprintf(forming, sizeof forming, "%.4e", p.formation_cpu_seconds);
    std::printf("  %-8s %6d %7d %8ld %11.4e %11.4e %11s %10.1f %9.2f\n", p.who.c_str(), p.size, p.diodes, p.steps,
                p.cpu_seconds, p.cpu_per_simulated_second(), forming, p.peak_rss_mb, p.wall_seconds);
  }
  for (const std::string& who : scale_series(study)) {
    const GrowthExponents g = growth_exponents(study, who);
    if (g.runs < 2) {
      std::printf("  growth exponent %s: n/a (fewer than two successful runs with >= %d diodes)\n", who.c_str(),
                  study.fit_min_diodes);
      continue;
    }
    std::printf("  growth exponent %s: CPU/sim-s ~ diodes^%.2f, peak memory above the idle child ~ diodes^%.2f "
                "(least squares over %d runs with >= %d diodes)\n",
                who.c_str(), g.cpu, g.memory, g.runs, study.fit_min_diodes);
  }
  std::fflush(stdout);
}

void write_scale_csv(const ScaleStudy& study, const std::string& csv) {
  AtomicFile file(csv);
  std::FILE* out = std::fopen(file.temp().c_str(), "w");
  if (!out) throw CliError(kExitUsage, "error: cannot write " + csv + ": " + std::strerror(errno));
  std::fprintf(out, "family,who,size,diodes,status,tstop,steps,cpu_seconds,cpu_per_sim_second,"
                    "formation_cpu_seconds,peak_rss_mb,baseline_rss_mb,wall_seconds,failure\n");
  for (const ScalePoint& p : study.points) {
    const bool ok = p.ok();
    std::fprintf(out, "%s,%s,%d,%d,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s\n", scale_family_name(study.family), p.who.c_str(),
                 p.size, p.diodes, p.status.c_str(), number(p.tstop).c_str(), ok ? std::to_string(p.steps).c_str() : "",
                 number(ok ? p.cpu_seconds : kNaN).c_str(), number(ok ? p.cpu_per_simulated_second() : kNaN).c_str(),
                 number(ok ? p.formation_cpu_seconds : kNaN).c_str(), number(p.peak_rss_mb).c_str(),
                 number(study.baseline_rss_mb).c_str(), number(p.wall_seconds).c_str(), csv_field(p.failure).c_str());
  }
  if (std::fclose(out) != 0) throw CliError(kExitUsage, "error: cannot write " + csv);
  file.commit();
}

void write_scale_chart(const ScaleStudy& study, const std::string& png) {
  const std::vector<std::string> series = scale_series(study);
  std::vector<std::string> drawn;  // series with at least one successful run
  std::string data;
  char buf[256];
  for (const std::string& who : series) {
    std::string block;
    for (const ScalePoint& p : study.points)
      if (p.who == who && p.ok() && p.cpu_seconds > 0) {
        std::snprintf(buf, sizeof buf, "%d %.6e %.6e\n", p.diodes, p.cpu_per_simulated_second(), p.peak_rss_mb);
        block += buf;
      }
    if (block.empty()) continue;
    data += "$s" + std::to_string(drawn.size()) + " << EOD\n" + block + "EOD\n";
    drawn.push_back(who);
  }
  if (drawn.empty()) return;
  AtomicFile file(png);
  std::string script = "set terminal pngcairo size 1400,640 noenhanced font ',10'\nset output " +
                       gnuplot_string(file.temp()) + "\n" + data;
  script += "set multiplot layout 1,2 title " +
            gnuplot_string(std::string("bench --scale ") + scale_family_name(study.family) +
                           ": cost against circuit size (exponents fitted over runs with >= " +
                           std::to_string(study.fit_min_diodes) + " diodes)") +
            "\n";
  script += "set logscale xy\nset grid\nset key top left\nset format x '%g'\nset format y '%g'\n";
  script += "set xlabel 'diodes'\n";
  auto plot = [&](int column, bool memory) {
    std::string line = "plot ";
    for (size_t k = 0; k < drawn.size(); ++k) {
      const GrowthExponents g = growth_exponents(study, drawn[k]);
      const double e = memory ? g.memory : g.cpu;
      std::string title = drawn[k];
      if (std::isfinite(e)) {
        std::snprintf(buf, sizeof buf, " (exponent %.2f)", e);
        title += buf;
      }
      line += (k ? ", " : "") + std::string("$s") + std::to_string(k) + " using 1:" + std::to_string(column) +
              " with linespoints lw 2 pt 7 title " + gnuplot_string(title);
    }
    if (memory) {
      std::snprintf(buf, sizeof buf, ", %.6e with lines dt 2 lc rgb 'gray40' title 'an idle child'", study.baseline_rss_mb);
      line += buf;
    }
    return line + "\n";
  };
  script += "set title 'CPU per simulated second (lcspice: parse + form + run; ngspice: its analysis)'\n";
  script += "set ylabel 'CPU seconds per simulated second'\n" + plot(2, false);
  script += "set title " + gnuplot_string("peak resident set of each run's own process") + "\n";
  script += "set ylabel 'peak memory [MB]'\n" + plot(3, true);
  script += "unset multiplot\n";
  run_gnuplot(script, "'" + png + "'");
  file.commit();
}

}  // namespace lcs
