#include "ngspice/deck_translation.h"

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
  if (w.kind == Waveform::Kind::Pulse) {
    // lcspice: a zero rise/fall time is a jump; ngspice would replace it by TSTEP.
    for (size_t k : {3u, 4u})
      if (k < w.params.size() && w.params[k] == 0.0) w.params[k] = 1e-9 * tstop;
  }
  return w.describe();
}

}  // namespace

std::string ngspice_node_vector(const std::string& node) { return node; }

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
  for (const Probe& p : probes)
    if (p.kind == Probe::Kind::NodeVoltage && p.a == "0") deck.probes[p.name()] = {"", ""};

  std::map<std::string, const PairInfo*> pair_of;
  for (const PairInfo& p : model.pairs()) pair_of[netlist.elements[p.element].name] = &p;

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
      const std::string mid = "lcs_" + el.name + "_mid";
      const std::string meter = deck_name('v', "thr_" + el.name);
      const std::string mname = "lcs_m_" + el.name;
      ResolvedDiodeLaw law;
      law.law = pair.law;
      law.fitted = pair.fitted;
      const SmoothDiodeLaw smooth =
          smooth_equivalent(card, law, options.emission, options.saturation_current);
      deck.lines.push_back(meter + " " + anode + " " + mid + " DC " + num(smooth.series_von));
      models.push_back(".model " + mname + " D(IS=" + num(smooth.is) + " N=" + num(smooth.n) +
                       " RS=" + num(smooth.rs) + ")");
      if (!pair.fitted) deck.ideal_diodes.push_back(el.name);
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
      const std::string meter = deck_name('v', "amm_" + el.name);
      const std::string mid = "lcs_" + el.name + "_amm";
      deck.lines.push_back(meter + " " + a + " " + mid + " DC 0");
      deck.probes["i(" + el.name + ")"] = {meter + "#branch", ""};
      a = mid;
    }
    std::string line = name + " " + a + " " + b + " ";
    switch (el.kind) {
      case ElementKind::CurrentSource: line += waveform_text(el.waveform, tran.tstop); break;
      default:
        line += num(el.value);
        if (el.ic) line += " IC=" + num(*el.ic);
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
  double tmax = options.max_step > 0 ? options.max_step : tran.tstep;
  if (tran.tmax > 0 && tran.tmax < tmax) tmax = tran.tmax;
  deck.lines.push_back(".tran " + num(tran.tstep) + " " + num(tran.tstop) + " " + num(tran.tstart) +
                       " " + num(tmax) + (tran.uic ? " uic" : ""));
  if (!options.options.empty()) {
    std::string o = ".options";
    for (const std::string& w : options.options) o += " " + w;
    deck.lines.push_back(o);
  }
  deck.lines.push_back(".end");
  return deck;
}

}  // namespace lcs
