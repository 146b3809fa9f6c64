#include "cli/source_sampling.h"

#include <cmath>
#include <cstdio>
#include <iostream>

#include "cli/exit_codes.h"
#include "cli/load_circuit.h"

namespace lcs {

namespace {

// The most steps the guard subdivides to before it refuses instead.
constexpr double kMaxGuardedSteps = 1e7;

constexpr double kStepsPerPeriod = 50;
constexpr double kStepsPerPulseWidth = 5;
constexpr double kStepsPerTimeConstant = 5;

std::string seconds(double t) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g s", t);
  return buf;
}

void consider(std::optional<SourceFeature>& finest, const Element& e, const std::string& what,
              double length, double steps, double oscillates_for = 0) {
  if (!(length > 0) || !std::isfinite(length)) return;
  const double max_step = length / steps;
  if (!finest || max_step < finest->max_step)
    finest = SourceFeature{e.name, what + " " + seconds(length), max_step, oscillates_for};
}

void features_of(const Element& e, std::optional<SourceFeature>& finest) {
  const Waveform& w = e.waveform;
  const std::vector<double>& p = w.params;
  const int written = w.written < 0 ? static_cast<int>(p.size()) : w.written;
  switch (w.kind) {
    case Waveform::Kind::Dc:
      return;
    case Waveform::Kind::Sin:  // SIN(VO VA FREQ TD THETA PHASE)
      if (p.size() >= 3 && p[1] != 0 && p[2] > 0)
        consider(finest, e, "period", 1.0 / p[2], kStepsPerPeriod,
                 w.sine_end());
      return;
    case Waveform::Kind::Pulse:  // PULSE(V1 V2 TD TR TF PW PER)
      if (p.size() < 7 || p[0] == p[1]) return;
      if (written >= 4) consider(finest, e, "rise time", p[3], 1);
      if (written >= 5) consider(finest, e, "fall time", p[4], 1);
      if (written >= 6) consider(finest, e, "pulse width", p[5], kStepsPerPulseWidth);
      if (written >= 7) consider(finest, e, "period", p[6], kStepsPerPeriod);
      return;
    case Waveform::Kind::Exp:  // EXP(V1 V2 TD1 TAU1 TD2 TAU2): a written time constant
      if (p.size() < 6 || p[0] == p[1]) return;
      if (written >= 4) consider(finest, e, "time constant TAU1", p[3], kStepsPerTimeConstant);
      if (written >= 6) consider(finest, e, "time constant TAU2", p[5], kStepsPerTimeConstant);
      return;
    case Waveform::Kind::Sffm:  // SFFM(VO VA FC MDI FS ...): the highest instantaneous frequency
      if (p.size() >= 5 && p[1] != 0 && p[2] > 0)
        consider(finest, e, "shortest period", 1.0 / (p[2] + std::abs(p[3]) * std::abs(p[4])), kStepsPerPeriod,
                 INFINITY);
      return;
    case Waveform::Kind::Am:  // AM(VO VMO VMA FM FC ...): the upper sideband FC + FM
      if (p.size() >= 5 && (p[1] != 0 || p[2] != 0) && p[4] > 0)
        consider(finest, e, "carrier period", 1.0 / (p[4] + std::abs(p[3])), kStepsPerPeriod, INFINITY);
      return;
    case Waveform::Kind::Pwl:  // PWL(t1 v1 t2 v2 ...): a segment along which the value changes
      for (std::size_t k = 2; k + 1 < p.size(); k += 2)
        if (p[k + 1] != p[k - 1]) consider(finest, e, "PWL segment", p[k] - p[k - 2], 1);
      return;
  }
}

}  // namespace

std::optional<SourceFeature> finest_source_feature(const Netlist& netlist) {
  std::optional<SourceFeature> finest;
  for (const Element& e : netlist.elements)
    if (e.kind == ElementKind::VoltageSource || e.kind == ElementKind::CurrentSource) features_of(e, finest);
  return finest;
}

namespace {

// Steps per output step for `finest` at options.step (1: the step resolves it), 0 past the limit.
int substeps_for(const std::optional<SourceFeature>& finest, const TransientOptions& options) {
  if (!finest || options.step <= finest->max_step * (1 + 1e-9)) return 1;
  const double k = std::ceil(options.step / finest->max_step * (1 - 1e-12));
  return k * (options.tstop / options.step) > kMaxGuardedSteps ? 0 : static_cast<int>(k);
}

}  // namespace

std::optional<TransientOptions> fixed_step_fallback(const Netlist& netlist, TransientOptions options, double step,
                                                    bool step_given) {
  options.method = fixed_step_default_method().name;
  options.method_options.max_step = 0;
  options.step = step;
  options.substeps = step_given ? 1 : substeps_for(finest_source_feature(netlist), options);
  if (options.substeps == 0) return std::nullopt;
  return options;
}

void guard_source_sampling(const Netlist& netlist, bool step_given, const std::string& step_name,
                           TransientOptions& options) {
  const std::optional<SourceFeature> finest = finest_source_feature(netlist);
  if (!finest || options.step <= finest->max_step * (1 + 1e-9)) return;
  const std::string source = "source " + finest->element + "'s " + finest->what;
  if (step_given) {
    warn("--step " + seconds(options.step) + " is longer than " + seconds(finest->max_step) + " (" + source +
         "): " + options.method + " samples that source too coarsely to resolve it");
    return;
  }
  const int k = substeps_for(finest, options);
  if (k == 0) {
    // The event method takes edges and PWL corners exactly, but its steps are bounded by an
    // oscillating source too (0.5/omega: 4 pi a period, against the 50 here), and past its own
    // limit of 1e10 steps (event_driven.h) it is no remedy.
    const double oscillating = std::min(finest->oscillates_for, options.tstop);
    const bool event_would_do = oscillating / finest->max_step * (4 * M_PI / kStepsPerPeriod) <= 1e10;
    const std::string remedy = event_would_do ? "use --method event (exact between events) or give --step"
                                              : "shorten the .tran or give --step";
    const std::string message = step_name + " " + seconds(options.step) + " cannot resolve " + source + ": " +
                                options.method + " would need steps of " + seconds(finest->max_step) +
                                ", more than " + std::to_string(static_cast<long>(kMaxGuardedSteps)) +
                                " steps; " + remedy;
    if (netlist.tran) {
      std::string located = NetlistError(netlist.tran->loc, message).formatted();
      const Element* e = netlist.find_element(finest->element);
      if (e && e->loc.known())
        located += "\n" + format_diagnostic(e->loc, "note", source + " is written here");
      throw CliError(kExitNetlist, located);
    }
    throw CliError(kExitUsage, "error: " + message);
  }
  options.substeps = k;
  std::cerr << "lcspice: note: " << options.method << " steps at " << seconds(options.step / k) << " ("
            << options.substeps << " per " << step_name << " " << seconds(options.step) << ", to resolve " << source
            << "); rows every " << step_name << "\n";
}

}  // namespace lcs
