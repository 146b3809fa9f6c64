#include "netlist/element_card.h"

#include "netlist/instance_parasitics.h"
#include "netlist/parallel_copies.h"
#include "netlist/part_attributes.h"
#include "netlist/source_card.h"

#include <cmath>
#include <optional>

namespace lcs::parse {
namespace {

struct Reader {
  const Card& card;
  const ElementScope& scope;
  std::string name;  // flat name, for messages
  std::vector<std::string>* warnings_ = nullptr;
  mutable std::size_t temperature_coefficient = 0;  // token of the first nonzero TC=/tc1=/tc2=

  void node(std::size_t i, Element& e) const {
    if (i >= card.size()) throw NetlistError(card.after_last(), "missing node for " + quote(name));
    const Token& t = card[i];
    if (!t.is_word()) throw NetlistError(card.at(t), "expected a node name, got " + quote(t.text));
    e.nodes.push_back(scope.node(t.lower));
  }

  void distinct_nodes(const Element& e, const char* why = nullptr) const {
    if (e.nodes[0] == e.nodes[1])
      throw NetlistError(card.at(2), name + " connects node " + quote(e.nodes[0]) + " to itself" +
                                         (why ? std::string(" (") + why + ")" : std::string()));
  }

  double value(std::size_t i) const {
    if (i >= card.size()) throw NetlistError(card.after_last(), "missing value for " + quote(name));
    return value_of(card, i, *scope.params);
  }

  [[noreturn]] void extra(std::size_t i) const {
    const Token& t = card[i];
    if (t.is_word() && i + 1 < card.size() && card[i + 1].is(Token::Kind::Equals))
      throw NetlistError(card.at(t), "unknown parameter " + quote(t.text) + " for " + quote(name) +
                                         ltspice_parasitic_hint(t.lower));
    throw NetlistError(card.at(t), "unexpected extra token " + quote(t.text));
  }

  // What follows the value of R, L and C: `M=m` (m copies in parallel: ngspice's multiplier) and,
  // for L and C, `IC=value` and LTspice's parasitics (into *parasitics). Returns m (1 when not given).
  double trailing(std::size_t i, Element& e, bool ic_allowed, InstanceParasitics* parasitics = nullptr) const {
    double m = 1.0;
    std::vector<std::string> attributes;  // LTspice's part data, skipped
    while (i < card.size()) {
      if (const std::size_t next = skip_part_attribute(card, i, e.kind, attributes); next != i) {
        i = next;
        continue;
      }
      if (parasitics) {
        const std::size_t next = read_parasitic(card, i, e.kind, *scope.params, name, *parasitics);
        if (next != i) {
          i = next;
          continue;
        }
      }
      const bool assignment = card[i].is_word() && i + 1 < card.size() && card[i + 1].is(Token::Kind::Equals);
      if (assignment && (card[i].is_word("m") || (ic_allowed && card[i].is_word("ic")))) {
        if (i + 2 >= card.size()) throw NetlistError(card.after_last(), "missing value for " + quote(card[i].lower));
        const double v = value_of(card, i + 2, *scope.params);
        if (card[i].is_word("m")) {
          positive(i + 2, v, "multiplier m");
          m = v;
        } else {
          e.ic = v;
        }
        i += 3;
        continue;
      }
      // Temperature coefficients (ngspice's tc1= tc2=, PSpice's TC=a[,b]) scale the value by
      // 1 + tc1 (T - TNOM) + tc2 (T - TNOM)^2: nothing at the nominal temperature, the only one
      // lcspice simulates (.temp is ignored with a warning). The values are read to check them.
      if (assignment && (card[i].is_word("tc") || card[i].is_word("tc1") || card[i].is_word("tc2"))) {
        const bool list = card[i].is_word("tc");
        const std::size_t at = i;
        if (i + 2 >= card.size()) throw NetlistError(card.after_last(), "missing value for " + quote(card[i].lower));
        bool nonzero = value_of(card, i + 2, *scope.params) != 0;
        i += 3;
        if (list && i < card.size() && card[i].is(Token::Kind::Comma)) {
          if (i + 1 >= card.size()) throw NetlistError(card.after_last(), "missing second value for 'tc'");
          nonzero = value_of(card, i + 1, *scope.params) != 0 || nonzero;
          i += 2;
        }
        if (nonzero && !temperature_coefficient) temperature_coefficient = at;
        continue;
      }
      if (assignment && (card[i].is_word("temp") || card[i].is_word("dtemp"))) {
        if (i + 2 >= card.size()) throw NetlistError(card.after_last(), "missing value for " + quote(card[i].lower));
        value_of(card, i + 2, *scope.params);
        warnings_->push_back(warning_line(card.at(i), quote(name) + ": " + card[i].lower +
                                                          "= is ignored (no temperature model)"));
        i += 3;
        continue;
      }
      extra(i);
    }
    if (!attributes.empty()) warnings_->push_back(warning_line(card.at(0), part_attributes_warning(name, attributes)));
    return m;
  }

