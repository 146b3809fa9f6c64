#include "netlist/elaborate.h"

#include <algorithm>
#include <cstdio>
#include <memory>
#include <optional>
#include <set>

#include "netlist/control_cards.h"
#include "netlist/element_card.h"
#include "netlist/measure_card.h"
#include "netlist/model_card.h"
#include "netlist/number.h"
#include "netlist/parallel_copies.h"
#include "netlist/out_of_scope.h"
#include "netlist/param_scope.h"

namespace lcs::parse {
namespace {

// LTspice/PSpice's `.step` reruns the deck per value; the CSV holds one run.
NetlistError step_refusal(const Card& card) {
  return NetlistError(card.at(0), "'.step' (parameter sweeps, LTspice/PSpice) is not supported: lcspice runs one "
                                  "transient per deck; give each value its own deck or .param");
}

std::string short_number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", x);
  return buf;
}

// Bounds that keep hostile input from exhausting memory or the stack.
// Elements plus instances after expansion. Formation and the sparse steps are linear in the
// circuit since issue 12 (`lcspice run` of 25000 half-wave rectifiers, 100,001 elements, 1000
// steps: 2.1 s, 275 MB), and methods that need the dense LCS refuse a circuit too large for it
// (solver/model/dense_budget.h); the bound keeps a hostile deck's expansion within about 1 GB.
constexpr std::size_t kMaxElements = 200'000;
constexpr int kMaxInstanceDepth = 100;
// The model of diodes written without one (a name no `.model` card can clash with: it has a space).
const char* const kDefaultDiode = "ideal default";

// "line 12", or "other.cir:12" when the first one is in another file.
std::string where(const SourceLocation& first, const SourceLocation& here) {
  if (first.file != here.file) return first.file + ":" + std::to_string(first.line);
  return "line " + std::to_string(first.line);
}

// A `name=value` value: the inside of a single {..} / '..', or the raw text of the tokens.
std::pair<int, int> value_span(const Card& card, std::size_t first, std::size_t last) {
  const Token& t = card[first];
  if (last - first == 1 && t.is_expression()) return {t.begin + 1, t.end - 1};
  return {t.begin, card[last - 1].end};
}

// One level of expansion: the top level or one X instance. It lives on the stack while its body
// is expanded; nested instances point to it as their parent.
struct Instance {
  const SubcktDef* def = nullptr;
  std::string prefix;                          // "" at the top level, "x1.", "x1.x2.", ...
  std::map<std::string, std::string> ports;    // port name -> flat node outside
  std::unique_ptr<ParamScope> scope;
  const Instance* parent = nullptr;
  std::map<std::string, std::string> models;   // model name as written -> flat model name
  int depth = 0;
  double multiplier = 1.0;                     // m= of this instance times its parents' (parallel_copies.h)
};

class Elaborator {
 public:
  explicit Elaborator(Netlist& netlist) : net_(netlist) {}

  void run(const SubcktDef& top, const Card* control_tran) {
    Instance root;
    root.def = &top;
    root.scope = std::make_unique<ParamScope>();
    collect_global_nodes(top);
    diode_capacitance_ = diode_capacitance_option(top);
    expand(root);
    check_internal_nodes();
    if (control_tran && !net_.tran) net_.tran = parse_tran(*control_tran, *root.scope, net_.warnings);
    note_unused_models();
    warn_temperature_coefficients();
    resolve_couplings();
    resolve_controls();
    check_node_ics();
    check_probes();
    check_measures();
    double tstep = net_.tran ? net_.tran->tstep : 0.0, tstop = net_.tran ? net_.tran->tstop : 0.0;
    for (Element& e : net_.elements)
      if (e.kind == ElementKind::VoltageSource || e.kind == ElementKind::CurrentSource) e.waveform.resolve(tstep, tstop);
  }

 private:
  std::string map_node(const Instance& in, const std::string& n) const {
    if (is_ground(n)) return "0";
    auto it = in.ports.find(n);
    if (it != in.ports.end()) return it->second;
    if (global_nodes_.count(n)) return n;
    return in.prefix + n;
  }

