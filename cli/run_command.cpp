#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>

#include "cli/commands.h"
#include "cli/csv_writer.h"
#include "cli/exit_codes.h"
#include "cli/load_circuit.h"
#include "cli/measure.h"
#include "cli/progress.h"
#include "cli/source_sampling.h"
#include "solver/integrators/diode_refit.h"
#include "solver/integrators/fit_sensitivity.h"
#include "solver/integrators/transient.h"
#include "solver/model/netlist_options.h"
#include "solver/model/smooth_netlist.h"
#include "solver/model/numerical_failure.h"

namespace lcs {

namespace {

void note(const std::string& message) { std::cerr << "lcspice: note: " << message << "\n"; }

const MethodEntry& method_of(const TransientOptions& options) { return *find_method(options.method); }

// "event, smooth": the methods --rtol/--atol apply to.
std::string adaptive_method_names() {
  std::string out;
  for (const MethodEntry& e : method_registry())
    if (e.adaptive()) out += (out.empty() ? "" : ", ") + e.name;
  return out;
}

// The method that integrates Shockley diodes (smooth_reference); "(none)" if none is registered.
std::string smooth_method_name() {
  const MethodEntry* e = smooth_reference_method();
  return e ? e->name : "(none)";
}

// SPEC §1: --diode ideal | shockley | auto. Shockley diodes are integrated by the smooth-model
// method only; every other method solves complementarity problems with the ideal law.
void apply_diode_model(const RunArgs& args, TransientOptions& options) {
  const std::string& d = args.diode;
  if (d.empty() || d == "auto") return;
  const std::string smooth = smooth_method_name();
  if (d == "shockley") {
    if (!smooth_reference_method())
      throw CliError(kExitUsage, "error: --diode shockley: no method integrates Shockley diodes");
    if (args.method.empty()) options.method = smooth;
    if (!method_of(options).smooth_model)
      throw CliError(kExitUsage, "error: --diode shockley needs --method " + smooth + " (method " +
                                     options.method + " uses the ideal law)");
    return;
  }
  if (d == "ideal") {
    if (method_of(options).smooth_model)
      throw CliError(kExitUsage, "error: --method " + options.method + " integrates Shockley diodes; "
                                 "--diode ideal needs a complementarity method");
    return;
  }
  throw CliError(kExitUsage, "error: unknown diode model '" + d + "' (known: ideal, shockley, auto)");
}

// A sink whose finish() is left to its owner: the fallback run's rows replace the failed default
// run's CSV only when it succeeds (run_transient finishes its sink also on a numerical failure,
// with the rows so far; unfinished, CsvSink removes its temporary file).
class FinishOnSuccess : public OutputSink {
 public:
  explicit FinishOnSuccess(OutputSink& sink) : sink_(sink) {}
  void begin(const std::vector<std::string>& names) override { sink_.begin(names); }
  void row(double t, const Eigen::VectorXd& values) override { sink_.row(t, values); }
  void finish() override {}

