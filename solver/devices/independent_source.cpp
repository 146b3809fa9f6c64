#include "solver/devices/independent_source.h"

#include <algorithm>

#include "solver/devices/two_terminal_cards.h"

namespace lcs {

namespace {

// The waveform as ngspice reads it. lcspice: a zero PULSE rise/fall time is a jump, and at the
// instant itself the value after it; ngspice would replace a zero by TSTEP, so the edge becomes
// one of 1e-6 TSTOP that ends at the jump (shorter ones are lost to its breakpoint resolution).
std::string ngspice_waveform(Waveform w, double tstop) {
  if (w.kind == Waveform::Kind::Pulse && w.params.size() >= 7) {
    const double eps = 1e-6 * tstop;
    double& td = w.params[2];
    double& tr = w.params[3];
    double& tf = w.params[4];
    double& pw = w.params[5];
    if (tr == 0.0) td -= eps, tr = eps;
    if (tf == 0.0) pw = std::max(0.0, pw - eps), tf = eps;
  }
  return w.describe();
}

}  // namespace

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