  // `.global NODE...` (top level, anywhere in the deck): inside every subcircuit instance NODE is
  // the top-level node of that name (ngspice), unless it is one of the subcircuit's ports.
  void collect_global_nodes(const SubcktDef& top) {
    for (const Card* card : top.body) {
      if (!(*card)[0].is_word(".global")) continue;
      if (card->size() == 1) throw NetlistError(card->after_last(), "missing node names after '.global'");
      for (std::size_t k = 1; k < card->size(); ++k) {
        const Token& t = (*card)[k];
        if (t.is(Token::Kind::Comma)) continue;
        if (!t.is_word()) throw NetlistError(card->at(t), "expected a node name, got " + quote(t.text));
        global_nodes_.insert(t.lower);
      }
    }
  }

  // A nonzero TC= changes nothing at the nominal temperature, the one lcspice simulates; a deck
  // that sets another with `.options temp=` or `tnom=` (accepted silently, as every unknown
  // option is) would get it wrong without a word. (`.temp` warns on its own card.)
  void warn_temperature_coefficients() {
    if (!first_temperature_coefficient_) return;
    for (const char* option : {"temp", "tnom"})
      if (net_.options.count(option)) {
        const auto& [name, loc] = *first_temperature_coefficient_;
        net_.warnings.push_back(warning_line(loc, quote(name) + ": temperature coefficients are not modelled: "
                                                  "lcspice runs at the nominal temperature (.options " +
                                                  option + "= is ignored)"));
        return;
      }
  }

  // `.options diodecap` (or diodecap=1; diodecap=0 is off), anywhere at the top level: the
  // diode cards' CJO is modelled (model_card.h), so a card's warning must not list it as ignored
  // and the models read after the option need to know before the `.options` card is reached.
  static bool diode_capacitance_option(const SubcktDef& top) {
    bool on = false;
    for (const Card* card : top.body) {
      const Card& c = *card;
      if (!(c[0].is_word(".options") || c[0].is_word(".option") || c[0].is_word(".opt"))) continue;
      for (std::size_t k = 1; k < c.size(); ++k) {
        if (!c[k].is_word("diodecap")) continue;
        const bool valued = k + 2 < c.size() && c[k + 1].is(Token::Kind::Equals);
        on = !(valued && parse_number(c[k + 2].lower) == 0.0);  // as read_netlist_options reads it
      }
    }
    return on;
  }

  void check_internal_nodes() const {
    if (internal_nodes_.empty()) return;
    for (const Element& e : net_.elements)
      for (const std::string& node : e.nodes) {
        auto it = internal_nodes_.find(node);
        if (it != internal_nodes_.end() && !it->second.count(e.name))
          throw NetlistError(e.loc, quote(e.name) + " connects to node " + quote(node) +
                                        ", the internal node lcspice makes for an instance parasitic (Rser=, "
                                        "Lser=): rename the node");
      }
  }

  void register_name(const std::string& flat, const SourceLocation& loc, const char* what) {
    auto [it, inserted] = names_.emplace(flat, loc);
    if (!inserted)
      throw NetlistError(loc, std::string("duplicate ") + what + " name " + quote(flat) + " (first defined at " +
                                  where(it->second, loc) + ")");
    if (names_.size() > kMaxElements)
      throw NetlistError(loc, "netlist too large (more than " + std::to_string(kMaxElements) +
                                  " elements after subcircuit expansion)");
  }

  void expand(Instance& in) {
    const std::vector<const Card*>& body = in.def->body;
    for (const Card* card : body) {
      if ((*card)[0].is_word(".func")) define_function(*card, *in.scope);
      if ((*card)[0].is_word(".param")) define_params(*card, *in.scope);
    }
    in.scope->evaluate_all();
    // Models next, so a diode may use a model defined further down (or in an enclosing scope).
    for (const Card* card : body)
      if ((*card)[0].is_word(".model")) add_model(*card, in);
    for (const Card* card : body) {
      const std::string& k = card->keyword();
      const bool word = (*card)[0].is_word();
      if (word && k[0] == '.') {
        control_card(*card, in);
      } else if (word && k[0] == 'x') {
        instantiate(*card, in);
      } else {
        add_element(*card, in);
      }
    }
  }

