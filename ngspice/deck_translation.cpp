#include "ngspice/deck_translation.h"

#include <algorithm>
#include <cstdio>
#include <stdexcept>

#include "solver/model/diode_law.h"

namespace lcs {

namespace {

std::string num(double x) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.12g", x);
  return buf;
}

// ngspice takes the element type from the first letter of the name.
std::string deck_name(char letter, const std::string& name) {
  if (!name.empty() && name[0] == letter && name.find('.') == std::string::npos) return name;
  return std::string(1, letter) + "_" + name;
}

char letter_of(ElementKind kind) {
  switch (kind) {
    case ElementKind::Resistor: return 'r';
    case ElementKind::Inductor: return 'l';
    case ElementKind::Capacitor: return 'c';
    case ElementKind::Coupling: return 'k';
    case ElementKind::VoltageSource: return 'v';
    case ElementKind::CurrentSource: return 'i';
    case ElementKind::Diode: return 'd';
  }
  return 'x';
}

std::string waveform_text(Waveform w, double tstop) {
  if (w.kind == Waveform::Kind::Pulse && w.params.size() >= 7) {
    // lcspice: a zero rise/fall time is a jump, and at the instant itself the value after it.
    // ngspice would replace a zero by TSTEP: give it a tiny edge that ends at the jump.
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

// Names made up by the translation, kept clear of the netlist's own element and node names.
class NameBook {
 public:
  explicit NameBook(const Netlist& n) {
    for (const Element& el : n.elements) {
      used_.insert(el.name);
      for (const std::string& node : el.nodes) used_.insert(node);
    }
  }
  std::string fresh(const std::string& wanted) {
    std::string name = wanted;
    for (int k = 2; used_.count(name); ++k) name = wanted + "_" + std::to_string(k);
    used_.insert(name);
    return name;
  }

 private:
  std::set<std::string> used_;
};

}  // namespace

std::string ngspice_node_vector(const std::string& node) { return node == "0" ? "" : node; }

TranslatedDeck translate_to_ngspice(const CircuitModel& model, const std::vector<Probe>& probes,
                                    const TranslationOptions& options) {
  const Netlist& netlist = model.netlist();
  if (!netlist.tran) throw std::invalid_argument("the netlist has no .tran card");
  const TranSpec& tran = *netlist.tran;
  TranslatedDeck deck;
  deck.lines.push_back(netlist.title.empty() ? "lcspice deck" : netlist.title);
  deck.lines.push_back("* translated by lcspice validate: ideal diodes as VON source + Shockley diode");

  std::set<std::string> current_probes;
  for (const Probe& p : probes) {
    if (p.kind == Probe::Kind::ElementCurrent) current_probes.insert(p.a);
    else deck.probes[p.name()] = {ngspice_node_vector(p.a),
                                  p.kind == Probe::Kind::NodePairVoltage ? ngspice_node_vector(p.b) : ""};
  }

  std::map<std::string, const PairInfo*> pair_of;
  for (const PairInfo& p : model.pairs()) pair_of[netlist.elements[p.element].name] = &p;

  NameBook names(netlist);
  const bool uic = tran.uic || !options.initial_conditions.empty();
  std::vector<std::string> models;
  for (const Element& el : netlist.elements) {
    if (el.kind == ElementKind::Coupling) continue;
    const std::string name = deck_name(letter_of(el.kind), el.name);
    std::string a = el.nodes.at(0);
    const std::string b = el.nodes.at(1);
    const bool probed = current_probes.count(el.name) > 0;

    if (el.kind == ElementKind::Diode) {
      const PairInfo& pair = *pair_of.at(el.name);
      const DiodeModel& card = netlist.diode_models.at(el.model);
      std::string anode = a, cathode = b;
      if (options.reversed_diodes.count(el.name)) std::swap(anode, cathode);
      const std::string mid = names.fresh("lcs_" + el.name + "_mid");
      const std::string meter = names.fresh(deck_name('v', "thr_" + el.name));
      const std::string mname = names.fresh("lcs_m_" + el.name);
      ResolvedDiodeLaw law;
      law.law = pair.law;
      law.fitted = pair.fitted;
      const SmoothDiodeLaw smooth =
          smooth_equivalent(card, law, options.emission, options.saturation_current);
      deck.lines.push_back(meter + " " + anode + " " + mid + " DC " + num(smooth.series_von));
      models.push_back(".model " + mname + " D(IS=" + num(smooth.is) + " N=" + num(smooth.n) +
                       " RS=" + num(smooth.rs) + ")");
      if (!(pair.fitted || card.has_is || card.has_n || card.has_rs)) deck.ideal_diodes.push_back(el.name);
      deck.lines.push_back(name + " " + mid + " " + cathode + " " + mname);
      deck.probes["i(" + el.name + ")"] = {meter + "#branch", ""};
      continue;
    }
    if (el.kind == ElementKind::VoltageSource) {
      deck.lines.push_back(name + " " + a + " " + b + " " + waveform_text(el.waveform, tran.tstop));
      deck.probes["i(" + el.name + ")"] = {name + "#branch", ""};
      continue;
    }
    if (probed) {  // 0 V ammeter between n+ and the element
      const std::string meter = names.fresh(deck_name('v', "amm_" + el.name));
      const std::string mid = names.fresh("lcs_" + el.name + "_amm");
      deck.lines.push_back(meter + " " + a + " " + mid + " DC 0");
      deck.probes["i(" + el.name + ")"] = {meter + "#branch", ""};
      a = mid;
    }
    std::string line = name + " " + a + " " + b + " ";
    switch (el.kind) {
      case ElementKind::CurrentSource: line += waveform_text(el.waveform, tran.tstop); break;
      default: {
        line += num(el.value);
        auto given = options.initial_conditions.find(el.name);
        if (given != options.initial_conditions.end()) line += " IC=" + num(given->second);
        else if (el.ic) line += " IC=" + num(*el.ic);
      }
    }
    deck.lines.push_back(line);
  }
  for (const Element& el : netlist.elements)
    if (el.kind == ElementKind::Coupling)
      deck.lines.push_back(deck_name('k', el.name) + " " + deck_name('l', el.coupled.at(0)) + " " +
                           deck_name('l', el.coupled.at(1)) + " " + num(el.value));
  for (const std::string& m : models) deck.lines.push_back(m);

  if (!netlist.node_ics.empty()) {
    std::string ic = ".ic";
    for (const NodeIc& n : netlist.node_ics) ic += " v(" + n.node + ")=" + num(n.value);
    deck.lines.push_back(ic);
  }
  double tmax = tran.tmax > 0 && tran.tmax < tran.tstep ? tran.tmax : tran.tstep;
  if (options.max_step > 0) tmax = options.max_step;  // asked for explicitly: it wins
  deck.lines.push_back(".tran " + num(tran.tstep) + " " + num(tran.tstop) + " " + num(tran.tstart) +
                       " " + num(tmax) + (uic ? " uic" : ""));
  if (!options.options.empty()) {
    std::string o = ".options";
    for (const std::string& w : options.options) o += " " + w;
    deck.lines.push_back(o);
  }
  deck.lines.push_back(".end");
  return deck;
}

}  // namespace lcs
