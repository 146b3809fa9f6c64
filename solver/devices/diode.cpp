#include "solver/devices/diode.h"

#include <cmath>
#include <cstdio>

namespace lcs {

double shockley_voltage(const DiodeModel& model, double current) {
  return model.n * kThermalVoltage * std::log1p(current / model.is) + model.rs * current;
}

namespace {

ResolvedDiodeLaw fitted_law(const JunctionCurve& curve, double ifit, const CurrentRange& range) {
  const LineFit f = range.empty() ? chord_fit(curve, ifit / 10, ifit * 10)
                                  : minimax_fit(curve, range.lo, range.hi);
  ResolvedDiodeLaw r;
  r.law = f.law;
  r.fitted = true;
  r.circuit_fit = !range.empty();
  r.fit_i1 = f.i1;
  r.fit_i2 = f.i2;
  r.fit_error = f.max_error;
  r.fit_error_fraction = f.error_fraction;
  return r;
}

}  // namespace

ResolvedDiodeLaw resolve_diode_law(const DiodeModel& model, double ifit, const CurrentRange& range) {
  if (model.von || model.ron) {
    ResolvedDiodeLaw r;
    r.law.von = model.von.value_or(0.0);
    r.law.ron = model.ron.value_or(0.0);
    return r;
  }
  return fitted_law(forward_curve(model.is, model.n, model.rs), ifit, range);
}

ResolvedDiodeLaw resolve_breakdown_law(const DiodeModel& model, double ifit, const CurrentRange& range) {
  if (model.von || model.ron || model.rrev) {
    ResolvedDiodeLaw r;
    r.law.von = *model.bv;
    r.law.ron = model.rrev.value_or(model.ron.value_or(0.0));
    return r;
  }
  return fitted_law(breakdown_curve(*model.bv, model.ibv, model.nbv.value_or(model.n), model.rs), ifit, range);
}

SmoothDiodeLaw smooth_equivalent(const DiodeModel& card, const ResolvedDiodeLaw& law,
                                 double emission, double saturation_current) {
  if (law.fitted || card.has_is || card.has_n || card.has_rs)
    return {0.0, card.is, card.n, card.rs, card.bv, card.ibv, card.nbv};
  SmoothDiodeLaw s{law.law.von, saturation_current, emission, law.law.ron, card.bv, card.ibv, std::nullopt};
  if (card.bv) s.ibv = saturation_current * (*card.bv + law.law.von) / kThermalVoltage;
  return s;
}

namespace {
const DiodeModel& model_of(const Element& element, const Netlist& netlist) {
  auto it = netlist.diode_models.find(element.model);
  if (it == netlist.diode_models.end())
    throw NetlistError(element.loc, "diode " + element.name + ": unknown model '" + element.model + "'");
  return it->second;
}

// The card of `area` diodes in parallel (the element's value: area times m; 0 when not set, 1):
// the saturation and breakdown currents times the area, the series, on- and breakdown
// resistances divided by it, VON, N and BV as they are.
DiodeModel parallel_card(DiodeModel card, double area) {
  if (!(area > 0) || area == 1.0) return card;
  card.is *= area;
  card.ibv *= area;
  if (card.cjo) *card.cjo *= area;
  card.rs /= area;
  if (card.ron) *card.ron /= area;
  if (card.rrev) *card.rrev /= area;
  return card;
}

}  // namespace

CurrentRange junction_range(const DeviceOptions& options, const std::string& key, bool breakdown) {
  const auto it = options.diode_ranges.find(key);
  if (it == options.diode_ranges.end()) return {};
  return breakdown ? it->second.reverse : it->second.forward;
}

Diode::Diode(const Element& element, const Netlist& netlist, const DeviceOptions& options)
    : Device(element),
      card_(parallel_card(model_of(element, netlist), element.value)),
      law_(resolve_diode_law(card_, options.ifit, junction_range(options, element.name, false))) {
  if (card_.bv) breakdown_ = resolve_breakdown_law(card_, options.ifit, junction_range(options, element.name, true));
  if (options.diodecap) capacitance_ = card_.cjo.value_or(0.0);
}

std::vector<BranchDecl> Diode::branches() const {
  const std::string &anode = element_.nodes.at(0), &cathode = element_.nodes.at(1);
  std::vector<BranchDecl> out{{name(), BranchClass::Diode, anode, cathode}};
  if (breakdown_) out.push_back({name() + ":bv", BranchClass::Diode, cathode, anode});
  if (capacitance() > 0) out.push_back({name() + ":cj", BranchClass::Capacitor, anode, cathode});
  return out;
}

// i(d) is the forward minus the breakdown current, plus the junction capacitance's (part of the
// device, as in ngspice's diode).
std::vector<std::pair<int, double>> Diode::element_current() const {
  if (!breakdown_ && !(capacitance() > 0)) return {};
  std::vector<std::pair<int, double>> out{{0, 1.0}};
  if (breakdown_) out.push_back({1, -1.0});
  if (capacitance() > 0) out.push_back({breakdown_ ? 2 : 1, 1.0});
  return out;
}

PairLaw junction_pair_law(const std::string& name, int element, const ResolvedDiodeLaw& law, SmoothJunction smooth) {
  PairLaw pair;
  pair.name = name;
  pair.element = element;
  pair.law = law.law;
  pair.fitted = law.fitted;
  pair.circuit_fit = law.circuit_fit;
  pair.fit_i1 = law.fit_i1;
  pair.fit_i2 = law.fit_i2;
  pair.fit_error = law.fit_error;
  pair.fit_error_fraction = law.fit_error_fraction;
  pair.smooth = smooth;
  return pair;
}

// i(d) is the forward minus the breakdown current; the two never conduct together.
std::vector<FittedJunction> Diode::fitted_junctions() const {
  std::vector<FittedJunction> out;
  if (law_.fitted) out.push_back({name(), false, name(), 1.0, card_, law_.law});
  if (breakdown_ && breakdown_->fitted) out.push_back({name(), true, name(), -1.0, card_, breakdown_->law});
  return out;
}

void Diode::stamp(const StampContext& context, Stamps& stamps) const {
  stamps.pairs.push_back({context.branch(0), junction_pair_law(name(), element_index(), law_, {card_.is, card_.n})});
  // The smooth method's breakdown junction: I = IBV (exp((v_r - BV) / (N Vt)) - 1) over the
  // reverse voltage v_r beyond the law's threshold BV, ngspice's breakdown branch (to IBV).
  if (breakdown_)
    stamps.pairs.push_back({context.branch(1), junction_pair_law(name() + ":bv", element_index(), *breakdown_,
                                                        {card_.ibv, card_.nbv.value_or(card_.n)})});
  if (capacitance() > 0) stamps.storage.push_back({context.branch(breakdown_ ? 2 : 1), capacitance(), std::nullopt});
}

std::string ngspice_junction(const std::string& tag, const std::string& anode, const std::string& cathode,
                             const SmoothDiodeLaw& smooth, const NgspiceDeckContext& context,
                             NgspiceCards& cards) {
  const std::string mid = context.fresh("lcs_" + tag + "_mid");
  const std::string meter = context.fresh(Device::deck_name('v', "thr_" + tag));
  const std::string model = context.fresh("lcs_m_" + tag);
  cards.lines.push_back(meter + " " + anode + " " + mid + " DC " + Device::number(smooth.series_von));
  // ngspice's BV is the junction's, behind the threshold source: the branch breaks down at -bv.
  const std::string breakdown = smooth.bv ? " BV=" + Device::number(*smooth.bv + smooth.series_von) +
                                                " IBV=" + Device::number(smooth.ibv) +
                                                (smooth.nbv ? " NBV=" + Device::number(*smooth.nbv) : "")
                                          : "";
  cards.models.push_back(".model " + model + " D(IS=" + Device::number(smooth.is) + " N=" +
                         Device::number(smooth.n) + " RS=" + Device::number(smooth.rs * context.ron_factor) +
                         breakdown + ")");
  if (context.open)
    cards.lines.push_back(Device::deck_name('r', "open_" + tag) + " " + mid + " " + cathode + " 1e15");
  else
    cards.lines.push_back(Device::deck_name('d', tag) + " " + mid + " " + cathode + " " + model);
  return meter;
}

// The junction capacitance is a capacitor of CJO across the junction, behind a 0 V ammeter that
// also carries the junction's current: i(d) is the device's, as lcspice's.
NgspiceCards Diode::ngspice(const NgspiceDeckContext& context) const {
  NgspiceCards cards;
  std::string anode = element_.nodes.at(0), cathode = element_.nodes.at(1);
  if (context.reversed) std::swap(anode, cathode);
  const SmoothDiodeLaw smooth =
      smooth_equivalent(card_, law_, context.emission, context.saturation_current);
  std::string ammeter;
  if (capacitance() > 0) {
    ammeter = context.fresh(deck_name('v', "amm_" + name()));
    const std::string inner = context.fresh("lcs_" + name() + "_a");
    cards.lines.push_back(ammeter + " " + anode + " " + inner + " DC 0");
    anode = inner;
    auto ic = context.branch_initial.find(name() + ":cj");
    cards.lines.push_back(context.fresh(deck_name('c', name() + "_cj")) + " " + anode + " " + cathode + " " +
                          number(capacitance()) +
                          (ic != context.branch_initial.end() ? " IC=" + number(ic->second) : ""));
  }
  const std::string meter = ngspice_junction(name(), anode, cathode, smooth, context, cards);
  cards.ideal_diode = !(law_.fitted || card_.has_is || card_.has_n || card_.has_rs);
  cards.probes["i(" + name() + ")"] = {(ammeter.empty() ? meter : ammeter) + "#branch", ""};
  return cards;
}

std::vector<std::string> Diode::notes() const {
  std::vector<std::string> out;
  if (capacitance() > 0) {
    char buf[200];
    std::snprintf(buf, sizeof buf, "diode %s: junction capacitance %.6g F (CJO at zero bias, .options diodecap)", name().c_str(),
                  capacitance());
    out.push_back(buf);
  }
  for (const std::string& p : card_.ignored)
    out.push_back("diode " + name() + ": model parameter " + p + " is ignored by the ideal model");
  return out;
}

}  // namespace lcs
