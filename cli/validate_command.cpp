// `lcspice validate`: the same circuit in lcspice (ideal diodes) and in ngspice (Shockley diodes,
// in-process through libngspice), every probe compared on lcspice's time grid. With
// `--method smooth` lcspice integrates the very Shockley diodes the ngspice deck gets
// (smooth_netlist with validate's emission and saturation current): the same model on both
// sides, so what remains is the two integrators' error.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <optional>
#include <iostream>
#include <sstream>

#include <unistd.h>

#include "cli/atomic_file.h"
#include "cli/commands.h"
#include "cli/csv_writer.h"
#include "cli/exit_codes.h"
#include "cli/gnuplot.h"
#include "cli/load_circuit.h"
#include "ngspice/deck_translation.h"
#include "ngspice/ngspice_session.h"
#include "ngspice/probe_series.h"
#include "solver/integrators/transient.h"
#include "solver/devices/diode.h"
#include "solver/model/initial_state.h"
#include "solver/model/numerical_failure.h"
#include "solver/model/smooth_netlist.h"

namespace lcs {

namespace {

struct ProbeComparison {
  std::string name;
  double max_error = 0, range = 0, magnitude = 0, worst_time = 0;
  // Relative to the range; a probe that is constant in lcspice is measured against its size.
  double relative() const {
    const double scale = range > 0 ? range : magnitude > 0 ? magnitude : 1.0;
    return max_error / scale;
  }
};

// Linear interpolation of (t, y) at time s (t increasing; clamped at the ends).
double interpolate(const std::vector<double>& t, const std::vector<double>& y, double s) {
  if (s <= t.front()) return y.front();
  if (s >= t.back()) return y.back();
  const size_t k = std::upper_bound(t.begin(), t.end(), s) - t.begin();
  const double w = (s - t[k - 1]) / (t[k] - t[k - 1]);
  return y[k - 1] + w * (y[k] - y[k - 1]);
}

std::vector<double> ngspice_series(const NgspiceResult& r, const ProbeSource& src,
                                   const std::string& probe) {
  try {
    return probe_series(r, src);
  } catch (const NgspiceError& e) {
    throw CliError(kExitNumerical, std::string("lcspice: error: ") + e.what() + " for probe " + probe);
  }
}

std::string file_stem(const std::string& path) {
  const size_t dot = path.rfind('.');
  return dot != std::string::npos && path.find('/', dot) == std::string::npos ? path.substr(0, dot) : path;
}

std::string sanitized(const std::string& probe) {
  std::string s;
  for (char c : probe) s += std::isalnum(static_cast<unsigned char>(c)) || c == '.' ? c : '_';
  while (!s.empty() && s.back() == '_') s.pop_back();
  return s;
}

void write_atomically(const std::string& path, const std::string& text) {
  AtomicFile file(path);
  {
    std::ofstream out(file.temp());
    out << text;
    if (!out) throw CliError(kExitUsage, "error: cannot write '" + path + "'");
  }
  file.commit();
}

// The report: the table as CSV, both waveforms per probe as CSV, one PNG overlay per probe.
void write_report(const std::string& path, const std::vector<ProbeComparison>& rows, double tol,
                  const MemorySink& ours, const std::vector<std::vector<double>>& theirs,
                  const std::string& our_model) {
  std::ostringstream table;
  table << "probe,max_abs_error,range,max_error_over_range,time_of_worst,tolerance,within\n";
  char buf[256];
  for (const ProbeComparison& c : rows) {
    std::snprintf(buf, sizeof buf, ",%.6e,%.6e,%.6e,%.9e,%.3e,%s\n", c.max_error, c.range,
                  c.relative(), c.worst_time, tol, c.relative() <= tol ? "yes" : "no");
    table << csv_quote(c.name) << buf;
  }
  write_atomically(path, table.str());

  const std::string stem = file_stem(path);
  std::ostringstream waves;
  waves << "time";
  for (const ProbeComparison& c : rows) waves << "," << csv_quote("lcspice " + c.name) << "," << csv_quote("ngspice " + c.name);
  waves << "\n";
  for (size_t k = 0; k < ours.times.size(); ++k) {
    std::snprintf(buf, sizeof buf, "%.14e", ours.times[k]);
    waves << buf;
    for (size_t p = 0; p < rows.size(); ++p) {
      std::snprintf(buf, sizeof buf, ",%.14e,%.14e", ours.rows[k](p), theirs[p][k]);
      waves << buf;
    }
    waves << "\n";
  }
  const std::string waves_path = stem + "_waveforms.csv";
  write_atomically(waves_path, waves.str());

  std::string script = "set datafile separator comma\nset grid\nset key outside right\n"
                       "set terminal pngcairo size 1100,450 noenhanced font ',10'\n"
                       "set xlabel 'time [s]'\n";
  std::vector<std::unique_ptr<AtomicFile>> pngs;
  for (size_t p = 0; p < rows.size(); ++p) {
    pngs.push_back(std::make_unique<AtomicFile>(stem + "_" + sanitized(rows[p].name) + ".png"));
    script += "set output " + gnuplot_string(pngs.back()->temp()) + "\nset title " +
              gnuplot_string(rows[p].name + ": lcspice (" + our_model + ") and ngspice (Shockley)") +
              "\nplot " + gnuplot_string(waves_path) + " skip 1 using 1:" + std::to_string(2 + 2 * p) +
              " with lines lw 2 title 'lcspice', " + gnuplot_string(waves_path) + " skip 1 using 1:" +
              std::to_string(3 + 2 * p) + " with lines lw 1 dt 2 title 'ngspice'\n";
  }
  script += "set output\n";
  run_gnuplot(script, "the report");
  for (auto& png : pngs) png->commit();
}

}  // namespace

int validate_command(const ValidateArgs& args) { return validate_with_reversed_diodes(args, {}); }

int validate_with_reversed_diodes(const ValidateArgs& args,
                                  const std::set<std::string>& reversed_in_ngspice_deck) {
  Netlist netlist = load_netlist(args.netlist);
  if (!netlist.tran) {
    SourceLocation file_only;
    file_only.file = netlist.file;
    throw CliError(kExitNetlist, format_diagnostic(file_only, "error", "no .tran card: nothing to validate"));
  }
  TransientOptions run;
  run.method = args.method.empty() ? default_method().name : args.method;
  if (!find_method(run.method))
    throw CliError(kExitUsage, "error: unknown method '" + run.method + "' (known: " + method_names() + ")");
  // lcspice's own first-order error must sit well below the model gap being checked.
  run.step = args.step ? *args.step : netlist.tran->tstep / 10;
  run.tstop = netlist.tran->tstop;
  run.tstart = netlist.tran->tstart;
  run.uic = netlist.tran->uic;
  std::string why;
  if (!run.IsValid(&why)) {
    if (!args.step) throw CliError(kExitNetlist, NetlistError(netlist.tran->loc, why).formatted());
    throw CliError(kExitUsage, "error: " + why);
  }
  auto positive = [](double v) { return v > 0 && std::isfinite(v); };
  if (!positive(args.tol)) throw CliError(kExitUsage, "error: --tol must be a positive number");
  if (!positive(args.emission)) throw CliError(kExitUsage, "error: --emission must be a positive number");
  if (!positive(args.timeout)) throw CliError(kExitUsage, "error: --timeout must be a positive number of seconds");
  if (args.max_step && !positive(*args.max_step))
    throw CliError(kExitUsage, "error: --max-step must be a positive number");

  CircuitModel model = build_model(netlist, 0.0, run.tstop);
  // What lcspice integrates: the ideal circuit, or for `smooth` the Shockley circuit of the deck.
  const bool smooth = find_method(run.method)->smooth_model;
  TranslationOptions topt;
  std::optional<CircuitModel> smooth_model;
  if (smooth) {
    SmoothingOptions so;
    so.emission = args.emission;
    so.saturation_current = topt.saturation_current;
    smooth_model = build_model(smooth_netlist(netlist, so), 0.0, run.tstop);
  }
  const CircuitModel& ours_model = smooth ? *smooth_model : model;
  std::vector<Probe> probes = probes_for(netlist, model, args.probes);
  if (probes.empty()) {
    SourceLocation file_only;
    file_only.file = netlist.file;
    throw CliError(kExitNetlist, format_diagnostic(file_only, "error", "nothing to compare: the circuit has no probes"));
  }
  // The comparison needs every diode current too, for the expected model gap.
  std::vector<Probe> all = probes;
  for (const PairInfo& p : model.pairs())
    all.push_back({Probe::Kind::ElementCurrent, netlist.elements[p.element].name, "", {}});
  OutputMap outputs = output_map_or_exit(ours_model, all);

  topt.emission = args.emission;
  if (args.max_step) topt.max_step = *args.max_step;
  topt.options = args.ngspice_options;
  topt.reversed_diodes = reversed_in_ngspice_deck;
  const bool element_ics = std::any_of(netlist.elements.begin(), netlist.elements.end(),
                                       [](const Element& el) { return el.ic.has_value(); });
  if (!run.uic && element_ics) {
    // ngspice honours IC= only with UIC; lcspice applies it over the operating point. Start
    // ngspice from lcspice's initial state instead: every capacitor voltage and inductor current.
    try {
      const CircuitModel& m = ours_model;
      const InitialState init = initial_state(m, false, 0.0);
      const Eigen::VectorXd z0 = Eigen::VectorXd::Zero(m.lcs().pairs());
      const CircuitGraph& g = m.graph();
      for (size_t b = 0; b < g.branches.size(); ++b) {
        if (g.branches[b].cls == BranchClass::Capacitor)
          topt.initial_conditions[g.branches[b].name] = m.evaluate_dc(m.branch_voltage(b), init.x, z0, 0.0);
        if (g.branches[b].cls == BranchClass::Inductor)
          topt.initial_conditions[g.branches[b].name] = m.evaluate_dc(m.branch_current(b), init.x, z0, 0.0);
      }
    } catch (const NumericalFailure& e) {
      throw CliError(kExitNumerical, std::string("lcspice: error: numerical failure ") + e.what());
    }
  }
  TranslatedDeck deck = translate_to_ngspice(model, all, topt);
  if (args.print_deck) {
    for (const std::string& line : deck.lines) std::cout << line << "\n";
    return kExitOk;
  }

  MemorySink ours;
  try {
    run_transient(ours_model, outputs, run, ours);
  } catch (const NumericalFailure& e) {
    throw CliError(kExitNumerical, std::string("lcspice: error: numerical failure ") + e.what());
  }
  NgspiceResult theirs;
  try {
    NgspiceRun nr;
    nr.deck = deck.lines;
    nr.timeout_seconds = args.timeout;
    theirs = run_ngspice_transient(nr);
  } catch (const NgspiceError& e) {
    std::string text = std::string("lcspice: error: ngspice failed: ") + e.what();
    const auto& m = e.messages();
    for (size_t k = m.size() > 8 ? m.size() - 8 : 0; k < m.size(); ++k) text += "\n  ngspice: " + m[k];
    throw CliError(kExitNumerical, text);
  }
  if (theirs.time.size() < 2)
    throw CliError(kExitNumerical, "lcspice: error: ngspice returned fewer than 2 time points");

  std::vector<ProbeComparison> rows;
  std::vector<std::vector<double>> interpolated;
  for (size_t p = 0; p < probes.size(); ++p) {
    const std::string name = outputs.names[p];
    const std::vector<double> y = ngspice_series(theirs, deck.probes.at(name), name);
    ProbeComparison c;
    c.name = name;
    double lo = INFINITY, hi = -INFINITY;
    std::vector<double> at_ours(ours.times.size());
    for (size_t k = 0; k < ours.times.size(); ++k) {
      const double mine = ours.rows[k](p);
      at_ours[k] = interpolate(theirs.time, y, ours.times[k]);
      lo = std::min(lo, mine);
      hi = std::max(hi, mine);
      c.magnitude = std::max(c.magnitude, std::abs(mine));
      const double e = std::abs(mine - at_ours[k]);
      if (e > c.max_error) c.max_error = e, c.worst_time = ours.times[k];
    }
    c.range = hi - lo;
    rows.push_back(c);
    interpolated.push_back(std::move(at_ours));
  }

  // Expected gap between the models: about N Vt ln(I/IS) per conducting ideal junction.
  double peak = 0;
  for (size_t p = probes.size(); p < all.size(); ++p)
    for (const Eigen::VectorXd& row : ours.rows) peak = std::max(peak, row(p));
  const double gap = peak > 0 ? args.emission * kThermalVoltage * std::log(peak / topt.saturation_current) : 0.0;

  std::printf("validate %s\n", netlist.file.c_str());
  if (smooth)
    std::printf("  lcspice: Shockley diodes, smooth (SUNDIALS IDA), output every %g s, %zu rows\n",
                run.step, ours.times.size());
  else
    std::printf("  lcspice: ideal diodes, %s, h = %g s, %zu rows\n", run.method.c_str(), run.step, ours.times.size());
  std::printf("  ngspice: %zu time points, %.3f s CPU\n", theirs.time.size(), theirs.analysis_cpu_seconds);
  if (smooth)
    std::printf("  both integrate the same Shockley diodes (ideal ones as VON sources + N = %g, IS = %g A):\n"
                "  expected model gap 0; what differs is the two integrators' error\n",
                args.emission, topt.saturation_current);
  else if (!deck.ideal_diodes.empty())
    std::printf("  ideal diodes as VON sources + Shockley diodes (N = %g, IS = %g A); expected model gap:\n"
                "  about %.3g V per conducting junction (N Vt ln(I/IS) at the peak diode current %.3g A)\n",
                args.emission, topt.saturation_current, gap, peak);
  if (!smooth && deck.ideal_diodes.size() < model.pairs().size())
    std::printf("  diodes with their own IS/N/RS: compared as the card gives them (the gap is the "
                "card's Shockley curve against lcspice's VON/RON)\n");
  std::printf("\n");
  std::printf("  %-16s %12s %12s %14s %14s\n", "probe", "max|error|", "range", "max|err|/range", "at t");
  bool ok = true;
  for (const ProbeComparison& c : rows) {
    const bool within = c.relative() <= args.tol;
    ok = ok && within;
    std::printf("  %-16s %12.4e %12.4e %14.4e %14.6e  %s\n", c.name.c_str(), c.max_error, c.range,
                c.relative(), c.worst_time, within ? "ok" : "OUTSIDE");
  }
  std::printf("\n%s: every probe within %g of its range\n", ok ? "PASS" : "FAIL", args.tol);
  if (!ok) std::printf("(a probe outside tolerance: exit code 4)\n");
  std::fflush(stdout);
  if (!args.report.empty()) write_report(args.report, rows, args.tol, ours, interpolated,
                                        smooth ? "Shockley diodes" : "ideal diodes");
  return ok ? kExitOk : kExitValidate;
}

}  // namespace lcs