  void define_params(const Card& card, ParamScope& scope) {
    if (card.size() == 1) throw NetlistError(card.after_last(), "missing 'name=value' after '.param'");
    for (const Assignment& a : split_assignments(card, 1, card.size(), false, true)) {
      const Token& name = card[a.name];
      if (!is_identifier(name.lower)) throw NetlistError(card.at(name), "invalid parameter name " + quote(name.text));
      if (name.lower == "pi") throw NetlistError(card.at(name), "cannot redefine 'pi'");
      auto [b, e] = value_span(card, a.value_first, a.value_last);
      scope.define(name.lower, &card, b, e);
    }
  }

  void control_card(const Card& card, Instance& in) {
    const std::string& k = card.keyword();
    switch (classify_dot_card(k)) {
      case DotCard::Param:  // defined before the other cards of the scope
      case DotCard::Func:
      case DotCard::Model:
      case DotCard::Subckt:  // taken out by build_definitions
      case DotCard::Ends:
      case DotCard::Op:
      case DotCard::Global:  // read before the expansion (collect_global_nodes)
        return;
      case DotCard::Tran:
        if (net_.tran)
          throw NetlistError(card.at(0), "duplicate '.tran' card (first at " + where(net_.tran->loc, card.at(0)) + ")");
        net_.tran = parse_tran(card, *in.scope, net_.warnings);
        if (net_.tran->step_picked)
          net_.warnings.push_back(warning_line(
              card.at(0), std::string(net_.tran->stop_only ? "'.tran TSTOP' (LTspice)" : "'.tran 0 TSTOP' (LTspice/PSpice)") +
                              ": lcspice picks TSTEP = " +
                              (net_.tran->tmax > 0 && net_.tran->tstep == net_.tran->tmax
                                   ? std::string("TMAX")
                                   : (net_.tran->tstart > 0 ? "(TSTOP - TSTART)/" : "TSTOP/") +
                                         std::to_string(kPickedStepsPerSpan)) +
                              " = " + short_number(net_.tran->tstep) +
                              " s, the print step and the fixed-step methods' default step"));
        return;
      case DotCard::Ic:
        for (NodeIc& ic : parse_ic(card, *in.scope)) net_.node_ics.push_back(std::move(ic));
        return;
      case DotCard::Nodeset:
        for (NodeIc& ic : parse_ic(card, *in.scope)) net_.node_sets.push_back(std::move(ic));
        return;
      case DotCard::Print:
      case DotCard::Save:
        for (Probe& p : parse_probe_card(card, net_.warnings, print_every_probe_)) net_.probes.push_back(std::move(p));
        return;
      case DotCard::Options:
        parse_options(card, *in.scope, net_);
        return;
      case DotCard::Title:
        net_.title = card.size() > 1 ? card.text(card[1].begin, card.tokens.back().end) : "";
        return;
      case DotCard::Measure:
        if (std::optional<Measure> m = parse_measure(card, *in.scope, net_.warnings)) {
          for (const Measure& other : net_.measures)
            if (other.name == m->name)
              throw NetlistError(m->loc, "duplicate measure name " + quote(m->name) + " (first defined at " +
                                             where(other.loc, m->loc) + ")");
          net_.measures.push_back(std::move(*m));
        }
        return;
      case DotCard::Ignored:
        net_.warnings.push_back(warning_line(card.at(0), quote(k) + " is not supported and is ignored"));
        return;
      case DotCard::Endc:
        throw NetlistError(card.at(0), "'.endc' without '.control'");
      case DotCard::Unknown:
        if (k == ".step") throw step_refusal(card);  // in a subcircuit
        throw NetlistError(card.at(0), "unknown control card " + quote(card[0].text));
    }
  }

