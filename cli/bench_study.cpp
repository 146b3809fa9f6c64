#include "cli/bench_study.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>

#include "cli/exit_codes.h"
#include "cli/repeat_for_timing.h"
#include "cli/load_circuit.h"
#include "ngspice/deck_translation.h"
#include "ngspice/ngspice_session.h"
#include "ngspice/probe_series.h"
#include "solver/integrators/transient.h"
#include "solver/model/numerical_failure.h"
#include "solver/model/smooth_netlist.h"

namespace lcs {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// BenchPoint::reference: which circuit the reference solves (a model, not a method name).
constexpr const char* kIdealModel = "ideal";
constexpr const char* kSmoothModel = "smooth";

// A circuit ready to run: its model, probes and run parameters.
struct Prepared {
  std::unique_ptr<CircuitModel> model;
  OutputMap outputs;
  double tstep = 0, tstop = 0;
  bool uic = false;
};

// The outputs are mapped by the caller: both circuits of a study share the ideal one's probes.
Prepared prepare(const Netlist& netlist) {
  Prepared p;
  p.tstep = netlist.tran->tmax > 0 ? std::min(netlist.tran->tstep, netlist.tran->tmax) : netlist.tran->tstep;
  p.tstop = netlist.tran->tstop;
  p.uic = netlist.tran->uic;
  p.model = std::make_unique<CircuitModel>(build_model(netlist, 0.0, p.tstop));
  return p;
}

struct Timed {
  MemorySink sink;
  TransientSummary summary;
  double cpu = 0;
};

// Runs a method, repeated for timing (repeat_for_timing.h); the first run's rows, the fastest
// run's summary.
Timed run(const Prepared& p, const std::string& method, double step, double rtol, double atol,
          const std::vector<double>& extra, double min_seconds) {
  TransientOptions o;
  o.method = method;
  o.step = step;
  o.tstop = p.tstop;
  o.uic = p.uic;
  o.method_options.rtol = rtol;
  o.method_options.atol = atol;
  o.extra_output_times = extra;
  Timed t;
  double best = 0;
  t.cpu = least_cpu_of_repeats(min_seconds, [&](int k) {
    MemorySink sink;
    TransientSummary s = run_transient(*p.model, p.outputs, o, sink);
    const double cpu = s.cpu_setup + s.cpu_steps;
    if (k == 0 || cpu < best) {
      best = cpu;
      t.summary = s;
    }
    if (k == 0) t.sink = std::move(sink);
    return cpu;
  });
  return t;
}

// Per-probe scale of the reference: its range, or its size for a constant probe.
std::vector<double> scales(const MemorySink& ref) {
  std::vector<double> lo(ref.names.size(), INFINITY), hi(ref.names.size(), -INFINITY), mag(ref.names.size(), 0);
  for (const Eigen::VectorXd& row : ref.rows)
    for (size_t c = 0; c < ref.names.size(); ++c) {
      lo[c] = std::min(lo[c], row(c));
      hi[c] = std::max(hi[c], row(c));
      mag[c] = std::max(mag[c], std::abs(row(c)));
    }
  std::vector<double> s(ref.names.size());
  for (size_t c = 0; c < s.size(); ++c) s[c] = hi[c] > lo[c] ? hi[c] - lo[c] : mag[c] > 0 ? mag[c] : 1.0;
  return s;
}

// Max over probes of max |y - y_ref| / scale at the times both have (matched within 1e-9 of the
// output step; rows of one run at times the other lacks are not compared).
double compare(const MemorySink& run, const MemorySink& ref, const std::vector<double>& scale, double tstep) {
  double worst = 0;
  size_t j = 0;
  long matched = 0;
  const double tol = 1e-9 * tstep;
  for (size_t k = 0; k < run.times.size(); ++k) {
    const double t = run.times[k];
    while (j < ref.times.size() && ref.times[j] < t - tol) ++j;
    if (j >= ref.times.size()) break;
    if (std::abs(ref.times[j] - t) > tol) continue;
    ++matched;
    for (size_t c = 0; c < scale.size(); ++c)
      worst = std::max(worst, std::abs(run.rows[k](c) - ref.rows[j](c)) / scale[c]);
  }
  return matched > 0 ? worst : kNaN;
}

// A fixed-step reference's rows read linearly at `times` (those within its span; sorted): it has
// rows at its own steps only, ngspice's are elsewhere.
MemorySink rows_at(const MemorySink& ref, const std::vector<double>& times) {
  MemorySink out;
  out.names = ref.names;
  size_t j = 0;
  for (double t : times) {
    while (j + 1 < ref.times.size() && ref.times[j + 1] < t) ++j;
    if (j + 1 >= ref.times.size()) break;
    if (t < ref.times[j]) continue;
    const double a = ref.times[j], b = ref.times[j + 1];
    const double f = b > a ? (t - a) / (b - a) : 0.0;
    out.times.push_back(t);
    out.rows.push_back(ref.rows[j] + f * (ref.rows[j + 1] - ref.rows[j]));
  }
  return out;
}

// 10^a, 10^(a - step), ..., 10^b.
std::vector<double> powers(double a, double b, int per_decade_step) {
  std::vector<double> out;
  for (int e = static_cast<int>(std::round(std::log10(a))); e >= static_cast<int>(std::round(std::log10(b)));
       e -= per_decade_step)
    out.push_back(std::pow(10.0, e));
  return out;
}

BenchPoint failed(const std::string& method, const std::string& setting, double parameter,
                  const std::string& reference, const std::string& why) {
  BenchPoint b;
  b.method = method;
  b.setting = setting;
  b.parameter = parameter;
  b.reference = reference;
  b.error = b.error_vs_ideal = b.cpu_seconds = kNaN;
  b.failure = why;
  return b;
}

std::string setting_text(const std::string& name, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%s=%.3g", name.c_str(), v);
  return buf;
}

}  // namespace

