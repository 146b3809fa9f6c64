#include "ngspice/deck_translation.h"

#include <algorithm>
#include <cstdio>
#include <stdexcept>

#include "solver/devices/device.h"

namespace lcs {

namespace {

std::string num(double x) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.12g", x);
  return buf;
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

// KiCad's net names, `net-(r1-pad1)` (lexer.cpp reads them as one name): ngspice 39 ends a name
// at ')' and refuses a D card with one ("could not find a valid modelname"), so the deck names
// such a node with its parentheses spelled out.
std::string ngspice_node_name(const std::string& node) {
  if (node.find_first_of("()") == std::string::npos) return node;
  std::string out;
  for (char c : node) out += c == '(' ? "_lp_" : c == ')' ? "_rp_" : std::string(1, c);
  return out;
}

std::string ngspice_node_vector(const std::string& node) { return node == "0" ? "" : ngspice_node_name(node); }

namespace {

// The devices write their nodes' own names into their cards: those ngspice cannot read are
// renamed there, as whole blank-separated words.
void rename_nodes_in_cards(const Netlist& netlist, std::vector<std::string>& lines) {
  std::set<std::string> renamed;
  for (const Element& e : netlist.elements)
    for (const std::string& n : e.nodes)
      if (ngspice_node_name(n) != n) renamed.insert(n);
  if (renamed.empty()) return;
  for (std::string& line : lines) {
    if (line.find('(') == std::string::npos) continue;
    std::string out;
    std::size_t i = 0;
    while (i < line.size()) {
      const std::size_t blank = line.find(' ', i);
      const std::size_t end = blank == std::string::npos ? line.size() : blank;
      const std::string word = line.substr(i, end - i);
      out += renamed.count(word) ? ngspice_node_name(word) : word;
      if (blank == std::string::npos) break;
      out += ' ';
      i = blank + 1;
    }
    line = out;
  }
}

}  // namespace

TranslatedDeck translate_to_ngspice(const CircuitModel& model, const std::vector<Probe>& probes,
                                    const TranslationOptions& options) {
  return translate_to_ngspice(model.netlist(), model.devices(), probes, options);
}

TranslatedDeck translate_to_ngspice(const Netlist& netlist, const std::vector<std::shared_ptr<Device>>& devices,
                                    const std::vector<Probe>& probes, const TranslationOptions& options) {
  if (!netlist.tran) throw std::invalid_argument("the netlist has no .tran card");
  const TranSpec& tran = *netlist.tran;
  TranslatedDeck deck;
  deck.lines.push_back(netlist.title.empty() ? "lcspice deck" : netlist.title);
  deck.lines.push_back("* translated by lcspice validate: ideal diodes as VON source + Shockley diode");

  std::set<std::string> current_probes;
  for (const Probe& p : probes) {
    if (p.kind == Probe::Kind::ElementCurrent) current_probes.insert(p.a);
    else if (p.kind != Probe::Kind::TerminalCurrent) deck.probes[p.name()] = {ngspice_node_vector(p.a),
                                  p.kind == Probe::Kind::NodePairVoltage ? ngspice_node_vector(p.b) : ""};
  }

  NameBook names(netlist);
  const bool uic = tran.uic || !options.initial_conditions.empty() || !options.line_initial_conditions.empty();
  NgspiceDeckContext context;
  context.tstop = tran.tstop;
  context.emission = options.emission;
  context.saturation_current = options.saturation_current;
  context.fresh = [&names](const std::string& wanted) { return names.fresh(wanted); };
  std::vector<std::string> models, after;  // cards of devices without branches (K) come last
  for (const std::shared_ptr<Device>& device : devices) {
    context.current_probed = current_probes.count(device->name()) > 0;
    context.reversed = options.reversed_diodes.count(device->name()) > 0;
    context.open = options.open_diodes.count(device->name()) > 0;
    auto factor = options.ron_factor.find(device->name());
    context.ron_factor = factor != options.ron_factor.end() ? factor->second : 1.0;
    // By element name, or by the name of the device's capacitor branch (a transistor's "q1:cbe").
    context.initial_value.reset();
    context.branch_initial.clear();
    context.line_initial.reset();
    auto line = options.line_initial_conditions.find(device->name());
    if (line != options.line_initial_conditions.end()) context.line_initial = line->second;
    auto given = options.initial_conditions.find(device->name());
    if (given != options.initial_conditions.end()) context.initial_value = given->second;
    for (const BranchDecl& b : device->branches()) {
      auto inner = options.initial_conditions.find(b.name);
      if (b.name != device->name() && b.cls == BranchClass::Capacitor && inner != options.initial_conditions.end())
        context.branch_initial[b.name] = inner->second;
    }
    NgspiceCards cards = device->ngspice(context);
    std::vector<std::string>& into = device->branches().empty() ? after : deck.lines;
    into.insert(into.end(), cards.lines.begin(), cards.lines.end());
    models.insert(models.end(), cards.models.begin(), cards.models.end());
    for (auto& [probe, source] : cards.probes) deck.probes[probe] = source;
    if (cards.ideal_diode) deck.ideal_diodes.push_back(device->name());
    if (!cards.witness.empty()) deck.witnesses.push_back(cards.witness);
  }
  deck.lines.insert(deck.lines.end(), after.begin(), after.end());
  rename_nodes_in_cards(netlist, deck.lines);
  for (auto& [probe, source] : deck.probes) {
    source.plus = ngspice_node_name(source.plus);
    source.minus = ngspice_node_name(source.minus);
  }
  for (const std::string& m : models) deck.lines.push_back(m);

  if (!netlist.node_ics.empty()) {
    std::string ic = ".ic";
    for (const NodeIc& n : netlist.node_ics) ic += " v(" + ngspice_node_name(n.node) + ")=" + num(n.value);
    deck.lines.push_back(ic);
  }
  if (!options.nodesets.empty()) {
    std::string set = ".nodeset";
    for (const auto& [node, value] : options.nodesets) set += " v(" + ngspice_node_name(node) + ")=" + num(value);
    deck.lines.push_back(set);
  }
  if (!options.node_holds.empty()) {
    std::string hold = ".ic";
    for (const auto& [node, value] : options.node_holds) hold += " v(" + ngspice_node_name(node) + ")=" + num(value);
    deck.lines.push_back(hold);
  }
  double tmax = tran.tmax > 0 && tran.tmax < tran.tstep ? tran.tmax : tran.tstep;
  if (options.max_step > 0) tmax = options.max_step;  // asked for explicitly: it wins
  const double tstop = options.tstop > 0 ? options.tstop : tran.tstop;
  deck.tstop = tstop;
  deck.lines.push_back(".tran " + num(tran.tstep) + " " + num(tstop) + " " + num(tran.tstart) +
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