  void add_model(const Card& card, Instance& in) {
    ModelCard m = parse_model_card(card, *in.scope, in.prefix, net_.warnings, diode_capacitance_);
    const std::string flat = in.prefix + m.name;
    auto it = model_locs_.find(flat);
    if (it != model_locs_.end())
      throw NetlistError(card.at(1), "model " + quote(m.name) + " is already defined at " + where(it->second, card.at(1)));
    model_locs_[flat] = card.at(1);
    model_types_[flat] = m.type;
    in.models[m.name] = flat;
    if (m.unsimulated) unsimulated_models_.push_back({flat, m.type, card.at(2)});
    if (m.type == "d") net_.diode_models[flat] = std::move(m.diode);
    if (m.type == "npn" || m.type == "pnp") net_.bjt_models[flat] = std::move(m.bjt);
    if (m.type == "ltra") net_.line_models[flat] = std::move(m.line);
    if (m.type == "sw" || m.type == "csw" || m.type == "vswitch" || m.type == "iswitch")
      net_.switch_models[flat] = std::move(m.sw);
  }

  void add_element(const Card& card, Instance& in) {
    ElementScope scope;
    scope.params = in.scope.get();
    scope.prefix = in.prefix;
    scope.node = [&](const std::string& n) { return map_node(in, n); };
    scope.is_model = [&](const std::string& n) { return !find_model(in, n).empty(); };
    // A diode of a model type lcspice does not simulate (CIDER's NUMD): that, not its other fields.
    if (card.keyword()[0] == 'd' && card.size() > 3 && card[3].is_word()) {
      const std::string flat = find_model(in, card[3].lower);
      if (!flat.empty()) refuse_unsimulated(card, 3, model_types_.at(flat));
    }
    ParsedElement pe = parse_element(card, scope, net_.warnings);
    if (pe.temperature_coefficient_token && !first_temperature_coefficient_)
      first_temperature_coefficient_ = std::make_pair(pe.element.name, card.at(pe.temperature_coefficient_token));
    scale_for_parallel_copies(pe.element, in.multiplier);
    register_name(pe.element.name, card.at(0), "element");
    const std::size_t index = net_.elements.size();
    if (pe.element.kind == ElementKind::Diode)
      pe.element.model = pe.element.model.empty() ? default_diode_model(card) : resolve_diode_model(in, card, pe.model_token);
    if (pe.element.kind == ElementKind::Bjt) pe.element.model = resolve_bjt_model(in, card, pe.model_token);
    if (pe.element.kind == ElementKind::LossyLine)
      pe.element.model = resolve_line_model(in, card, pe.model_token);
    if (pe.element.kind == ElementKind::VSwitch || pe.element.kind == ElementKind::CSwitch)
      pe.element.model = resolve_switch_model(in, card, pe.model_token, pe.element.kind == ElementKind::CSwitch);
    if (pe.element.kind == ElementKind::Coupling)
      coupling_refs_.push_back({index, {card.at(pe.coupled_tokens[0]), card.at(pe.coupled_tokens[1])}});
    if (pe.shorted) {
      net_.warnings.push_back(warning_line(card.at(1), quote(pe.element.name) + " has both terminals on node " +
                                                          quote(pe.element.nodes[0]) +
                                                          ": it carries no current and is left out of the circuit"));
      shorted_.insert(pe.element.name);
      return;
    }
    if (pe.control_token) control_refs_.push_back({index, card.at(pe.control_token)});
    net_.elements.push_back(std::move(pe.element));
    const std::string owner = net_.elements.back().name;
    std::size_t extra_coupling = 0;
    for (Element& parasitic : pe.parasitics) {
      register_name(parasitic.name, card.at(0), "element");
      if (parasitic.kind == ElementKind::Coupling) {
        const auto& tokens = pe.extra_coupled_tokens.at(extra_coupling++);
        coupling_refs_.push_back({net_.elements.size(), {card.at(tokens[0]), card.at(tokens[1])}});
      }
      scale_for_parallel_copies(parasitic, in.multiplier);
      for (const std::string& node : parasitic.nodes)
        if (node.rfind(owner + "#", 0) == 0) {
          std::set<std::string>& users = internal_nodes_[node];
          users.insert(owner);
          users.insert(parasitic.name);
        }
      net_.elements.push_back(std::move(parasitic));
    }
  }

