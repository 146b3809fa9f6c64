// Turns the caller's deck into the exact line array handed to ngSpice_Circ. Internal to the bridge.
//
// ngSpice_Circ feeds each line to ngspice's line collector, which skips blank lines, strips
// leading blanks, and starts parsing when it sees a `.end` card. The collector is global state, so
// a deck must reach it in one piece and end at its `.end`: a missing `.end` leaves lines behind,
// lines after `.end` start another circuit, a blank title makes the first element the title, and a
// `.control` block is executed synchronously inside ngSpice_Circ (no time limit; `quit` there
// tears ngspice down for the rest of the process). This file removes those traps.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace lcs::ngspice_deck {

struct PreparedDeck {
  std::vector<std::string> lines;  // title first, `.end` last; valid when error is empty
  std::string error;               // why the deck cannot be sent (then nothing is sent)
};

// - entries are split at embedded newlines ('\r' before '\n' dropped), so one string per deck works;
// - an empty deck is an error; a blank title, or a title that ngspice would read as `.end`, is
//   replaced by "untitled";
// - a `.control` ... `.endc` block is an error (the bridge runs the deck's `.tran` itself);
// - everything after the first `.end` card is dropped, and `.end` is appended when missing.
PreparedDeck prepare(const std::vector<std::string>& deck);

// The `.end` card exactly as ngspice's collector detects it: leading blanks, then `.end`
// (any case), then end of line or a blank. `.ends`/`.endc`/`.endl` are not `.end`.
bool is_end_card(std::string_view line);

}  // namespace lcs::ngspice_deck
