// ngspice's preprocessor conditionals: `.if (expr)`, `.elseif (expr)`, `.else`, `.endif`, nested.
// Internal to the netlist reader.
#pragma once

#include <vector>

#include "netlist/lexer.h"

namespace lcs::parse {

// Keeps the cards of the branches taken and drops the rest and the conditional cards themselves.
// A condition is an expression of the top-level `.param` values defined above it (in taken
// branches, outside subcircuits); nonzero is true. Throws NetlistError, located.
std::vector<Card> resolve_conditionals(std::vector<Card> cards);

}  // namespace lcs::parse