  // `D anode cathode` without a model: LTspice's default diode, which is ideal (VON = 0, RON = 0:
  // lcspice's ideal law exactly). One shared model; one warning for the deck.
  std::string default_diode_model(const Card& card) {
    if (!net_.diode_models.count(kDefaultDiode)) {
      DiodeModel d;
      d.name = kDefaultDiode;
      d.von = 0.0;
      d.ron = 0.0;
      d.loc = card.at(0);
      net_.diode_models[kDefaultDiode] = d;
      net_.warnings.push_back(warning_line(card.at(0), "diode " + quote(card[0].lower) +
                                                           " has no model name (LTspice dialect): it and every "
                                                           "other such diode get the ideal diode, VON = 0, RON = 0"));
    }
    return kDefaultDiode;
  }

  // Xname nodes... SUBNAME [params:] [name=value ...]
  void instantiate(const Card& card, Instance& in) {
    const std::size_t n = card.size();
    const std::string flat = in.prefix + card[0].lower;
    std::vector<std::size_t> words;
    std::size_t i = 1;
    for (; i < n; ++i) {
      const Token& t = card[i];
      if (t.is_word("params:")) break;
      if (t.is_word() && i + 1 < n && card[i + 1].is(Token::Kind::Equals)) break;
      if (!t.is_word()) throw NetlistError(card.at(t), "expected a node or subcircuit name, got " + quote(t.text));
      words.push_back(i);
    }
    if (words.empty()) throw NetlistError(card.after_last(), "missing subcircuit name for " + quote(flat));
    const std::size_t name_token = words.back();
    words.pop_back();
    if (i < n && card[i].is_word("params:")) ++i;
    const std::string& sub = card[name_token].lower;

    const SubcktDef* def = in.def->find(sub);
    if (!def) throw UndefinedNameError(card.at(name_token), "subcircuit " + quote(sub) + " is not defined");
    for (const Instance* p = &in; p; p = p->parent)
      if (p->def == def) throw NetlistError(card.at(name_token), "recursive instantiation of subcircuit " + quote(sub));
    if (in.depth >= kMaxInstanceDepth) throw NetlistError(card.at(0), "subcircuit instances nested too deeply");
    if (words.size() != def->ports.size())
      throw NetlistError(card.at(name_token),
                         quote(flat) + " connects " + std::to_string(words.size()) + " node" + (words.size() == 1 ? "" : "s") +
                             " but subcircuit " + quote(sub) + " has " + std::to_string(def->ports.size()) + " port" +
                             (def->ports.size() == 1 ? "" : "s"));
    register_name(flat, card.at(0), "instance");

    Instance child;
    child.def = def;
    child.prefix = flat + ".";
    child.parent = &in;
    child.depth = in.depth + 1;
    child.multiplier = in.multiplier;
    child.scope = std::make_unique<ParamScope>(in.scope.get());
    for (std::size_t k = 0; k < words.size(); ++k) child.ports[def->ports[k]] = map_node(in, card[words[k]].lower);
    for (const Assignment& a : split_assignments(card, i, n, false, true)) {
      const Token& name = card[a.name];
      // ngspice's multiplier, m copies of the instance in parallel; a subcircuit that declares a
      // parameter m takes it as that parameter instead (as ngspice does).
      if (name.lower == "m" && !def->param("m")) {
        const double m = value_of(card, a.value_first, a.value_last, *in.scope, true);
        if (!(m > 0)) throw NetlistError(card.at(a.value_first), "multiplier m of " + quote(flat) + " must be positive");
        child.multiplier *= m;
        continue;
      }
      if (!def->param(name.lower))
        throw NetlistError(card.at(name), "subcircuit " + quote(sub) + " has no parameter " + quote(name.lower));
      child.scope->set(name.lower, value_of(card, a.value_first, a.value_last, *in.scope, true));
    }
    for (const SubcktDef::Param& p : def->params) {
      if (child.scope->defines(p.name)) continue;
      auto [b, e] = value_span(*def->card, p.value_first, p.value_last);
      child.scope->define(p.name, def->card, b, e);
    }
    expand(child);
  }

  // The flat name of the model a diode card names: the innermost instance that defines it.
  // The model a name denotes in this instance or an enclosing one (flat name), or "".
  std::string find_model(const Instance& in, const std::string& name) const {
    for (const Instance* p = &in; p; p = p->parent) {
      auto it = p->models.find(name);
      if (it != p->models.end()) return it->second;
    }
    return "";
  }

