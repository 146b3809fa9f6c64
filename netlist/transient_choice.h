// Which transient analysis a deck runs: its `.tran` card, or else the `tran` command of its
// `.control` block (SPEC §2). Internal to the netlist reader.
#pragma once

#include <string>
#include <vector>

#include "netlist/deck_reader.h"

namespace lcs::parse {

// The `tran` command to run (nullptr when the deck has a `.tran` card, or no transient analysis
// at all). Adds one warning naming the `.control` commands that are not run. With `required`, a
// deck without a transient analysis that asks for another one (an `.op`/`.dc`/`.ac`... card or a
// `dc`/`op`/... command) is refused there: lcspice runs transient analyses only.
const Card* choose_transient(const Deck& deck, bool required, std::vector<std::string>& warnings);

}  // namespace lcs::parse
