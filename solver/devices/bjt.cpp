#include "solver/devices/bjt.h"

#include <tuple>

namespace lcs {

namespace {

const BjtModel& model_of(const Element& element, const Netlist& netlist) {
  auto it = netlist.bjt_models.find(element.model);
  if (it == netlist.bjt_models.end())
    throw NetlistError(element.loc, "transistor " + element.name + ": unknown model '" + element.model + "'");
  return it->second;
}

double alpha(double beta) { return beta / (1 + beta); }

}  // namespace

DiodeModel junction_card(const BjtModel& model, Junction junction, double area) {
  const bool e = junction == Junction::BaseEmitter;
  DiodeModel d;
  d.name = model.name + (e ? ":be" : ":bc");
  d.loc = model.loc;
  d.von = e ? (model.vone ? model.vone : model.von) : (model.vonc ? model.vonc : model.von);
  d.ron = e ? (model.rone ? model.rone : model.ron) : (model.ronc ? model.ronc : model.ron);
  if (d.ron) *d.ron /= area;
  // BR = 0 (no reverse transfer) keeps I_CS = IS rather than an infinite one.
  const double a = e ? alpha(model.bf) : alpha(model.br);
  d.is = model.is * area / (a > 0 ? a : 1.0);
  d.n = e ? model.nf : model.nr;
  d.has_is = model.has_is;
  d.has_n = e ? model.has_nf : model.has_nr;
  return d;
}

Bjt::Bjt(const Element& element, const Netlist& netlist, const DeviceOptions& options)
    : Device(element), card_(model_of(element, netlist)), area_(element.value > 0 ? element.value : 1.0) {
  cbe_ = options.bjtcap ? *options.bjtcap : card_.cje ? *card_.cje * area_ : 0.0;
  cbc_ = card_.cjc ? *card_.cjc * area_ : 0.0;
  alpha_f_ = alpha(card_.bf);
  alpha_r_ = alpha(card_.br);
  card_e_ = junction_card(card_, Junction::BaseEmitter, area_);
  card_c_ = junction_card(card_, Junction::BaseCollector, area_);
  law_e_ = resolve_diode_law(card_e_, options.ifit, junction_range(options, name() + ":be", false));
  law_c_ = resolve_diode_law(card_c_, options.ifit, junction_range(options, name() + ":bc", false));
  if (card_.smooth) {  // the smooth method: Shockley junctions (smooth_netlist)
    for (auto [card, law] : {std::pair{&card_e_, &law_e_}, std::pair{&card_c_, &law_c_}}) {
      const SmoothDiodeLaw s = smooth_equivalent(*card, *law, card_.smooth->emission,
                                                 card_.smooth->saturation_current);
      law->law = {s.series_von, s.rs};
      law->fitted = false;
      card->is = s.is;
      card->n = s.n;
    }
  }
}

const std::string& Bjt::node(char terminal) const {
  return element_.nodes.at(terminal == 'c' ? 0 : terminal == 'b' ? 1 : 2);
}

Bjt::Layout Bjt::layout() const {
  Layout l;
  int next = 0;
  const bool e_open = node('b') == node('e'), c_open = node('b') == node('c');
  if (!e_open) l.de = next++;
  if (!c_open) l.dc = next++;
  if (!e_open && !c_open) {
    l.f = next++;
    l.r = next++;
  }
  if (!e_open && cbe_ > 0) l.cbe = next++;
  if (!c_open && cbc_ > 0) l.cbc = next++;
  return l;
}

std::vector<BranchDecl> Bjt::branches() const {
  const Layout l = layout();
  const std::string &c = node('c'), &b = node('b'), &e = node('e');
  const bool n = !card_.pnp;
  std::vector<BranchDecl> out;
  if (l.de >= 0) out.push_back({name() + ":be", BranchClass::Diode, n ? b : e, n ? e : b});
  if (l.dc >= 0) out.push_back({name() + ":bc", BranchClass::Diode, n ? b : c, n ? c : b});
  if (l.f >= 0) out.push_back({name() + ":f", BranchClass::CurrentSource, n ? c : b, n ? b : c});
  if (l.r >= 0) out.push_back({name() + ":r", BranchClass::CurrentSource, n ? e : b, n ? b : e});
  if (l.cbe >= 0) out.push_back({name() + ":cbe", BranchClass::Capacitor, n ? b : e, n ? e : b});
  if (l.cbc >= 0) out.push_back({name() + ":cbc", BranchClass::Capacitor, n ? b : c, n ? c : b});
  return out;
}

void Bjt::stamp(const StampContext& context, Stamps& stamps) const {
  const Layout l = layout();
  auto pair = [&](int local, const char* junction, const DiodeModel& card, const ResolvedDiodeLaw& law) {
    if (local < 0) return;
    PairLaw p = junction_pair_law(name() + ":" + junction, element_index(), law, {card.is, card.n});
    p.transfer = true;
    stamps.pairs.push_back({context.branch(local), p});
  };
  pair(l.de, "be", card_e_, law_e_);
  pair(l.dc, "bc", card_c_, law_c_);
  if (l.cbe >= 0) stamps.storage.push_back({context.branch(l.cbe), cbe_, std::nullopt});
  if (l.cbc >= 0) stamps.storage.push_back({context.branch(l.cbc), cbc_, std::nullopt});
  // i_F - alpha_F i_DE = 0 and i_R - alpha_R i_DC = 0 (both present or both left out).
  if (l.f >= 0) {
    stamps.relations.push_back({context.branch(l.f), {{Term::Of::Current, context.branch(l.f), 1.0},
                                                      {Term::Of::Current, context.branch(l.de), -alpha_f_}}});
    stamps.relations.push_back({context.branch(l.r), {{Term::Of::Current, context.branch(l.r), 1.0},
                                                      {Term::Of::Current, context.branch(l.dc), -alpha_r_}}});
  }
}

// Into the terminal, NPN: i_C = aF i_DE - i_DC - i_CBC, i_B = (1 - aF) i_DE + (1 - aR) i_DC +
// i_CBE + i_CBC, i_E = aR i_DC - i_DE - i_CBE (the capacitances are part of the device: their
// currents enter at the base and leave at the emitter and the collector, as in ngspice's BJT);
// PNP: the negatives. A left-out junction carries nothing.
std::vector<std::pair<int, double>> Bjt::terminal_current(char terminal) const {
  const Layout l = layout();
  const double s = card_.pnp ? -1.0 : 1.0;
  double de = 0, dc = 0, cbe = 0, cbc = 0;
  switch (terminal) {
    case 'c': de = alpha_f_, dc = -1, cbc = -1; break;
    case 'b': de = 1 - alpha_f_, dc = 1 - alpha_r_, cbe = 1, cbc = 1; break;
    case 'e': de = -1, dc = alpha_r_, cbe = -1; break;
    default: return {};
  }
  std::vector<std::pair<int, double>> out;
  if (l.de >= 0 && de != 0) out.push_back({l.de, s * de});
  if (l.dc >= 0 && dc != 0) out.push_back({l.dc, s * dc});
  if (l.cbe >= 0 && cbe != 0) out.push_back({l.cbe, s * cbe});
  if (l.cbc >= 0 && cbc != 0) out.push_back({l.cbc, s * cbc});
  return out;
}

// Each terminal through a 0 V ammeter (its current is ic/ib/ie), each junction as a threshold
// source plus a sharp Shockley diode (ngspice_junction), the transfer currents as F sources
// controlled by the junctions' threshold sources. A card whose junctions are fitted (a vendor
// Gummel–Poon card) runs ngspice's own BJT reduced to Ebers–Moll: IS, BF, BR, NF, NR.
NgspiceCards Bjt::ngspice(const NgspiceDeckContext& context) const {
  NgspiceCards cards;
  std::map<char, std::string> inner;
  for (char t : {'c', 'b', 'e'}) {
    const std::string meter = context.fresh(deck_name('v', "i" + std::string(1, t) + "_" + name()));
    inner[t] = context.fresh("lcs_" + name() + "_" + t);
    cards.lines.push_back(meter + " " + node(t) + " " + inner[t] + " DC 0");
    cards.probes[std::string("i") + t + "(" + name() + ")"] = {meter + "#branch", ""};
  }
  const bool n = !card_.pnp;
  const Layout l = layout();
  auto capacitance = [&](const char* tag, char other, double c) {
    auto ic = context.branch_initial.find(name() + ":c" + tag);
    cards.lines.push_back(deck_name('c', name() + "_" + tag) + " " + inner[n ? 'b' : other] + " " +
                          inner[n ? other : 'b'] + " " + number(c) +
                          (ic != context.branch_initial.end() ? " IC=" + number(ic->second) : ""));
  };
  if (l.cbe >= 0) capacitance("be", 'e', cbe_);
  if (l.cbc >= 0) capacitance("bc", 'c', cbc_);
  const bool gummel_poon = law_e_.fitted && law_c_.fitted;
  if (gummel_poon) {
    const std::string model = context.fresh("lcs_m_" + name());
    std::string c = inner['c'], e = inner['e'];
    if (context.reversed) std::swap(c, e);
    cards.lines.push_back(deck_name('q', name()) + " " + c + " " + inner['b'] + " " + e + " " + model +
                          " " + number(area_) + (element_.initially_on.value_or(true) ? "" : " OFF"));
    cards.models.push_back(".model " + model + (n ? " NPN" : " PNP") + "(IS=" + number(card_.is) +
                           " BF=" + number(card_.bf) + " BR=" + number(card_.br) + " NF=" +
                           number(card_.nf) + " NR=" + number(card_.nr) + ")");
    cards.witness = name() + ": ngspice's BJT with the card reduced to Ebers-Moll (IS, BF, BR, NF, NR)";
    return cards;
  }
  // Test hook: written backwards, collector and emitter swapped.
  const std::string c = context.reversed ? inner['e'] : inner['c'];
  const std::string e = context.reversed ? inner['c'] : inner['e'];
  const std::string& b = inner['b'];
  std::string meter_e, meter_c;
  auto junction = [&](const char* tag, const std::string& other, const DiodeModel& card,
                      const ResolvedDiodeLaw& law) {
    const SmoothDiodeLaw s = smooth_equivalent(card, law, context.emission, context.saturation_current);
    return ngspice_junction(name() + "_" + tag, n ? b : other, n ? other : b, s, context, cards);
  };
  if (l.de >= 0) meter_e = junction("be", e, card_e_, law_e_);
  if (l.dc >= 0) meter_c = junction("bc", c, card_c_, law_c_);
  // Each transfer source wherever its junction is: in the model a transfer between two terminals
  // on one node is a self-loop and left out (layout()), but here the terminals are apart behind
  // their meters, and a diode-connected transistor's collector current is alphaF * i_DE.
  if (l.de >= 0)
    cards.lines.push_back(deck_name('f', name() + "_f") + " " + (n ? c : b) + " " + (n ? b : c) + " " +
                          meter_e + " " + number(alpha_f_));
  if (l.dc >= 0)
    cards.lines.push_back(deck_name('f', name() + "_r") + " " + (n ? e : b) + " " + (n ? b : e) + " " +
                          meter_c + " " + number(alpha_r_));
  cards.ideal_diode = !(law_e_.fitted || law_c_.fitted || card_.has_is || card_.has_nf || card_.has_nr);
  cards.witness = name() + ": Ebers-Moll of threshold sources, Shockley junctions and F sources";
  return cards;
}

// The junctions' branches carry exactly the junction currents i_DE, i_DC (the transfer sources
// and the capacitances are branches of their own).
std::vector<FittedJunction> Bjt::fitted_junctions() const {
  const Layout l = layout();
  std::vector<FittedJunction> out;
  if (l.de >= 0 && law_e_.fitted) out.push_back({name() + ":be", false, name() + ":be", 1.0, card_e_, law_e_.law});
  if (l.dc >= 0 && law_c_.fitted) out.push_back({name() + ":bc", false, name() + ":bc", 1.0, card_c_, law_c_.law});
  return out;
}

std::vector<std::string> Bjt::notes() const {
  std::vector<std::string> out;
  char buf[320];
  std::snprintf(buf, sizeof buf, "transistor %s: %s, alphaF = %.6g, alphaR = %.6g", name().c_str(),
                card_.pnp ? "PNP" : "NPN", alpha_f_, alpha_r_);
  out.push_back(buf);
  // A junction whose terminals share a node carries nothing: it and its capacitance are left
  // out of the model (layout()), and so out of these notes.
  const Layout l = layout();
  for (auto [tag, law, present] : {std::tuple{"B-E", &law_e_, l.de >= 0}, std::tuple{"B-C", &law_c_, l.dc >= 0}}) {
    if (!present) {
      std::snprintf(buf, sizeof buf, "transistor %s: %s junction left out (its terminals are one node, %s)",
                    name().c_str(), tag, node('b').c_str());
      out.push_back(buf);
      continue;
    }
    if (!law->fitted) continue;
    std::snprintf(buf, sizeof buf,
                  "transistor %s: %s junction fitted to its Shockley curve between %.9g A and %.9g A (%s): "
                  "VON = %.9g V, RON = %.9g ohm",
                  name().c_str(), tag, law->fit_i1, law->fit_i2,
                  law->circuit_fit ? "the currents it carries here" : ".options ifit", law->law.von, law->law.ron);
    out.push_back(buf);
  }
  for (const std::string& p : card_.ignored)
    out.push_back("transistor " + name() + ": model parameter " + p + " is ignored by the ideal model");
  if (l.cbe >= 0) {
    std::snprintf(buf, sizeof buf, "transistor %s: base-emitter capacitance %.6g F (%s)", name().c_str(),
                  cbe_, card_.cje && cbe_ == *card_.cje * area_ ? "CJE" : ".options bjtcap");
    out.push_back(buf);
  }
  if (l.cbc >= 0) {
    std::snprintf(buf, sizeof buf, "transistor %s: base-collector capacitance %.6g F (CJC)", name().c_str(), cbc_);
    out.push_back(buf);
  }
  return out;
}

}  // namespace lcs
