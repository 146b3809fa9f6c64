#include "netlist/instance_parasitics.h"

#include "netlist/parallel_copies.h"

namespace lcs::parse {

bool takes_parasitic(ElementKind kind, const std::string& k) {
  switch (kind) {
    case ElementKind::Inductor: return k == "rser" || k == "rpar" || k == "cpar";
    case ElementKind::Capacitor: return k == "rser" || k == "lser" || k == "rpar" || k == "cpar";
    case ElementKind::VoltageSource: return k == "rser" || k == "cpar";
    default: return false;
  }
}

std::size_t read_parasitic(const Card& card, std::size_t i, ElementKind kind, const ParamScope& scope,
                           const std::string& name, InstanceParasitics& out) {
  const Token& t = card[i];
  if (!t.is_word() || i + 1 >= card.size() || !card[i + 1].is(Token::Kind::Equals) || !takes_parasitic(kind, t.lower))
    return i;
  if (i + 2 >= card.size()) throw NetlistError(card.after_last(), "missing value for " + quote(t.text));
  const double v = value_of(card, i + 2, scope);
  if (t.lower == "rpar" ? !(v > 0) : !(v >= 0))
    throw NetlistError(card.at(i + 2), t.text + " of " + quote(name) + " must be " +
                                           (t.lower == "rpar" ? "positive" : "zero (none) or positive"));
  std::optional<double>& slot = t.lower == "rser" ? out.rser : t.lower == "lser" ? out.lser
                              : t.lower == "rpar" ? out.rpar : out.cpar;
  if (slot) throw NetlistError(card.at(t), quote(t.text) + " given twice for " + quote(name));
  slot = v;
  return i + 3;
}

std::vector<Element> expand_parasitics(Element& e, const InstanceParasitics& p, double m) {
  std::vector<Element> out;
  auto add = [&](ElementKind kind, const char* suffix, double value, const std::string& a, const std::string& b) {
    Element x;
    x.kind = kind;
    x.name = e.name + "#" + suffix;
    x.nodes = {a, b};
    x.value = value;
    x.loc = e.loc;
    scale_for_parallel_copies(x, m);
    out.push_back(std::move(x));
  };
  const std::string plus = e.nodes.at(0), minus = e.nodes.at(1);
  std::string at = plus;  // the series chain runs from the first node to the element
  if (p.rser && *p.rser > 0) {
    add(ElementKind::Resistor, "rser", *p.rser, at, e.name + "#rser");
    at = e.name + "#rser";
  }
  if (p.lser && *p.lser > 0) {
    add(ElementKind::Inductor, "lser", *p.lser, at, e.name + "#lser");
    at = e.name + "#lser";
  }
  e.nodes[0] = at;
  if (p.rpar) add(ElementKind::Resistor, "rpar", *p.rpar, plus, minus);
  if (p.cpar && *p.cpar > 0) add(ElementKind::Capacitor, "cpar", *p.cpar, plus, minus);
  return out;
}

}  // namespace lcs::parse
