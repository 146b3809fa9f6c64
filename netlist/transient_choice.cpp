#include "netlist/transient_choice.h"

#include <algorithm>

namespace lcs::parse {
namespace {

const char* const kOtherAnalyses[] = {"op", "dc", "ac", "noise", "tf", "pz", "disto", "sens", "pss", "sp"};

bool is_other_analysis(const std::string& lower_name) {
  return std::any_of(std::begin(kOtherAnalyses), std::end(kOtherAnalyses),
                     [&](const char* a) { return lower_name == a; });
}

}  // namespace

const Card* choose_transient(const Deck& deck, bool required, std::vector<std::string>& warnings) {
  const bool has_tran_card =
      std::any_of(deck.cards.begin(), deck.cards.end(), [](const Card& c) { return c[0].is_word(".tran") || c[0].is_word(".tran/op"); });
  const Card* chosen = nullptr;
  std::vector<std::string> ignored;  // distinct command names, in order
  for (const ControlBlock& block : deck.controls)
    for (const ControlCommand& command : block.commands) {
      if (!has_tran_card && !chosen && command.name == "tran") {
        chosen = &command.card;
        continue;
      }
      if (std::find(ignored.begin(), ignored.end(), command.name) == ignored.end()) ignored.push_back(command.name);
    }
  if (!deck.controls.empty()) {
    std::string list;
    for (const std::string& name : ignored) list += (list.empty() ? "'" : ", '") + name + "'";
    std::string what = has_tran_card ? "'.control' block is not run (the deck's '.tran' card is)"
                       : chosen       ? "'.control' block: its 'tran' command is run"
                                      : "'.control' block is not run";
    if (!list.empty()) what += std::string(chosen ? "; ignored: " : "; its commands: ") + list;
    warnings.push_back(warning_line(deck.controls.front().loc, what));
  }
  if (has_tran_card || chosen || !required) return chosen;

  // No transient analysis: name what the deck asks for instead, where it asks for it.
  const std::string refusal = "the deck has no transient analysis (no '.tran' card and no 'tran' command in "
                              "'.control'; lcspice runs transient analyses only): ";
  for (const Card& card : deck.cards) {
    const std::string& k = card.keyword();
    if (card[0].is_word() && k.size() > 1 && k[0] == '.' && is_other_analysis(k.substr(1)))
      throw NetlistError(card.at(0), refusal + "it asks for " + quote(k));
  }
  for (const ControlBlock& block : deck.controls)
    for (const ControlCommand& command : block.commands)
      if (is_other_analysis(command.name))
        throw NetlistError(command.loc, refusal + "the '.control' block runs " + quote(command.name));
  return nullptr;  // no analysis at all: the caller's own message (nothing to simulate)
}

}  // namespace lcs::parse
