#include "netlist/subcircuit.h"

#include <optional>

#include "netlist/control_cards.h"
#include "netlist/element_card.h"
#include "netlist/param_scope.h"

namespace lcs::parse {
namespace {

constexpr std::size_t kMaxDefinitionNesting = 100;

// "line 12", or "other.cir:12" when the first one is in another file.
std::string where(const SourceLocation& first, const SourceLocation& here) {
  if (first.file != here.file) return first.file + ":" + std::to_string(first.line);
  return "line " + std::to_string(first.line);
}

std::unique_ptr<SubcktDef> parse_header(const Card& card, std::vector<std::string>& warnings) {
  auto def = std::make_unique<SubcktDef>();
  def->card = &card;
  const std::size_t n = card.size();
  if (n < 2) throw NetlistError(card.after_last(), "missing subcircuit name after " + quote(card[0].text));
  if (!card[1].is_word()) throw NetlistError(card.at(1), "expected a subcircuit name, got " + quote(card[1].text));
  def->name = card[1].lower;
  std::size_t i = 2;
  for (; i < n; ++i) {
    const Token& t = card[i];
    if (t.is_word("params:")) {
      ++i;
      break;
    }
    if (t.is_word() && i + 1 < n && card[i + 1].is(Token::Kind::Equals)) break;
    if (!t.is_word()) throw NetlistError(card.at(t), "expected a port name, got " + quote(t.text));
    if (is_ground(t.lower))  // as ngspice: the port is ground inside; the node connected there is not joined to it
      warnings.push_back(warning_line(card.at(t), "port " + quote(t.lower) + " of subcircuit " + quote(def->name) +
                                                      " is ground: inside it is node '0', whatever an instance "
                                                      "connects there"));
    for (const std::string& p : def->ports)
      if (p == t.lower)
        throw NetlistError(card.at(t), "duplicate port " + quote(t.lower) + " in subcircuit " + quote(def->name));
    def->ports.push_back(t.lower);
  }
  for (const Assignment& a : split_assignments(card, i, n, false, true)) {
    const Token& name = card[a.name];
    if (!is_identifier(name.lower)) throw NetlistError(card.at(name), "invalid parameter name " + quote(name.text));
    if (def->param(name.lower))
      throw NetlistError(card.at(name), "duplicate parameter " + quote(name.lower) + " in subcircuit " + quote(def->name));
    def->params.push_back({name.lower, a.name, a.value_first, a.value_last});
  }
  return def;
}

}  // namespace

const SubcktDef* SubcktDef::find(const std::string& wanted) const {
  for (const SubcktDef* d = this; d; d = d->parent) {
    auto it = d->children.find(wanted);
    if (it != d->children.end()) return it->second.get();
  }
  return nullptr;
}

const SubcktDef::Param* SubcktDef::param(const std::string& wanted) const {
  for (const Param& p : params)
    if (p.name == wanted) return &p;
  return nullptr;
}

std::unique_ptr<SubcktDef> build_definitions(const std::vector<Card>& cards, std::vector<std::string>& warnings) {
  auto top = std::make_unique<SubcktDef>();
  std::vector<SubcktDef*> open = {top.get()};
  std::optional<NetlistError> misplaced;  // the first control card found inside a definition
  for (const Card& card : cards) {
    const std::string keyword = card[0].is_word() ? card.keyword() : std::string();
    if (keyword == ".subckt") {
      if (open.size() > kMaxDefinitionNesting)
        throw NetlistError(card.at(0), "subcircuit definitions nested too deeply");
      std::unique_ptr<SubcktDef> def = parse_header(card, warnings);
      SubcktDef* parent = open.back();
      auto it = parent->children.find(def->name);
      if (it != parent->children.end())
        throw NetlistError(card.at(1), "subcircuit " + quote(def->name) + " is already defined at " +
                                           where(it->second->card->at(1), card.at(1)));
      def->parent = parent;
      SubcktDef* raw = def.get();
      parent->children[def->name] = std::move(def);
      open.push_back(raw);
      continue;
    }
    if (keyword == ".ends") {
      if (open.size() == 1) throw NetlistError(card.at(0), "'.ends' without '.subckt'");
      const SubcktDef* current = open.back();
      if (card.size() > 1 && card[1].lower != current->name)
        throw NetlistError(card.at(1), "'.ends " + card[1].lower + "' does not match '.subckt " + current->name + "'");
      if (card.size() > 2) throw NetlistError(card.at(2), "unexpected extra token " + quote(card[2].text));
      open.pop_back();
      continue;
    }
    if (open.size() > 1 && !keyword.empty() && keyword[0] == '.' && !misplaced) {
      DotCard kind = classify_dot_card(keyword);
      if (kind == DotCard::Unknown)
        misplaced = NetlistError(card.at(0), "unknown control card " + quote(card[0].text));
      else if (!allowed_in_subcircuit(kind))
        misplaced = NetlistError(card.at(0), quote(card[0].lower) + " is not allowed inside a subcircuit");
    }
    open.back()->body.push_back(&card);
  }
  // A forgotten .ends is the likelier cause of control cards inside a definition: report it first.
  if (open.size() > 1)
    throw NetlistError(open.back()->card->at(0), "missing '.ends' for subcircuit " + quote(open.back()->name));
  if (misplaced) throw *misplaced;
  return top;
}

}  // namespace lcs::parse