 private:
  OutputSink& sink_;
};

ModelOptions refit_model_options(double tstop) {
  ModelOptions o;
  o.t1 = tstop;
  return o;
}

}  // namespace

int run_command(const RunArgs& args) {
  Netlist netlist = load_netlist(args.netlist, !(args.step && args.tstop));
  TransientOptions options;
  const bool deck_names_method = apply_netlist_options(netlist, options);
  if (!args.method.empty()) {
    if (!find_method(args.method))
      throw CliError(kExitUsage, "error: unknown method '" + args.method + "' (known: " +
                                     method_names() + ")");
    options.method = args.method;
  }
  if (args.theta) options.method_options.theta = *args.theta;
  options.method_options.euler_at_switching = args.euler_at_switching;
  apply_diode_model(args, options);
  if (args.rtol) options.method_options.rtol = *args.rtol;
  if (args.atol) options.method_options.atol = *args.atol;
  if (args.emission && !(*args.emission > 0))
    throw CliError(kExitUsage, "error: --emission must be positive");

  if (!netlist.tran && !(args.step && args.tstop)) {
    SourceLocation file_only;
    file_only.file = netlist.file;
    throw CliError(kExitNetlist, format_diagnostic(file_only, "error",
                                                   "no .tran card: nothing to simulate (add "
                                                   ".tran TSTEP TSTOP, or give --step and --tstop)"));
  }
  if (netlist.tran) {
    const TranSpec& tran = *netlist.tran;
    options.step = tran.tmax > 0 ? std::min(tran.tstep, tran.tmax) : tran.tstep;
    options.tstop = tran.tstop;
    options.tstart = tran.tstart;
    options.uic = tran.uic;
  }
  if (args.step) options.step = *args.step;
  if (args.tstop) options.tstop = *args.tstop;
  if (!netlist.tran)  // source defaults (SIN frequency, PULSE edges and width) follow the run
    for (Element& el : netlist.elements) el.waveform.reresolve(options.step, options.tstop);
  std::string why;
  if (!options.IsValid(&why)) {
    // Values from the .tran card are the netlist's: a located error (exit 2), not a usage one.
    if (netlist.tran && !args.step && !args.tstop)
      throw CliError(kExitNetlist, NetlistError(netlist.tran->loc, why).formatted());
    throw CliError(kExitUsage, "error: " + why);
  }

  auto smoothed = [&args](const Netlist& n) {
    SmoothingOptions smoothing;
    if (args.emission) smoothing.emission = *args.emission;
    try {
      return smooth_netlist(n, smoothing);
    } catch (const NetlistError& e) {
      throw CliError(kExitNetlist, e.formatted());
    }
  };
  if (method_of(options).smooth_model) netlist = smoothed(netlist);
  CircuitModel model = build_model(netlist, 0.0, options.tstop);
  // SPEC §1: event wherever it applies, unless a method is named (--method, .options method=,
  // --diode shockley).
  const bool method_defaulted = args.method.empty() && args.diode != "shockley" && !deck_names_method;
  if (method_defaulted) {
    std::string why;
    options.method = default_method_for(model, &why).name;
    if (!why.empty()) note("method " + options.method + ": the default method does not apply (" + why + ")");
  }
  // SPEC §3: event and smooth write rows at the multiples of TSTEP (plus events) also where the
  // deck's TMAX is smaller; TMAX then bounds smooth's steps. (The fixed-step methods step at it.)
  const bool tmax_below_tstep = netlist.tran && !args.step && netlist.tran->tmax > 0 &&
                                netlist.tran->tmax < netlist.tran->tstep;
  auto step_for_method = [&] {
    if (!tmax_below_tstep) return;
    const bool fixed = method_of(options).fixed_step();
    options.step = fixed ? netlist.tran->tmax : netlist.tran->tstep;
    options.method_options.max_step = fixed ? 0 : netlist.tran->tmax;
  };
  step_for_method();
  // A method that cannot integrate this circuit is a usage error (the netlist is fine, as another
  // method shows), like --diode shockley with a complementarity method.
  std::string not_applicable;
  if (method_of(options).applies && !method_of(options).applies(model, &not_applicable))
    throw CliError(kExitUsage, "error: method " + options.method + ": " + not_applicable);
  if (method_of(options).fixed_step()) guard_source_sampling(netlist, args.step.has_value(), "TSTEP", options);
  // The ideal run with its fitted lines refitted lower, kept to judge the final run against
  // (fit_sensitivity.h): made where lines were fitted and nothing else has judged them.
  std::unique_ptr<RecordedRows> lowered;
  std::string lowered_failure;
  FitSensitivityOptions sensitivity_options;
  sensitivity_options.unjudged = floating_potential_probes(model, probes_for(netlist, model, args.probes));
  // The runs made before the final one (the refit's passes, the lowered lines) fall back as the
  // final run does when the default method stops: euler, under the aliasing guard (silently: the
  // final run's note says so when it falls back too). A bridge whose fitted diodes differ stopped
  // the event method in a refit pass, and the refit kept its first pass's lines without a word.
  std::optional<TransientOptions> before_final_fallback;
  // --diode auto's ideal run, written instead where its smooth run stops at a numerical failure.
  struct IdealRun {
    Netlist netlist;
    CircuitModel model;
    TransientOptions options;
    std::string why_not;  // why auto chose the smooth method
  };
  std::optional<IdealRun> ideal_instead;
  if (method_defaulted && options.method == exact_reference_method().name && !method_of(options).smooth_model)
    before_final_fallback = fixed_step_fallback(netlist, options, tmax_below_tstep ? netlist.tran->tmax : options.step,
                                                args.step.has_value());
  if (!method_of(options).smooth_model) {
    // Cards without VON/RON: their lines refitted to the currents this circuit carries.
    DiodeRefitOptions refit_options;
    refit_options.fallback = before_final_fallback;
    const DiodeRefitResult refit = refit_diodes(netlist, refit_model_options(options.tstop), options, refit_options);
    if (refit.passes > 0) {
      if (args.stats) std::cerr << refit.BriefReport() << "\n";
      model = build_model(netlist, 0.0, options.tstop, refit.ranges);
      if (!refit.failure.empty())
        warn("fitting the diodes' lines to the currents they carry stopped at pass " + std::to_string(refit.passes) +
             " (" + refit.failure + "); the lines of the last pass that reached TSTOP are used");
    }
    const std::string poor = poor_fit_message(model);
    // --diode auto: the smooth method with Shockley diodes where a fit does not serve the circuit
    // (the whole circuit: the ideal and smooth models are not mixed in one run): a line poor over
    // the currents carried, or an answer that depends on the curve below them (fit_sensitivity.h).
    // An explicit --method of the ideal law is kept, with the warning.
    const bool auto_may_switch = args.diode == "auto" && args.method.empty() && smooth_reference_method() &&
                                 !first_switch(netlist);
    std::string smooth_because;
    if (auto_may_switch && !poor.empty()) {
      smooth_because = join_names(poorly_fitted_pairs(model)) + ": the ideal fit is poor over the currents carried";
    } else if (auto_may_switch && refit.passes > 0) {
      const FitSensitivityOptions& so = sensitivity_options;
      ModelOptions mo = refit_model_options(options.tstop);
      mo.diode_ranges = refit.ranges;
      const FitSensitivity s = fit_sensitivity(netlist, mo, options, probes_for(netlist, model, args.probes), so);
      if (args.stats && (s.measured || !s.failure.empty()))
        std::cerr << "fit sensitivity: " << s.Describe(so) << ", " << s.cpu_seconds << " s CPU\n";
      if (s.exceeds(so)) smooth_because = "the ideal answer depends on the junctions' curves: " + s.Describe(so);
    } else if (poor.empty() && refit.passes > 0) {
      ModelOptions mo = refit_model_options(options.tstop);
      mo.diode_ranges = refit.ranges;
      if (has_fitted_ranges(mo)) {
        lowered = std::make_unique<RecordedRows>();
        lowered_failure = run_with_lowered_lines(netlist, mo, options, probes_for(netlist, model, args.probes),
                                                 sensitivity_options, *lowered);
        if (!lowered_failure.empty() && before_final_fallback) {
          lowered = std::make_unique<RecordedRows>();
          lowered_failure = run_with_lowered_lines(netlist, mo, *before_final_fallback,
                                                   probes_for(netlist, model, args.probes), sensitivity_options,
                                                   *lowered);
        }
      }
    }
    if (!smooth_because.empty()) {
      std::cerr << "lcspice: --diode auto: " << smooth_because << "; running --method " << smooth_method_name()
                << " with Shockley diodes\n";
      ideal_instead.emplace(IdealRun{netlist, std::move(model), options, smooth_because});
      options.method = smooth_method_name();
      netlist = smoothed(netlist);
      model = build_model(netlist, 0.0, options.tstop);
    } else if (!poor.empty()) {
      warn(poor);
    }
  }
  // Judged against the method that runs: after the default is picked and --diode auto's switch.
  if (args.theta && !method_of(options).uses_theta)
    warn("--theta is used only by --method theta; method " + options.method + " ignores it");
  if (args.euler_at_switching && !method_of(options).uses_theta)
    warn("--euler-at-switching is used only by --method theta; method " + options.method + " ignores it");
  if ((args.rtol || args.atol) && !method_of(options).adaptive())
    warn("--rtol/--atol are used by the adaptive methods (" + adaptive_method_names() + "); " +
         options.method + " has a fixed step (--step)");
  if (args.emission && !method_of(options).smooth_model)
    warn("--emission is used only by --method " + smooth_method_name() + "; method " + options.method +
         " ignores it");
  const std::vector<Probe> probes = probes_for(netlist, model, args.probes);
  // `.meas`: the probes the measures read that the CSV does not write are run as hidden columns
  // after the CSV's own (MeasureTap keeps them out of the CSV).
  std::vector<Probe> run_probes = probes;
  std::vector<std::string> measured;
  for (const Probe& p : measure_probes(netlist.measures)) {
    measured.push_back(p.name());
    if (std::none_of(probes.begin(), probes.end(), [&](const Probe& q) { return q.name() == p.name(); }))
      run_probes.push_back(p);
  }
  OutputMap outputs = output_map_or_exit(model, run_probes);
  for (const std::string& w : floating_probe_warnings(model, probes)) warn(w);
  if (!options.uic)
    for (const std::string& w : dc_floating_start_warnings(model, netlist, &probes)) warn(w);
  // The default method (event) failing is not the end of a run nobody asked a method of: the
  // fixed-step default runs it again, with a warning, where the CSV can be written afresh (a file,
  // not standard output or a pipe). Its rows replace the CSV only if it gets to TSTOP; else the
  // default method's rows and failure stand. A method that was named fails as named.
  const bool may_fall_back = method_defaulted && options.method == exact_reference_method().name &&
                             !method_of(options).smooth_model;
  std::optional<NumericalFailure> default_failure;
  std::string default_where;
  for (;;) {
    CsvSink sink(args.output);
    FinishOnSuccess deferred(sink);
    OutputSink& out = default_failure ? static_cast<OutputSink&>(deferred) : sink;
    RecordedRows nominal;
    RowTee sink_and_nominal(out, nominal);
    TransientSummary failed;  // the summary up to a numerical failure
    OutputSink& csv_side = lowered ? static_cast<OutputSink&>(sink_and_nominal) : out;
    MeasureTap tap(csv_side, probes.size(), measured);
    try {
      TransientSummary summary;
      {
        ProgressLine progress("run " + options.method);
        if (progress.enabled()) options.progress = [&progress](double f) { progress.update(f); };
        summary = run_transient(model, outputs, options, netlist.measures.empty() ? csv_side : tap, &failed);
      }
      if (default_failure) sink.finish();
      for (const std::string& w : summary.warnings) warn(w);
      if (lowered) {
        FitSensitivity s;
        s.failure = lowered_failure;
        if (lowered_failure.empty()) s = compare_with_lowered(nominal, *lowered, options.step, sensitivity_options);
        if (args.stats) std::cerr << "fit sensitivity: " << s.Describe(sensitivity_options) << "\n";
        if (s.exceeds(sensitivity_options))
          warn("the ideal answer depends on the junctions' curves below the currents they carry (" +
               s.Describe(sensitivity_options) + "): use --diode auto (the Shockley junctions where it does), "
               "--diode shockley, or give VON/RON on the cards");
      }
      if (args.stats) std::cerr << summary.BriefReport() << "\n";
      if (!sink.path().empty() && sink.path() != "-")
        std::cerr << "lcspice: wrote " << summary.rows << " rows to " << sink.path() << "\n";
      // After a numerical failure (below) there are no measures (the run did not reach TSTOP), a warning.
      if (!netlist.measures.empty()) report_measures(evaluate_measures(netlist.measures, tap.waveforms()), std::cerr);
      return kExitOk;
    } catch (const NumericalFailure& e) {
      if (args.stats) std::cerr << failed.BriefReport() << "\n";
      std::string where;
      if (!sink.path().empty() && sink.path() != "-")
        where = sink.rows() > 0 ? "; rows computed so far are in " + sink.path()
                                : "; no row was computed (" + sink.path() + " holds the header only)";
      // No measures after a numerical failure (the run did not reach TSTOP), but a word that they
      // were not computed.
      auto measures_not_computed = [&] {
        if (!netlist.measures.empty())
          warn(".meas results not computed: the run stopped early at a numerical failure (" +
               std::to_string(netlist.measures.size()) + (netlist.measures.size() == 1 ? " measure)" : " measures)"));
      };
      if (default_failure) {
        measures_not_computed();
        throw CliError(kExitNumerical, std::string("lcspice: error: numerical failure ") + default_failure->what() +
                                           " (--method " + options.method + ", tried next, failed too " + e.what() +
                                           ")" + default_where);
      }
      // --diode auto: a smooth run that stops (a BJT switching an inductor off with no junction
      // capacitance: the collector's voltage jumps, and IDA's step fell to 1e-19 s) gives way to
      // the ideal answer it was chosen over, with the reason it was.
      if (ideal_instead && sink.replaceable()) {
        default_failure = e;
        default_where = where;
        warn("--diode auto: method " + options.method + " failed " + e.what() + "; writing the ideal answer (method " +
             ideal_instead->options.method + ", the junctions' fitted lines) instead, passed over because " +
             ideal_instead->why_not);
        netlist = std::move(ideal_instead->netlist);
        model = std::move(ideal_instead->model);
        options = ideal_instead->options;
        ideal_instead.reset();
        outputs = output_map_or_exit(model, run_probes);
        continue;
      }
      // The fixed-step default stands in unless it too would refuse (a source it would need more
      // than kMaxGuardedSteps steps to resolve, a step count that stopped the event method too):
      // then the event method's failure and rows stand.
      if (may_fall_back && sink.replaceable() && before_final_fallback) {
        default_failure = e;
        default_where = where;
        warn(std::string("method ") + options.method + " failed " + e.what() + "; running --method " +
             fixed_step_default_method().name + " (the fixed-step default) instead");
        options.method = fixed_step_default_method().name;
        step_for_method();
        guard_source_sampling(netlist, args.step.has_value(), "TSTEP", options);
        lowered.reset();  // judged against the event run's rows: not this run's
        continue;
      }
      measures_not_computed();
      throw CliError(kExitNumerical, std::string("lcspice: error: numerical failure ") + e.what() + where);
    }
  }
}

}  // namespace lcs
