#include "netlist/conditionals.h"

#include <algorithm>
#include <string>

#include "netlist/param_scope.h"

namespace lcs::parse {
namespace {

struct Branch {
  const Card* if_card;
  bool taken = false;     // some branch of this .if has been (or is being) taken
  bool active = false;    // the current branch is taken
  bool seen_else = false;
};

bool all_active(const std::vector<Branch>& open) {
  for (const Branch& b : open)
    if (!b.active) return false;
  return true;
}

bool condition(const Card& card, const ParamScope& scope) {
  if (card.size() < 2) throw NetlistError(card.after_last(), "missing condition after " + quote(card[0].lower));
  return evaluate_at(card, card[1].begin, card.tokens.back().end, scope) != 0.0;
}

void define_params(const Card& card, ParamScope& scope) {
  for (const Assignment& a : split_assignments(card, 1, card.size(), false, true)) {
    const Token& first = card[a.value_first];
    if (a.value_last - a.value_first == 1 && first.is_expression())
      scope.define(card[a.name].lower, &card, first.begin + 1, first.end - 1);
    else
      scope.define(card[a.name].lower, &card, first.begin, card[a.value_last - 1].end);
  }
}

}  // namespace

std::vector<Card> resolve_conditionals(std::vector<Card> cards) {
  const auto is_conditional = [](const Card& c) {
    return c[0].is_word(".if") || c[0].is_word(".elseif") || c[0].is_word(".else") || c[0].is_word(".endif");
  };
  if (std::none_of(cards.begin(), cards.end(), is_conditional)) return cards;
  ParamScope scope;
  std::vector<Branch> open;
  std::vector<std::size_t> kept;
  int subckt_depth = 0;
  for (std::size_t k = 0; k < cards.size(); ++k) {
    const Card& card = cards[k];
    const std::string keyword = card[0].is_word() ? card.keyword() : std::string();
    if (keyword == ".if") {
      Branch b{&card};
      if (all_active(open)) b.taken = b.active = condition(card, scope);
      open.push_back(b);
      continue;
    }
    if (keyword == ".elseif" || keyword == ".else" || keyword == ".endif") {
      if (open.empty()) throw NetlistError(card.at(0), quote(keyword) + " without '.if'");
      if (keyword == ".endif") {
        open.pop_back();
        continue;
      }
      Branch& top = open.back();
      if (top.seen_else) throw NetlistError(card.at(0), quote(keyword) + " after '.else'");
      bool outer = true;  // every enclosing branch is taken
      for (std::size_t j = 0; j + 1 < open.size(); ++j) outer = outer && open[j].active;
      if (keyword == ".else") {
        if (card.size() > 1) throw NetlistError(card.at(1), "unexpected extra token " + quote(card[1].text));
        top.seen_else = true;
        top.active = outer && !top.taken;
      } else {
        top.active = outer && !top.taken && condition(card, scope);
      }
      top.taken = top.taken || top.active;
      continue;
    }
    if (!all_active(open)) continue;
    if (keyword == ".subckt") ++subckt_depth;
    if (keyword == ".ends" && subckt_depth > 0) --subckt_depth;
    if (keyword == ".param" && subckt_depth == 0) define_params(card, scope);
    if (keyword == ".func" && subckt_depth == 0) define_function(card, scope);
    kept.push_back(k);
  }
  if (!open.empty()) throw NetlistError(open.back().if_card->at(0), "missing '.endif' for '.if'");
  if (kept.size() == cards.size()) return cards;
  std::vector<Card> out;
  out.reserve(kept.size());
  for (std::size_t k : kept) out.push_back(std::move(cards[k]));
  return out;
}

}  // namespace lcs::parse
