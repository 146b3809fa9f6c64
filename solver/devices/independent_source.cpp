#include "solver/devices/independent_source.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "solver/devices/two_terminal_cards.h"

namespace lcs {

namespace {

// The waveform as ngspice reads it. lcspice: a zero PULSE rise/fall time is a jump, and at the
// instant itself the value after it; ngspice would replace a zero by TSTEP, so the edge becomes
// one of 1e-6 TSTOP that ends at the jump (shorter ones are lost to its breakpoint resolution).
// EXP likewise: ngspice reads a zero TD1, TAU1, TD2 or TAU2 as its default (TSTEP-based), so a
// zero delay is written as 1e-6 TSTOP and a zero time constant (a jump here) as 1e-6 TSTOP.
std::string ngspice_waveform(Waveform w, double tstop) {
  const double eps = 1e-6 * tstop;
  if (w.kind == Waveform::Kind::Pulse && w.params.size() >= 7) {
    double& td = w.params[2];
    double& tr = w.params[3];
    double& tf = w.params[4];
    double& pw = w.params[5];
    double& per = w.params[6];
    if (tr == 0.0) td -= eps, tr = eps;
    if (tf == 0.0) pw = std::max(0.0, pw - eps), tf = eps;
    // ngspice reads a written 0 as its default here too: PW and PER = TSTOP. lcspice's PW 0 is no
    // plateau, its PER 0 one pulse (ngspice's second would start at TD + TSTOP, before TSTOP
    // where TD was moved back for a jump above: a 5 V row at TSTOP where lcspice has 0).
    if (pw == 0.0) pw = eps;
    if (per <= 0.0) per = 2 * tstop + std::abs(td) + tr + pw + tf;
  }
  if (w.kind == Waveform::Kind::Exp && w.params.size() >= 6) {
    double& td1 = w.params[2];
    double& td2 = w.params[4];
    if (td1 == 0.0) td1 = eps;
    if (td2 <= td1) td2 = td1;  // the second term starts with the first (as here)
    for (std::size_t k : {3, 5})
      if (w.params[k] == 0.0) w.params[k] = eps;
  }
  return w.describe();
}

std::string exact(double x) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

// SFFM and AM as a behavioural source's expression of `time`. Written out rather than passed
// through because ngspice's own keywords changed meaning: ngspice 39 (the library `validate`
// may load) reads AM(VA VO MF FC TD) and SFFM(VO VA FC MDI FS PHASEC PHASES) with no TD, while
// ngspice 40 and later, whose definitions lcspice follows, read AM(VO VMO VMA FM FC TD PHASEM
// PHASEC) and SFFM(VO VA FC MDI FS TD PHASEM PHASEC). Empty for the other waveforms. Its value
// from TD on (the caller gates it to 0 before a TD > 0: gate_pulse).
std::string modulated_expression(const Waveform& w) {
  if ((w.kind != Waveform::Kind::Am && w.kind != Waveform::Kind::Sffm) || w.params.size() < 8) return "";
  const std::vector<double>& p = w.params;
  const double two_pi = 6.283185307179586, degree = two_pi / 360;
  const std::string tau = p[5] == 0.0 ? "time" : "(time-" + exact(p[5]) + ")";
  auto sine = [&](double f, double phase) {
    return "sin(" + exact(two_pi * f) + "*" + tau + "+" + exact(phase * degree) + ")";
  };
  std::string e;
  if (w.kind == Waveform::Kind::Am) {
    e = exact(p[0]) + "+(" + exact(p[1]) + "+" + exact(p[2]) + "*" + sine(p[3], p[6]) + ")*" + sine(p[4], p[7]);
  } else {
    e = exact(p[0]) + "+" + exact(p[1]) + "*sin(" + exact(two_pi * p[2]) + "*" + tau + "+" +
        exact(p[7] * degree) + "+" + exact(p[3]) + "*" + sine(p[4], p[6]) + ")";
  }
  return e;
}

// A 0 -> 1 step at TD as an ngspice PULSE, which gives ngspice breakpoints at the jump (a
// behavioural source has none, and ngspice would step across it and interpolate): its edge is
// 1e-6 TSTOP long and ends at TD, as a zero PULSE edge is written.
std::string gate_pulse(double td, double tstop) {
  double edge = std::min(1e-6 * tstop, td / 2);
  return "PULSE(0 1 " + exact(td - edge) + " " + exact(edge) + " " + exact(edge) + " " + exact(10 * tstop) + " " +
         exact(20 * tstop) + ")";
}

}  // namespace

// LTspice's SIN with NCYCLES (which ngspice does not read) as ngspice's SIN plus a second SIN that
// starts at TE = TD + NCYCLES/FREQ and cancels it: amplitude -VA' (VA' = VA exp(-THETA (TE - TD)),
// the envelope at TE), phase PHASE + 360 NCYCLES (the first's phase at TE), offset VA' sin of that
// phase. Before TE the second is its offset plus -VA' sin(phase) (ngspice's value before a TD):
// zero; from TE on the sines cancel and the offset is the held value's VA' sin(...). In series
// for a voltage source, in parallel (behind the ammeter) for a current source.
NgspiceCards IndependentSource::stopped_sine_cards(const NgspiceDeckContext& context) const {
  Waveform main = element_.waveform;
  main.params.resize(6);
  const std::vector<double>& p = element_.waveform.params;
  const double te = element_.waveform.sine_end();
  const double va_end = p[1] * std::exp(-p[4] * (te - p[3]));
  const double phase_end = std::fmod(p[5] + 360.0 * p[6], 360.0);
  Waveform cancel = main;
  cancel.params = {va_end * std::sin(phase_end * 3.14159265358979323846 / 180.0), -va_end, p[2], te, p[4], phase_end};
  const std::string plus = element_.nodes.at(0), minus = element_.nodes.at(1);
  NgspiceCards cards;
  if (voltage_) {
    const std::string deck = deck_name('v', name()), mid = context.fresh("lcs_" + name() + "_ncycles");
    cards.lines.push_back(deck + " " + plus + " " + mid + " " + main.describe());
    cards.lines.push_back(context.fresh(deck_name('v', name() + "_ncycles")) + " " + mid + " " + minus + " " +
                          cancel.describe());
    cards.probes["i(" + name() + ")"] = {deck + "#branch", ""};
    return cards;
  }
  return parallel_two_terminal_cards({{deck_name('i', name()), main.describe()},
                                      {context.fresh(deck_name('i', name() + "_ncycles")), cancel.describe()}},
                                     plus, minus, name(), context);
}

IndependentSource::IndependentSource(const Element& element, const Netlist& netlist,
                                     const DeviceOptions&)
    : Device(element), voltage_(element.kind == ElementKind::VoltageSource) {}

std::vector<BranchDecl> IndependentSource::branches() const {
  return {{name(), voltage_ ? BranchClass::VoltageSource : BranchClass::CurrentSource,
           element_.nodes.at(0), element_.nodes.at(1)}};
}

void IndependentSource::stamp(const StampContext& context, Stamps& stamps) const {
  InputSignal signal;
  signal.quantity = voltage_ ? InputSignal::Quantity::Voltage : InputSignal::Quantity::Current;
  signal.label = name();
  signal.element = element_index();
  signal.waveform = element_.waveform;
  const int k = stamps.input(std::move(signal));
  const int b = context.branch(0);
  stamps.relations.push_back(
      {b, {{voltage_ ? Term::Of::Voltage : Term::Of::Current, b, 1.0}, {Term::Of::Input, k, -1.0}}});
}

NgspiceCards IndependentSource::ngspice(const NgspiceDeckContext& context) const {
  std::string expression = modulated_expression(element_.waveform);
  NgspiceCards gate;
  if (!expression.empty() && element_.waveform.params.at(5) > 0) {  // 0 before TD
    const std::string node = context.fresh("lcs_" + name() + "_gate");
    gate.lines.push_back(context.fresh(deck_name('v', name() + "_gate")) + " " + node + " 0 " +
                         gate_pulse(element_.waveform.params[5], context.tstop));
    expression = "(" + expression + ")*v(" + node + ")";
  }
  if (!expression.empty()) {
    auto with_gate = [&](NgspiceCards cards) {
      cards.lines.insert(cards.lines.begin(), gate.lines.begin(), gate.lines.end());
      return cards;
    };
    if (!voltage_)
      return with_gate(two_terminal_cards(deck_name('b', name()), element_.nodes.at(0), element_.nodes.at(1),
                                          "I=" + expression, name(), context));
    NgspiceCards cards;  // a 0 V source in series is the ammeter
    const std::string deck = deck_name('v', name()), mid = context.fresh("lcs_" + name() + "_b");
    cards.lines.push_back(deck + " " + element_.nodes.at(0) + " " + mid + " DC 0");
    cards.lines.push_back(deck_name('b', name()) + " " + mid + " " + element_.nodes.at(1) + " V=" + expression);
    cards.probes["i(" + name() + ")"] = {deck + "#branch", ""};
    return with_gate(cards);
  }
  if (std::isfinite(element_.waveform.sine_end())) return stopped_sine_cards(context);
  const std::string wave = ngspice_waveform(element_.waveform, context.tstop);
  if (!voltage_)
    return two_terminal_cards(deck_name('i', name()), element_.nodes.at(0), element_.nodes.at(1),
                              wave, name(), context);
  NgspiceCards cards;  // a voltage source is its own ammeter
  const std::string deck = deck_name('v', name());
  cards.lines.push_back(deck + " " + element_.nodes.at(0) + " " + element_.nodes.at(1) + " " + wave);
  cards.probes["i(" + name() + ")"] = {deck + "#branch", ""};
  return cards;
}

}  // namespace lcs