  std::string resolve_bjt_model(const Instance& in, const Card& card, std::size_t token) const {
    const std::string& name = card[token].lower;
    const std::string flat = find_model(in, name);
    if (flat.empty()) throw UndefinedNameError(card.at(token), "transistor model " + quote(name) + " is not defined");
    const std::string& type = model_types_.at(flat);
    refuse_unsimulated(card, token, type);
    if (type != "npn" && type != "pnp")
      throw NetlistError(card.at(token), "model " + quote(name) + " is not a transistor model (it is " + to_upper(type) + ")");
    return flat;
  }

  std::string resolve_line_model(const Instance& in, const Card& card, std::size_t token) const {
    const std::string& name = card[token].lower;
    const std::string flat = find_model(in, name);
    if (flat.empty()) throw UndefinedNameError(card.at(token), "line model " + quote(name) + " is not defined");
    const std::string& type = model_types_.at(flat);
    refuse_unsimulated(card, token, type);
    if (type != "ltra")
      throw NetlistError(card.at(token), "model " + quote(name) + " is not a line model (it is " + to_upper(type) + ")");
    return flat;
  }

  std::string resolve_switch_model(const Instance& in, const Card& card, std::size_t token, bool current) const {
    const std::string& name = card[token].lower;
    const std::string flat = find_model(in, name);
    const char* wanted = current ? "csw" : "sw";
    const char* pspice = current ? "iswitch" : "vswitch";
    if (flat.empty()) throw UndefinedNameError(card.at(token), "switch model " + quote(name) + " is not defined");
    const std::string& type = model_types_.at(flat);
    if (type != wanted && type != pspice)
      throw NetlistError(card.at(token), "model " + quote(name) + " is not a" + (current ? " CSW" : "n SW") +
                                             " model (it is " + to_upper(type) + "); " +
                                             (current ? "W switches take CSW (or ISWITCH) models" : "S switches take SW (or VSWITCH) models"));
    return flat;
  }

  std::string resolve_diode_model(const Instance& in, const Card& card, std::size_t token) const {
    const std::string& name = card[token].lower;
    for (const Instance* p = &in; p; p = p->parent) {
      auto it = p->models.find(name);
      if (it == p->models.end()) continue;
      const std::string& type = model_types_.at(it->second);
      refuse_unsimulated(card, token, type);
      if (type != "d")
        throw NetlistError(card.at(token), "model " + quote(name) + " is not a diode model (it is " + to_upper(type) + ")");
      return it->second;
    }
    throw UndefinedNameError(card.at(token), "diode model " + quote(name) + " is not defined");
  }

  static void refuse_unsimulated(const Card& card, std::size_t token, const std::string& type) {
    if (!unsimulated_model_kind(type).empty()) throw NetlistError(card.at(token), unsimulated_model_reason(type));
  }

  // Every element that uses a model lcspice does not simulate has been refused: the rest are unused.
  void note_unused_models() {
    std::set<std::string> said;  // a model in a subcircuit instantiated many times: one note
    for (const UnsimulatedModel& m : unsimulated_models_)
      if (said.insert(m.loc.file + ":" + std::to_string(m.loc.line) + ":" + std::to_string(m.loc.column)).second)
        net_.warnings.push_back(warning_line(m.loc, "model " + quote(m.name) + " (" + unsimulated_model_kind(m.type) +
                                                       ") is not simulated by lcspice; no element uses it: skipped"));
  }

  void resolve_couplings() {
    std::map<std::string, std::size_t> by_name;
    for (std::size_t i = 0; i < net_.elements.size(); ++i) by_name[net_.elements[i].name] = i;
    std::map<std::pair<std::string, std::string>, std::string> pairs;
    for (const CouplingRef& r : coupling_refs_) {
      const Element& k = net_.elements[r.element];
      for (int j = 0; j < 2; ++j) {
        auto it = by_name.find(k.coupled[j]);
        if (it == by_name.end()) throw NetlistError(r.locs[j], "coupled inductor " + quote(k.coupled[j]) + " is not defined");
        if (net_.elements[it->second].kind != ElementKind::Inductor)
          throw NetlistError(r.locs[j], quote(k.coupled[j]) + " is not an inductor");
      }
      auto key = std::minmax(k.coupled[0], k.coupled[1]);
      auto [it, inserted] = pairs.emplace(std::make_pair(key.first, key.second), k.name);
      if (!inserted)
        throw NetlistError(k.loc, "inductors " + quote(k.coupled[0]) + " and " + quote(k.coupled[1]) +
                                      " are already coupled by " + quote(it->second));
    }
  }

