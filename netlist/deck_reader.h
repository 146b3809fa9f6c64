// Reads a netlist file (or string) into its title and cards, expanding `.include` files in place.
// Internal to the netlist reader.
#pragma once

#include <string>
#include <vector>

#include "netlist/lexer.h"

namespace lcs::parse {

struct Deck {
  std::string title;        // first line of the top-level file, as written
  std::vector<Card> cards;  // every card up to `.end`, included files and library sections spliced in
  std::vector<ControlBlock> controls;  // `.control` blocks, in deck order
  // LTspice's `.lib FILE` includes whose FILE could not be opened (an LTspice install's
  // `standard.dio` beside a deck that defines its own models): each kept as the error it would
  // have been, reported if the deck uses a model or subcircuit it does not define.
  std::vector<NetlistError> unopened_libraries;
};

// `top` is the top-level file (its first line is the title). An included file has no title line,
// and is found relative to the directory of the file that includes it; so is the FILE of
// `.lib FILE SECTION`, whose section (`.lib SECTION` ... `.endl`) is spliced in. Throws NetlistError
// for an unreadable include or library file (but LTspice's `.lib FILE`: a warning, and the error
// kept in `unopened_libraries`), a missing section, or a cycle.
Deck read_deck(const SourceFilePtr& top, std::vector<std::string>& warnings);

// Reads a whole file; false when it cannot be opened, is a directory, is larger than 256 MiB, or
// (with `regular_only`) is not a regular file.
bool read_file(const std::string& path, std::string& text, bool regular_only);

}  // namespace lcs::parse