  void positive(std::size_t i, double v, const char* what) const {
    if (!(v > 0)) throw NetlistError(card.at(i), std::string(what) + " of " + quote(name) + " must be positive");
  }
};

bool starts_with_digit(const Token& t) {
  return t.is_expression() || (!t.lower.empty() && ((t.lower[0] >= '0' && t.lower[0] <= '9') || t.lower[0] == '.'));
}

// Q collector base emitter [substrate] model [area] [OFF] [AREA=a] [M=m] [IC=vbe,vce] [TEMP=t]
// The optional substrate node and the model name are told apart by which of them names a model,
// as ngspice does.
void parse_bjt(const Card& card, const Reader& r, const ElementScope& scope, ParsedElement& out,
               std::vector<std::string>& warnings) {
  Element& e = out.element;
  e.kind = ElementKind::Bjt;
  for (std::size_t i = 1; i <= 3; ++i) r.node(i, e);
  if (e.nodes[0] == e.nodes[1] && e.nodes[1] == e.nodes[2])
    throw NetlistError(card.at(1), r.name + " connects all three terminals to node " + quote(e.nodes[0]));
  std::vector<std::size_t> positional;
  std::size_t i = 4;
  for (; i < card.size(); ++i) {
    const Token& t = card[i];
    if (t.is_word("off") || (i + 1 < card.size() && card[i + 1].is(Token::Kind::Equals))) break;
    if (!t.is_word() && !t.is_expression()) throw NetlistError(card.at(t), "unexpected token " + quote(t.text));
    positional.push_back(i);
  }
  if (positional.empty()) throw NetlistError(card.after_last(), "missing model name for " + quote(r.name));
  auto names_model = [&](std::size_t k) { return card[k].is_word() && scope.is_model && scope.is_model(card[k].lower); };
  std::size_t model = positional[0], area = 0;
  if (names_model(positional[0])) {
    if (positional.size() > 2) r.extra(positional[2]);
    if (positional.size() == 2) area = positional[1];
  } else if (positional.size() >= 2 && (names_model(positional[1]) || !starts_with_digit(card[positional[1]]))) {
    model = positional[1];  // after a substrate node (not modelled)
    if (positional.size() > 3) r.extra(positional[3]);
    if (positional.size() == 3) area = positional[2];
    warnings.push_back(warning_line(card.at(positional[0]), quote(r.name) + ": substrate node " +
                                                            quote(card[positional[0]].lower) +
                                                            " is not modelled (no substrate junction)"));
  }
  if (!card[model].is_word()) throw NetlistError(card.at(model), "expected a model name, got " + quote(card[model].text));
  e.model = card[model].lower;
  out.model_token = model;
  e.value = 1.0;
  if (area) {
    e.value = r.value(area);
    r.positive(area, e.value, "area");
  }
  while (i < card.size()) {
    const Token& t = card[i];
    if (t.is_word("off")) {
      e.initially_on = false;  // among several operating points, one with this transistor off
      ++i;
      continue;
    }
    if (!(t.is_word() && i + 1 < card.size() && card[i + 1].is(Token::Kind::Equals))) r.extra(i);
    if (i + 2 >= card.size()) throw NetlistError(card.after_last(), "missing value for " + quote(t.lower));
    std::size_t last = i + 3;  // IC=vbe,vce takes two values
    if (t.lower == "ic") {
      while (last + 1 < card.size() && card[last].is(Token::Kind::Comma)) last += 2;
      warnings.push_back(warning_line(card.at(t), quote(r.name) + ": IC= is ignored (use .ic on the nodes)"));
    } else if (t.lower == "area" || t.lower == "m") {
      const double v = r.value(i + 2);
      r.positive(i + 2, v, t.lower == "area" ? "area" : "multiplier m");
      e.value *= v;
    } else if (t.lower == "temp" || t.lower == "dtemp") {
      warnings.push_back(warning_line(card.at(t), quote(r.name) + ": " + t.lower + "= is ignored (no temperature model)"));
    } else {
      r.extra(i);
    }
    i = last;
  }
}

// D ... model [area] [AREA=a] [M=m]: the diode's value is the area times m (m diodes in parallel).
void diode_instance_params(const Card& card, const Reader& r, std::size_t i, Element& e) {
  e.value = 1.0;
  if (i < card.size() && !(i + 1 < card.size() && card[i + 1].is(Token::Kind::Equals)) &&
      starts_with_digit(card[i])) {
    e.value = r.value(i);
    r.positive(i, e.value, "area");
    ++i;
  }
  while (i < card.size()) {
    const Token& t = card[i];
    if (t.is_word("off")) {
      e.initially_on = false;  // among several operating points, one with this diode off
      ++i;
      continue;
    }
    if (!(t.is_word() && i + 1 < card.size() && card[i + 1].is(Token::Kind::Equals))) r.extra(i);
    if (i + 2 >= card.size()) throw NetlistError(card.after_last(), "missing value for " + quote(t.lower));
    // ngspice's other instance parameters (Qucs-S writes Temp= on every diode): read, checked
    // and ignored with a warning, as on R, L, C and Q cards.
    const char* ignored = t.lower == "temp" || t.lower == "dtemp" ? "no temperature model"
                          : t.lower == "ic"                       ? "use .ic on the nodes"
                          : t.lower == "pj"                       ? "no sidewall junction model"
                                                                  : nullptr;
    if (ignored) {
      r.value(i + 2);
      r.warnings_->push_back(warning_line(card.at(t), quote(r.name) + ": " + t.lower + "= is ignored (" + ignored + ")"));
      i += 3;
      continue;
    }
    if (t.lower != "area" && t.lower != "m") r.extra(i);
    const double v = r.value(i + 2);
    r.positive(i + 2, v, t.lower == "area" ? "area" : "multiplier m");
    e.value *= v;
    i += 3;
  }
}

// The four port nodes of a T or O card; a port whose two nodes are one node is shorted.
void line_ports(const Card& card, const Reader& r, Element& e) {
  for (std::size_t i = 1; i <= 4; ++i) r.node(i, e);
  for (std::size_t port = 0; port < 2; ++port)
    if (e.nodes[2 * port] == e.nodes[2 * port + 1])
      throw NetlistError(card.at(2 * port + 2), "port " + std::to_string(port + 1) + " of " + quote(r.name) +
                                                    " connects node " + quote(e.nodes[2 * port]) + " to itself");
}

// IC=v1,i1,v2,i2: four numbers.
std::size_t line_ic(const Card& card, const Reader& r, std::size_t i, Element& e) {
  std::size_t k = i + 2;
  e.line_ic.clear();
  while (true) {
    e.line_ic.push_back(r.value(k));
    if (k + 1 < card.size() && card[k + 1].is(Token::Kind::Comma)) {
      k += 2;
      continue;
    }
    break;
  }
  if (e.line_ic.size() != 4)
    throw NetlistError(card.at(i), "IC= of " + quote(r.name) + " takes four values v1,i1,v2,i2");
  return k + 1;
}

// T p1+ p1- p2+ p2- Z0=z (TD=t | F=f [NL=nl]) [IC=v1,i1,v2,i2]   (ngspice's lossless line)
void parse_lossless_line(const Card& card, const Reader& r, Element& e) {
  e.kind = ElementKind::Line;
  line_ports(card, r, e);
  std::optional<double> z0, td, f, nl;
  std::size_t z0_at = 0, td_at = 0, f_at = 0, nl_at = 0;
  std::size_t i = 5;
  while (i < card.size()) {
    const Token& t = card[i];
    if (!(t.is_word() && i + 1 < card.size() && card[i + 1].is(Token::Kind::Equals))) r.extra(i);
    if (i + 2 >= card.size()) throw NetlistError(card.after_last(), "missing value for " + quote(t.lower));
    if (t.lower == "ic") {
      i = line_ic(card, r, i, e);
      continue;
    }
    const double v = r.value(i + 2);
    if (t.lower == "z0" || t.lower == "zo") {
      z0 = v, z0_at = i + 2;
    } else if (t.lower == "td") {
      td = v, td_at = i + 2;
    } else if (t.lower == "f") {
      f = v, f_at = i + 2;
    } else if (t.lower == "nl") {
      nl = v, nl_at = i + 2;
    } else {
      r.extra(i);
    }
    i += 3;
  }
  if (!z0) throw NetlistError(card.after_last(), "missing Z0= for " + quote(r.name));
  if (!(*z0 > 0) || !std::isfinite(*z0))
    throw NetlistError(card.at(z0_at), "Z0 of " + quote(r.name) + " must be positive");
  e.value = *z0;
  if (td) {
    if (!(*td > 0) || !std::isfinite(*td))
      throw NetlistError(card.at(td_at), "TD of " + quote(r.name) + " must be positive");
    e.delay = *td;
  } else if (f) {
    if (!(*f > 0) || !std::isfinite(*f))
      throw NetlistError(card.at(f_at), "F of " + quote(r.name) + " must be positive");
    const double length = nl.value_or(0.25);
    if (!(length > 0) || !std::isfinite(length))
      throw NetlistError(card.at(nl_at), "NL of " + quote(r.name) + " must be positive");
    e.delay = length / *f;
  } else {
    throw NetlistError(card.after_last(), "missing TD= (or F= [NL=]) for " + quote(r.name));
  }
  if (!(e.delay > 0) || !std::isfinite(e.delay))
    throw NetlistError(card.at(f_at ? f_at : td_at), "the delay of " + quote(r.name) + " must be positive");
}

// O p1+ p1- p2+ p2- model [IC=v1,i1,v2,i2]   (ngspice's LTRA line)
void parse_lossy_line(const Card& card, const Reader& r, ParsedElement& out) {
  Element& e = out.element;
  e.kind = ElementKind::LossyLine;
  line_ports(card, r, e);
  if (card.size() <= 5) throw NetlistError(card.after_last(), "missing model name for " + quote(r.name));
  if (!card[5].is_word()) throw NetlistError(card.at(5), "expected a model name, got " + quote(card[5].text));
  e.model = card[5].lower;
  out.model_token = 5;
  std::size_t i = 6;
  while (i < card.size()) {
    if (card[i].is_word("ic") && i + 2 < card.size() && card[i + 1].is(Token::Kind::Equals)) {
      i = line_ic(card, r, i, e);
      continue;
    }
    r.extra(i);
  }
}

// The control of E, G, S (nodes nc+ nc- at tokens 3, 4) or of F, H, W (a V source's name at
// token 3); returns the index of the token after it.
std::size_t read_control(const Card& card, const Reader& r, bool voltage_controlled, ParsedElement& out) {
  Element& e = out.element;
  if (voltage_controlled) {
    r.node(3, e);
    r.node(4, e);
    return 5;
  }
  if (card.size() <= 3) throw NetlistError(card.after_last(), "missing controlling voltage source for " + quote(r.name));
  if (!card[3].is_word())
    throw NetlistError(card.at(3), "expected the name of a voltage source, got " + quote(card[3].text));
  e.control = r.scope.prefix + card[3].lower;
  out.control_token = 3;
  return 4;
}

// E/G n+ n- nc+ nc- gain and F/H n+ n- vname gain: ngspice's linear controlled sources. Their
// behavioural forms (VALUE=, VOL=, CUR=, POLY, TABLE, LAPLACE) are nonlinear: refused by name.
void parse_controlled_source(const Card& card, const Reader& r, char letter, ParsedElement& out) {
  Element& e = out.element;
  const bool voltage_controlled = letter == 'e' || letter == 'g';
  e.kind = letter == 'e' ? ElementKind::Vcvs : letter == 'g' ? ElementKind::Vccs
         : letter == 'f' ? ElementKind::Cccs : ElementKind::Ccvs;
  r.node(1, e);
  r.node(2, e);
  r.distinct_nodes(e);
  for (std::size_t i = 3; i < card.size(); ++i) {
    const Token& t = card[i];
    const bool keyword = t.is_word("value") || t.is_word("vol") || t.is_word("cur") || t.is_word("poly") ||
                         t.is_word("table") || t.is_word("laplace") || t.is_word("freq");
    if (keyword && (i + 1 >= card.size() || !card[i + 1].is_word()))
      throw NetlistError(card.at(t), quote(r.name) + ": the behavioural form " + quote(t.lower) +
                                         " is not supported (only linear controlled sources: " +
                                         (voltage_controlled ? "n+ n- nc+ nc- gain" : "n+ n- vname gain") + ")");
  }
  const std::size_t gain = read_control(card, r, voltage_controlled, out);
  e.value = r.value(gain);
  if (!std::isfinite(e.value)) throw NetlistError(card.at(gain), "the gain of " + quote(r.name) + " must be finite");
  if (card.size() > gain + 1) r.extra(gain + 1);
}

// S n+ n- nc+ nc- model [ON|OFF] and W n+ n- vname model [ON|OFF]: ngspice's ideal switches.
void parse_switch(const Card& card, const Reader& r, char letter, ParsedElement& out) {
  Element& e = out.element;
  e.kind = letter == 's' ? ElementKind::VSwitch : ElementKind::CSwitch;
  r.node(1, e);
  r.node(2, e);
  r.distinct_nodes(e);
  const std::size_t model = read_control(card, r, letter == 's', out);
  if (card.size() <= model) throw NetlistError(card.after_last(), "missing model name for " + quote(r.name));
  if (!card[model].is_word()) throw NetlistError(card.at(model), "expected a model name, got " + quote(card[model].text));
  e.model = card[model].lower;
  out.model_token = model;
  if (card.size() > model + 1) {
    const Token& state = card[model + 1];
    if (state.is_word("on")) e.initially_on = true;
    else if (state.is_word("off")) e.initially_on = false;
    else r.extra(model + 1);
    if (card.size() > model + 2) r.extra(model + 2);
  }
}

}  // namespace

bool is_ground(const std::string& n) { return n == "0" || n == "gnd"; }

ParsedElement parse_element(const Card& card, const ElementScope& scope,
                            std::vector<std::string>& warnings) {
  const Token& head = card[0];
  if (!head.is_word()) throw NetlistError(card.at(head), "expected an element or a control card, got " + quote(head.text));
  ParsedElement out;
  Element& e = out.element;
  e.name = scope.prefix + head.lower;
  e.loc = card.at(head);
  Reader r{card, scope, e.name, &warnings};
  const char letter = head.lower[0];
  switch (letter) {
    case 'r':
    case 'l':
    case 'c': {
      e.kind = letter == 'r' ? ElementKind::Resistor : letter == 'l' ? ElementKind::Inductor : ElementKind::Capacitor;
      r.node(1, e);
      r.node(2, e);
      if (letter == 'l') r.distinct_nodes(e, "the current of an inductor shorted by itself is not set by the circuit");
      out.shorted = e.nodes[0] == e.nodes[1];
      const char* what = letter == 'r' ? "resistance" : letter == 'l' ? "inductance" : "capacitance";
      // ngspice and LTspice also take the value as a keyword: R1 a b r=1k (resistance=),
      // C1 b 0 c=1u (capacitance=), L1 b c l=1m (inductance=).
      std::size_t at = 3;
      if (at + 1 < card.size() && card[at + 1].is(Token::Kind::Equals) &&
          (card[at].lower == std::string(1, letter) || card[at].is_word(what)) && card[at].is_word())
        at += 2;
      e.value = r.value(at);
      r.positive(at, e.value, what);
      InstanceParasitics parasitics;
      const double m = r.trailing(at + 1, e, letter != 'r', letter == 'r' ? nullptr : &parasitics);
      scale_for_parallel_copies(e, m);
      if (parasitics.any() && !out.shorted) out.parasitics = expand_parasitics(e, parasitics, m);
      break;
    }
    case 'k': {
      e.kind = ElementKind::Coupling;
      // K L1 L2 k (ngspice); LTspice also takes K L1 L2 L3 ... k: every pair coupled by k, the
      // pairs after the first as elements of their own named K#2, K#3, ... The last token is k.
      std::vector<std::size_t> names;
      for (std::size_t i = 1; i + 1 < card.size(); ++i) {
        if (!card[i].is_word()) throw NetlistError(card.at(i), "expected an inductor name, got " + quote(card[i].text));
        names.push_back(i);
      }
      if (names.size() < 2) {
        // Fewer than three tokens after K: a number last is the coefficient (an inductor name
        // is missing), a name last is the second inductor (the coefficient is missing).
        const std::size_t last = card.size() - 1;
        if (card.size() == 3 && !starts_with_digit(card[last]) && card[last].is_word())
          throw NetlistError(card.after_last(), "missing coupling coefficient for " + quote(e.name));
        if (card.size() > 1 && !card[1].is_word() && !starts_with_digit(card[1]))
          throw NetlistError(card.at(1), "expected an inductor name, got " + quote(card[1].text));
        throw NetlistError(card.size() > 2 ? card.at(last) : card.after_last(),
                           "missing inductor name for " + quote(e.name) + " (K takes two or more inductors and k)");
      }
      for (std::size_t a = 0; a < names.size(); ++a)
        for (std::size_t b = 0; b < a; ++b)
          if (card[names[a]].lower == card[names[b]].lower)
            throw NetlistError(card.at(names[a]), quote(e.name) + " couples " + quote(card[names[a]].lower) +
                                                      (names.size() == 2 ? " with itself" : " twice"));
      const std::size_t value_token = names.back() + 1;
      e.value = r.value(value_token);
      // ngspice: -1 <= k <= 1 (a negative k: the windings' fluxes oppose, M = k sqrt(L1 L2) < 0).
      if (!(e.value >= -1 && e.value <= 1))
        throw NetlistError(card.at(value_token), "coupling coefficient of " + quote(e.name) + " must be in [-1, 1]");
      int serial = 1;
      for (std::size_t a = 0; a < names.size(); ++a)
        for (std::size_t b = a + 1; b < names.size(); ++b) {
          Element k = e;
          k.coupled = {scope.prefix + card[names[a]].lower, scope.prefix + card[names[b]].lower};
          if (serial++ == 1) {
            e = k;
            out.coupled_tokens[0] = names[a];
            out.coupled_tokens[1] = names[b];
          } else {
            k.name = e.name + "#" + std::to_string(serial - 1);
            out.parasitics.push_back(k);
            out.extra_coupled_tokens.push_back({names[a], names[b]});
          }
        }
      break;
    }
    case 'v':
    case 'i': {
      e.kind = letter == 'v' ? ElementKind::VoltageSource : ElementKind::CurrentSource;
      r.node(1, e);
      r.node(2, e);
      r.distinct_nodes(e, letter == 'v' ? "a voltage source cannot hold a voltage across a short" : nullptr);
      double m = 1.0;
      InstanceParasitics parasitics;
      e.waveform = parse_source_waveform(card, 3, *scope.params, e.name, warnings, letter == 'i' ? &m : nullptr,
                                         letter == 'v' ? &parasitics : nullptr);
      scale_for_parallel_copies(e, m);
      if (parasitics.any()) out.parasitics = expand_parasitics(e, parasitics, 1.0);
      break;
    }
    case 'd': {
      e.kind = ElementKind::Diode;
      r.node(1, e);
      r.node(2, e);
      out.shorted = e.nodes[0] == e.nodes[1];
      if (card.size() == 3) break;  // LTspice's default diode: the elaborator gives it the ideal law
      if (!card[3].is_word()) throw NetlistError(card.at(3), "expected a model name, got " + quote(card[3].text));
      e.model = card[3].lower;
      out.model_token = 3;
      diode_instance_params(card, r, 4, e);
      break;
    }
    case 'q':
      parse_bjt(card, r, scope, out, warnings);
      break;
    case 't':
      parse_lossless_line(card, r, e);
      break;
    case 'o':
      parse_lossy_line(card, r, out);
      break;
    case 'e':
    case 'f':
    case 'g':
    case 'h':
      parse_controlled_source(card, r, letter, out);
      break;
    case 's':
    case 'w':
      parse_switch(card, r, letter, out);
      break;
    default:
      throw NetlistError(card.at(head), "unknown element type " + quote(std::string(1, letter)));
  }
  out.temperature_coefficient_token = r.temperature_coefficient;
  return out;
}

}  // namespace lcs::parse
