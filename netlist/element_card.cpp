#include "netlist/element_card.h"

#include "netlist/source_card.h"

namespace lcs::parse {
namespace {

struct Reader {
  const Card& card;
  const ElementScope& scope;
  std::string name;  // flat name, for messages

  void node(std::size_t i, Element& e) const {
    if (i >= card.size()) throw NetlistError(card.after_last(), "missing node for " + quote(name));
    const Token& t = card[i];
    if (!t.is_word()) throw NetlistError(card.at(t), "expected a node name, got " + quote(t.text));
    e.nodes.push_back(scope.node(t.lower));
  }

  void distinct_nodes(const Element& e) const {
    if (e.nodes[0] == e.nodes[1])
      throw NetlistError(card.at(2), name + " connects node " + quote(e.nodes[0]) + " to itself");
  }

  double value(std::size_t i) const {
    if (i >= card.size()) throw NetlistError(card.after_last(), "missing value for " + quote(name));
    return value_of(card, i, *scope.params);
  }

  [[noreturn]] void extra(std::size_t i) const {
    const Token& t = card[i];
    if (t.is_word() && i + 1 < card.size() && card[i + 1].is(Token::Kind::Equals))
      throw NetlistError(card.at(t), "unknown parameter " + quote(t.text) + " for " + quote(name));
    throw NetlistError(card.at(t), "unexpected extra token " + quote(t.text));
  }

  // `IC=value` after the value of L and C.
  void optional_ic(std::size_t i, Element& e) const {
    while (i < card.size()) {
      if (card[i].is_word("ic") && i + 1 < card.size() && card[i + 1].is(Token::Kind::Equals)) {
        if (i + 2 >= card.size()) throw NetlistError(card.after_last(), "missing value for 'ic'");
        e.ic = value_of(card, i + 2, *scope.params);
        i += 3;
        continue;
      }
      extra(i);
    }
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
      warnings.push_back(warning_line(card.at(t), quote(r.name) + ": OFF is ignored (op finds every operating "
                                                  "point; .ic or .nodeset chooses one)"));
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
  Reader r{card, scope, e.name};
  const char letter = head.lower[0];
  switch (letter) {
    case 'r':
    case 'l':
    case 'c': {
      e.kind = letter == 'r' ? ElementKind::Resistor : letter == 'l' ? ElementKind::Inductor : ElementKind::Capacitor;
      r.node(1, e);
      r.node(2, e);
      r.distinct_nodes(e);
      e.value = r.value(3);
      r.positive(3, e.value, letter == 'r' ? "resistance" : letter == 'l' ? "inductance" : "capacitance");
      if (letter == 'r') {
        if (card.size() > 4) r.extra(4);
      } else {
        r.optional_ic(4, e);
      }
      break;
    }
    case 'k': {
      e.kind = ElementKind::Coupling;
      for (std::size_t i = 1; i <= 2; ++i) {
        if (i >= card.size()) throw NetlistError(card.after_last(), "missing inductor name for " + quote(e.name));
        if (!card[i].is_word()) throw NetlistError(card.at(i), "expected an inductor name, got " + quote(card[i].text));
        e.coupled.push_back(scope.prefix + card[i].lower);
        out.coupled_tokens[i - 1] = i;
      }
      if (e.coupled[0] == e.coupled[1])
        throw NetlistError(card.at(2), quote(e.name) + " couples " + quote(card[2].lower) + " with itself");
      e.value = r.value(3);
      if (!(e.value > 0 && e.value <= 1))
        throw NetlistError(card.at(3), "coupling coefficient of " + quote(e.name) + " must be in (0, 1]");
      if (card.size() > 4) r.extra(4);
      break;
    }
    case 'v':
    case 'i': {
      e.kind = letter == 'v' ? ElementKind::VoltageSource : ElementKind::CurrentSource;
      r.node(1, e);
      r.node(2, e);
      r.distinct_nodes(e);
      e.waveform = parse_source_waveform(card, 3, *scope.params, e.name, warnings);
      break;
    }
    case 'd': {
      e.kind = ElementKind::Diode;
      r.node(1, e);
      r.node(2, e);
      r.distinct_nodes(e);
      if (card.size() <= 3) throw NetlistError(card.after_last(), "missing model name for " + quote(e.name));
      if (!card[3].is_word()) throw NetlistError(card.at(3), "expected a model name, got " + quote(card[3].text));
      e.model = card[3].lower;
      out.model_token = 3;
      if (card.size() > 4) r.extra(4);
      break;
    }
    case 'q':
      parse_bjt(card, r, scope, out, warnings);
      break;
    case 't':
      throw NetlistError(card.at(head), "lossless transmission lines (T cards) are not supported yet");
    case 'o':
      throw NetlistError(card.at(head), "lossy transmission lines (O cards) are not supported yet");
    default:
      throw NetlistError(card.at(head), "unknown element type " + quote(std::string(1, letter)));
  }
  return out;
}

}  // namespace lcs::parse