  // F and H name a voltage source whose current controls them; in a subcircuit the name is the
  // instance's own (ngspice prefixes it like every other name of the instance).
  void resolve_controls() {
    for (const ControlRef& r : control_refs_) {
      const Element& e = net_.elements[r.element];
      const Element* v = net_.find_element(e.control);
      if (!v) throw NetlistError(r.loc, quote(e.name) + ": controlling voltage source " + quote(e.control) + " is not defined");
      if (v->kind != ElementKind::VoltageSource)
        throw NetlistError(r.loc, quote(e.name) + ": " + quote(e.control) + " is not a voltage source (it is a " +
                                      element_kind_name(v->kind) + "); " +
                                      (e.kind == ElementKind::CSwitch ? "W is" : "F and H are") +
                                      " controlled by a V source's current");
    }
  }

  std::set<std::string> nodes() const {
    std::set<std::string> out = {"0"};
    for (const Element& e : net_.elements) out.insert(e.nodes.begin(), e.nodes.end());
    return out;
  }

  void check_node_ics() {
    const std::set<std::string> all = nodes();
    for (std::vector<NodeIc>* list : {&net_.node_ics, &net_.node_sets}) {
      std::vector<NodeIc> unique;
      for (NodeIc& ic : *list) {
        if (!all.count(ic.node)) throw NetlistError(ic.loc, "unknown node " + quote(ic.node));
        auto same = std::find_if(unique.begin(), unique.end(), [&](const NodeIc& u) { return u.node == ic.node; });
        if (same != unique.end()) *same = ic;  // the later one wins
        else unique.push_back(ic);
      }
      *list = std::move(unique);
    }
  }

  // A probe as `.print` or `.meas` wrote it, checked against the circuit: an unknown node or
  // element is a located error. i(element) of an element left out (both terminals on one node)
  // reads zero: v(0,0) under the probe's own name.
  Probe checked_probe(const Probe& p, const std::set<std::string>& all) const {
    if (p.kind == Probe::Kind::ElementCurrent && shorted_.count(p.a)) {
      Probe zero = p;
      zero.kind = Probe::Kind::NodePairVoltage;
      zero.a = zero.b = "0";
      zero.label = p.name();
      return zero;
    }
    if (p.kind == Probe::Kind::ElementCurrent) {
      const Element* e = net_.find_element(p.a);
      if (!e) throw NetlistError(p.loc, "unknown element " + quote(p.a));
      if (e->kind == ElementKind::Coupling) throw NetlistError(p.loc, quote(p.a) + " has no current (it is a coupling)");
      if (e->kind == ElementKind::Bjt)
        throw NetlistError(p.loc, quote(p.a) + " is a transistor: probe its terminal currents ic(" + p.a +
                                      "), ib(" + p.a + ") or ie(" + p.a + ")");
    } else if (p.kind == Probe::Kind::TerminalCurrent) {
      const Element* e = net_.find_element(p.a);
      if (!e) throw NetlistError(p.loc, "unknown element " + quote(p.a));
      if (p.terminal == '2') {
        if (e->kind != ElementKind::Line && e->kind != ElementKind::LossyLine)
          throw NetlistError(p.loc, p.name() + ": " + quote(p.a) + " is not a transmission line (use i(" + p.a + "))");
      } else if (e->kind != ElementKind::Bjt) {
        throw NetlistError(p.loc, p.name() + ": " + quote(p.a) + " is not a transistor (use i(" + p.a + "))");
      }
    } else {
      for (const std::string* n : {&p.a, &p.b})
        if (!n->empty() && !all.count(*n)) throw NetlistError(p.loc, "unknown node " + quote(*n));
    }
    return p;
  }