CircuitStudy study_circuit(const std::string& path, const std::string& probe_list,
                           const std::vector<std::string>& extra_ngspice_options,
                           const BenchSettings& settings, const BenchProgress& progress) {
  CircuitStudy study;
  study.circuit = path;
  Netlist netlist = load_netlist(path);
  study.title = netlist.title;
  if (!netlist.tran)
    throw CliError(kExitNetlist, path + ": error: no .tran card: nothing to benchmark");
  Prepared ideal = prepare(netlist);
  const std::vector<Probe> probes = probes_for(netlist, *ideal.model, probe_list);
  ideal.outputs = output_map_or_exit(*ideal.model, probes);
  const double h = ideal.tstep;
  const double min_s = settings.min_timing_seconds;
  auto report = [&](const std::string& what, double f) {
    if (progress) progress(what, f);
  };

  // The ideal reference and its check.
  const std::string exact = exact_reference_method().name;
  const bool fine_euler = settings.ideal_reference == "euler";
  report("reference (" + settings.ideal_reference + ")", 0);
  if (fine_euler) {
    // Its rows are at multiples of TSTEP/64 and ngspice's points are read between them: a
    // source's corner between two rows (a PULSE edge, a PWL point) would be smeared over a row
    // interval there, and its check (TSTEP/64 against TSTEP/128 on their common rows) would not
    // show it (a 10 ns edge read 0.39 against ngspice where the event reference reads 0.04).
    const std::vector<double> corners = ideal.model->inputs().breakpoints(0.0, ideal.tstop);
    if (!corners.empty())
      throw CliError(kExitUsage, "lcspice: error: " + path + ": --reference euler reads its rows linearly between "
                                 "steps of TSTEP/64 and cannot place them on the sources' corners (the first at " +
                                 [&] {
                                   char buf[32];
                                   std::snprintf(buf, sizeof buf, "%.6g s", corners.front());
                                   return std::string(buf);
                                 }() + "): use the event reference");
  }
  Timed ref, ref_check;
  try {
    if (fine_euler) {
      ref = run(ideal, "euler", h / 64, 0, 0, {}, 0);
      ref_check = run(ideal, "euler", h / 128, 0, 0, {}, 0);
      study.ideal_reference_setting = "euler h=TSTEP/64 vs TSTEP/128";
    } else {
      ref = run(ideal, exact, h, 1e-13, 0, {}, 0);
      ref_check = run(ideal, exact, h / 2, 1e-14, 0, {}, 0);
      study.ideal_reference_setting = exact + " rtol=1e-13 vs 1e-14 at TSTEP/2";
    }
  } catch (const NumericalFailure& e) {
    throw CliError(kExitNumerical, "lcspice: error: " + path + ": no " +
                                       (fine_euler ? std::string("implicit Euler") : std::string("event-driven")) +
                                       " reference: " + e.what());
  }
  const std::vector<double> ref_scale = scales(ref.sink);
  study.ideal_reference_check = compare(ref_check.sink, ref.sink, ref_scale, h);

  // The smooth reference: the same circuit with Shockley diodes, as ngspice gets it.
  // None where the smooth method does not apply (switches): ngspice is then compared with the
  // ideal reference, as without a smooth method.
  const MethodEntry* smooth_entry = settings.smooth_reference ? smooth_reference_method() : nullptr;
  SmoothingOptions smoothing;
  study.emission = smoothing.emission;
  Prepared smooth;
  if (smooth_entry) smooth = prepare(smooth_netlist(netlist, smoothing));
  const bool have_smooth =
      smooth_entry != nullptr && (!smooth_entry->applies || smooth_entry->applies(*smooth.model, nullptr));
  const std::string smooth_ref = have_smooth ? smooth_entry->name : "";
  Timed sref;
  std::vector<double> sref_scale;
  study.smooth_reference_check = kNaN;
  if (have_smooth) {
    report("reference (" + smooth_ref + ")", 0.05);
    smooth.outputs = output_map_or_exit(*smooth.model, probes);
    try {
      sref = run(smooth, smooth_ref, h, 1e-10, 1e-13, {}, 0);
      Timed check = run(smooth, smooth_ref, h, 1e-11, 1e-14, {}, 0);
      sref_scale = scales(sref.sink);
      study.smooth_reference_check = compare(check.sink, sref.sink, sref_scale, h);
    } catch (const NumericalFailure& e) {
      throw CliError(kExitNumerical, "lcspice: error: " + path + ": no smooth reference: " + e.what());
    }
  }

  // Every method over its range of steps or tolerances.
  struct Plan {
    const MethodEntry* entry;
    std::string method, name;
    std::vector<double> values;
  };
  std::vector<Plan> plans;
  const bool q = settings.quick;
  for (const MethodEntry& m : method_registry()) {
    if (!settings.methods.empty() &&
        std::find(settings.methods.begin(), settings.methods.end(), m.name) == settings.methods.end())
      continue;
    if (m.bench_sweep == BenchSweep::Tolerance && m.smooth_model) {
      if (have_smooth) plans.push_back({&m, m.name, "rtol", q ? std::vector<double>{1e-4, 1e-7} : powers(1e-3, 1e-9, 1)});
    } else if (m.bench_sweep == BenchSweep::Tolerance) {
      // Not 1e-13: that run is the reference itself.
      plans.push_back({&m, m.name, "rtol", q ? std::vector<double>{1e-4, 1e-12} : powers(1e-3, 1e-11, 2)});
    } else {
      std::vector<double> steps;
      for (int k = q ? 1 : 2; k >= (q ? -1 : -4); k -= q ? 2 : 1) steps.push_back(h * std::ldexp(1.0, k));
      plans.push_back({&m, m.name, "h", steps});
    }
  }
  size_t total = 0, done = 0;
  for (const Plan& p : plans) total += p.values.size();
  std::vector<double> ngspice_reltols = q ? std::vector<double>{1e-3} : powers(1e-2, 1e-6, 1);
  if (settings.ngspice) total += ngspice_reltols.size();

  for (const Plan& p : plans) {
    for (double v : p.values) {
      report(p.method + " " + setting_text(p.name, v), 0.1 + 0.9 * done++ / std::max<size_t>(total, 1));
      const bool smooth_method = p.entry->smooth_model;
      const std::string reference = smooth_method ? kSmoothModel : kIdealModel;
      try {
        const Prepared& c = smooth_method ? smooth : ideal;
        Timed t = p.entry->bench_sweep == BenchSweep::StepSize
                      ? run(c, p.method, v, 0, 0, {}, min_s)
                      : run(c, p.method, h, v, smooth_method ? v * 1e-3 : 0, {}, min_s);
        BenchPoint b;
        b.method = p.method;
        b.setting = setting_text(p.name, v);
        b.parameter = v;
        b.reference = reference;
        b.error = smooth_method ? compare(t.sink, sref.sink, sref_scale, h) : compare(t.sink, ref.sink, ref_scale, h);
        b.error_vs_ideal = compare(t.sink, ref.sink, ref_scale, h);
        b.cpu_seconds = t.cpu;
        b.steps = t.summary.stepper.steps;
        b.lcp_solves = t.summary.stepper.lcp.solves;
        b.events = t.summary.stepper.events;
        b.rows = t.summary.rows;
        study.points.push_back(b);
      } catch (const NumericalFailure& e) {
        study.points.push_back(failed(p.method, setting_text(p.name, v), v, reference, e.what()));
      }
    }
  }

  // ngspice on the translated deck, compared at its own time points with both references
  // evaluated there (the event and smooth methods output at any requested time).
  if (settings.ngspice) {
    for (double reltol : ngspice_reltols) {
      report("ngspice " + setting_text("reltol", reltol), 0.1 + 0.9 * done++ / std::max<size_t>(total, 1));
      const std::string setting = setting_text("reltol", reltol);
      TranslationOptions topt;
      topt.emission = smoothing.emission;
      topt.saturation_current = smoothing.saturation_current;
      topt.options = extra_ngspice_options;
      for (const std::string& o : settings.ngspice_options) topt.options.push_back(o);
      topt.options.push_back(setting);
      const std::string reference = have_smooth ? kSmoothModel : kIdealModel;
      try {
        TranslatedDeck deck = translate_to_ngspice(*ideal.model, probes, topt);
        NgspiceRun nr;
        nr.deck = deck.lines;
        nr.timeout_seconds = settings.ngspice_timeout;
        // Like lcspice's runs, the best of a few (ngspice's own analysis CPU time each).
        NgspiceResult r = run_ngspice_transient(nr);
        for (int k = 1; k < (q ? 1 : 3); ++k) {
          NgspiceResult again = run_ngspice_transient(nr);
          r.analysis_cpu_seconds = std::min(r.analysis_cpu_seconds, again.analysis_cpu_seconds);
        }
        std::vector<double> times;
        for (double t : r.time)
          if (t > 0 && t <= ideal.tstop && (times.empty() || t > times.back())) times.push_back(t);
        MemorySink theirs;
        theirs.names = ideal.outputs.names;
        std::vector<std::vector<double>> series;
        for (const std::string& name : ideal.outputs.names) series.push_back(probe_series(r, deck.probes.at(name)));
        for (size_t k = 0; k < r.time.size(); ++k) {
          if (k > 0 && r.time[k] <= r.time[k - 1]) continue;
          Eigen::VectorXd row(series.size());
          for (size_t c = 0; c < series.size(); ++c) row(c) = series[c][k];
          theirs.times.push_back(r.time[k]);
          theirs.rows.push_back(row);
        }
        Timed ideal_there;
        if (fine_euler) ideal_there.sink = rows_at(ref.sink, times);
        else ideal_there = run(ideal, exact, h, 1e-13, 0, times, 0);
        BenchPoint b;
        b.method = "ngspice";
        b.setting = setting;
        b.parameter = reltol;
        b.reference = reference;
        b.error_vs_ideal = compare(theirs, ideal_there.sink, ref_scale, h);
        if (have_smooth) {
          Timed smooth_there = run(smooth, smooth_ref, h, 1e-10, 1e-13, times, 0);
          b.error = compare(theirs, smooth_there.sink, sref_scale, h);
        } else {
          b.error = b.error_vs_ideal;
        }
        b.cpu_seconds = r.analysis_cpu_seconds;
        b.steps = static_cast<long>(r.time.size());
        b.rows = static_cast<long>(r.time.size());
        study.points.push_back(b);
      } catch (const NgspiceError& e) {
        study.points.push_back(failed("ngspice", setting, reltol, reference,
                                      std::string("ngspice ") + to_string(e.kind()) + ": " + e.what()));
      } catch (const NumericalFailure& e) {
        study.points.push_back(failed("ngspice", setting, reltol, reference,
                                      std::string("reference at ngspice's points: ") + e.what()));
      }
    }
  }
  report("done", 1);
  return study;
}

}  // namespace lcs
