#include "solver/devices/diode.h"

#include <cmath>

namespace lcs {

double shockley_voltage(const DiodeModel& model, double current) {
  return model.n * kThermalVoltage * std::log1p(current / model.is) + model.rs * current;
}

ResolvedDiodeLaw resolve_diode_law(const DiodeModel& model, double ifit) {
  ResolvedDiodeLaw r;
  if (model.von || model.ron) {
    r.law.von = model.von.value_or(0.0);
    r.law.ron = model.ron.value_or(0.0);
    return r;
  }
  r.fitted = true;
  r.fit_i1 = ifit / 10;
  r.fit_i2 = ifit * 10;
  const double v1 = shockley_voltage(model, r.fit_i1), v2 = shockley_voltage(model, r.fit_i2);
  r.law.ron = (v2 - v1) / (r.fit_i2 - r.fit_i1);
  r.law.von = v1 - r.law.ron * r.fit_i1;
  return r;
}

SmoothDiodeLaw smooth_equivalent(const DiodeModel& card, const ResolvedDiodeLaw& law,
                                 double emission, double saturation_current) {
  if (law.fitted || card.has_is || card.has_n || card.has_rs) return {0.0, card.is, card.n, card.rs};
  return {law.law.von, saturation_current, emission, law.law.ron};
}

namespace {
const DiodeModel& model_of(const Element& element, const Netlist& netlist) {
  auto it = netlist.diode_models.find(element.model);
  if (it == netlist.diode_models.end())
    throw NetlistError(element.loc, "diode " + element.name + ": unknown model '" + element.model + "'");
  return it->second;
}

// The card of `area` diodes in parallel (the element's value: area times m; 0 when not set, 1):
// the saturation current times the area, the series and on-resistances divided by it, VON and N
// as they are.
DiodeModel parallel_card(DiodeModel card, double area) {
  if (!(area > 0) || area == 1.0) return card;
  card.is *= area;
  card.rs /= area;
  if (card.ron) *card.ron /= area;
  return card;
}
}  // namespace

Diode::Diode(const Element& element, const Netlist& netlist, const DeviceOptions& options)
    : Device(element), card_(parallel_card(model_of(element, netlist), element.value)), law_(resolve_diode_law(card_, options.ifit)) {}

std::vector<BranchDecl> Diode::branches() const {
  return {{name(), BranchClass::Diode, element_.nodes.at(0), element_.nodes.at(1)}};
}

void Diode::stamp(const StampContext& context, Stamps& stamps) const {
  PairLaw pair;
  pair.name = name();
  pair.element = element_index();
  pair.law = law_.law;
  pair.fitted = law_.fitted;
  pair.smooth = {card_.is, card_.n};
  stamps.pairs.push_back({context.branch(0), pair});
}

std::string ngspice_junction(const std::string& tag, const std::string& anode, const std::string& cathode,
                             const SmoothDiodeLaw& smooth, const NgspiceDeckContext& context,
                             NgspiceCards& cards) {
  const std::string mid = context.fresh("lcs_" + tag + "_mid");
  const std::string meter = context.fresh(Device::deck_name('v', "thr_" + tag));
  const std::string model = context.fresh("lcs_m_" + tag);
  cards.lines.push_back(meter + " " + anode + " " + mid + " DC " + Device::number(smooth.series_von));
  cards.models.push_back(".model " + model + " D(IS=" + Device::number(smooth.is) + " N=" +
                         Device::number(smooth.n) + " RS=" + Device::number(smooth.rs * context.ron_factor) + ")");
  if (context.open)
    cards.lines.push_back(Device::deck_name('r', "open_" + tag) + " " + mid + " " + cathode + " 1e15");
  else
    cards.lines.push_back(Device::deck_name('d', tag) + " " + mid + " " + cathode + " " + model);
  return meter;
}

NgspiceCards Diode::ngspice(const NgspiceDeckContext& context) const {
  NgspiceCards cards;
  std::string anode = element_.nodes.at(0), cathode = element_.nodes.at(1);
  if (context.reversed) std::swap(anode, cathode);
  const SmoothDiodeLaw smooth =
      smooth_equivalent(card_, law_, context.emission, context.saturation_current);
  const std::string meter = ngspice_junction(name(), anode, cathode, smooth, context, cards);
  cards.ideal_diode = !(law_.fitted || card_.has_is || card_.has_n || card_.has_rs);
  cards.probes["i(" + name() + ")"] = {meter + "#branch", ""};
  return cards;
}

std::vector<std::string> Diode::notes() const {
  std::vector<std::string> out;
  for (const std::string& p : card_.ignored)
    out.push_back("diode " + name() + ": model parameter " + p + " is ignored by the ideal model");
  return out;
}

}  // namespace lcs