  void check_probes() {
    const std::set<std::string> all = nodes();
    std::vector<Probe> unique;
    std::set<std::string> seen;
    for (const Probe& p : net_.probes) {
      Probe checked = checked_probe(p, all);
      if (seen.insert(checked.name()).second) unique.push_back(std::move(checked));
    }
    net_.probes = std::move(unique);
    net_.every_probe = print_every_probe_;
  }

  // The probes of `.meas` cards, checked as `.print`'s are.
  void check_measures() {
    if (net_.measures.empty()) return;
    const std::set<std::string> all = nodes();
    auto check = [&](Probe& p) { p = checked_probe(p, all); };
    std::set<std::string> measured;
    for (const Measure& m : net_.measures) measured.insert(m.name);
    for (Measure& m : net_.measures) {
      switch (m.kind) {
        case Measure::Kind::When:
          break;
        case Measure::Kind::Param:
          check_param_names(m, measured);
          break;
        case Measure::Kind::TrigTarg:
          for (MeasureCrossing* c : {&m.when, &m.targ})
            if (!c->at) check(c->probe);
          break;
        default:
          check(m.probe);
      }
      if (m.kind == Measure::Kind::FindWhen || m.kind == Measure::Kind::When) {
        check(m.when.probe);
        if (m.when.other) check(*m.when.other);
      }
    }
  }

  // A PARAM's names that are neither parameters nor measures: one warning, at the first, as
  // ngspice runs the deck and fails the measure (as the run will).
  void check_param_names(const Measure& m, const std::set<std::string>& measured) {
    std::vector<const MeasureExpression::Name*> unknown;
    for (const MeasureExpression::Name& n : m.expression.names)
      if (!measured.count(n.name)) unknown.push_back(&n);
    if (unknown.empty()) return;
    std::string list = quote(unknown[0]->name);
    const std::size_t shown = std::min<std::size_t>(unknown.size(), 3);
    for (std::size_t k = 1; k < shown; ++k) list += (k + 1 == unknown.size() ? " and " : ", ") + quote(unknown[k]->name);
    if (unknown.size() > shown) list += " and " + std::to_string(unknown.size() - shown) + " more";
    net_.warnings.push_back(warning_line(m.expression.location_of(*unknown[0]), list + (unknown.size() == 1 ? " is" : " are") +
                                                              " neither a measure lcspice computes nor a parameter: "
                                                              "measure " + quote(m.name) + " will fail"));
  }

  static std::string to_upper(std::string s) {
    for (char& c : s)
      if (c >= 'a' && c <= 'z') c = static_cast<char>(c - 'a' + 'A');
    return s;
  }

  struct CouplingRef {
    std::size_t element;
    SourceLocation locs[2];
  };

  struct ControlRef {
    std::size_t element;
    SourceLocation loc;
  };

  Netlist& net_;
  std::vector<ControlRef> control_refs_;
  std::map<std::string, SourceLocation> names_;
  std::set<std::string> global_nodes_;  // `.global` names (lower case)
  std::map<std::string, SourceLocation> model_locs_;
  std::map<std::string, std::string> model_types_;
  std::vector<CouplingRef> coupling_refs_;
  bool diode_capacitance_ = false;  // `.options diodecap`
  bool print_every_probe_ = false;  // a .print's V(*) or I(*)
  std::optional<std::pair<std::string, SourceLocation>> first_temperature_coefficient_;
  struct UnsimulatedModel {
    std::string name, type;
    SourceLocation loc;
  };
  std::vector<UnsimulatedModel> unsimulated_models_;
  std::set<std::string> shorted_;  // elements left out because both terminals are one node
  // Internal nodes of instance parasitics ("l1#rser") -> the elements that may use them (the
  // element and its parasitics): a deck's own node of that name is refused (check_internal_nodes).
  std::map<std::string, std::set<std::string>> internal_nodes_;
};

}  // namespace

void elaborate(const SubcktDef& top, Netlist& netlist, const Card* control_tran) {
  // `.step` first: LTspice writes its directives after the components, and an element using the
  // stepped parameter ({R}) would otherwise be reported as an undefined parameter.
  for (const Card* card : top.body)
    if (card->keyword() == ".step") throw step_refusal(*card);
  Elaborator(netlist).run(top, control_tran);
}

}  // namespace lcs::parse
