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
      throw NetlistError(card.at(head), "bipolar transistors (Q cards) are not supported yet");
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
