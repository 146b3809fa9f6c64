#include "netlist/part_attributes.h"

namespace lcs::parse {
namespace {

bool is_part_attribute(ElementKind kind, const std::string& k) {
  if (k == "mfg" || k == "pn" || k == "type") return true;
  switch (kind) {
    case ElementKind::Resistor: return k == "tol" || k == "pwr";
    case ElementKind::Inductor: return k == "ipk" || k == "irms";
    case ElementKind::Capacitor: return k == "v" || k == "irms";
    default: return false;
  }
}

}  // namespace

std::size_t skip_part_attribute(const Card& card, std::size_t i, ElementKind kind, std::vector<std::string>& skipped) {
  const Token& t = card[i];
  if (!t.is_word() || i + 2 >= card.size() || !card[i + 1].is(Token::Kind::Equals) ||
      !is_part_attribute(kind, t.lower))
    return i;
  const Token& value = card[i + 2];
  if (!(value.is_word() || value.is(Token::Kind::Quoted) || value.is(Token::Kind::Braced))) return i;
  skipped.push_back(t.text);
  return i + 3;
}

std::string part_attributes_warning(const std::string& name, const std::vector<std::string>& skipped) {
  if (skipped.empty()) return "";
  std::string list;
  for (const std::string& s : skipped) list += (list.empty() ? "" : ", ") + s;
  return "'" + name + "': LTspice part attribute" + (skipped.size() > 1 ? "s " : " ") + list +
         " ignored (ratings and part data: they do not change the simulation)";
}

}  // namespace lcs::parse
