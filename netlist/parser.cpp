// Entry points of the netlist reader: read (with includes), split into subcircuit definitions,
// elaborate into the flat Netlist.
#include "netlist/conditionals.h"
#include "netlist/deck_reader.h"
#include "netlist/elaborate.h"
#include "netlist/netlist.h"
#include "netlist/out_of_scope.h"
#include "netlist/subcircuit.h"
#include "netlist/transient_choice.h"

namespace lcs {

Netlist parse_netlist_string(const std::string& text, const std::string& file_name, const ReadOptions& options) {
  Netlist netlist;
  netlist.file = file_name;
  parse::SourceFilePtr file = parse::make_source_file(file_name, text);
  parse::Deck deck = parse::read_deck(file, netlist.warnings);
  netlist.title = deck.title;
  deck.cards = parse::resolve_conditionals(std::move(deck.cards));
  const parse::Card* control_tran = parse::choose_transient(deck, options.require_transient, netlist.warnings);
  std::unique_ptr<parse::SubcktDef> top = parse::build_definitions(deck.cards, netlist.warnings);
  parse::refuse_out_of_scope_elements(*top);
  try {
    parse::elaborate(*top, netlist, control_tran);
  } catch (const parse::UndefinedNameError& e) {
    // What is missing was most likely in the library that could not be opened: the error is that
    // library's, at its `.lib` line (issue 13: not a derived "not defined").
    if (deck.unopened_libraries.empty()) throw;
    const NetlistError& lib = deck.unopened_libraries.front();
    const SourceLocation& at = e.location();
    throw NetlistError(lib.location(), lib.message() + "; the deck needs it: " + e.message() + " (" + at.file + ":" +
                                           std::to_string(at.line) + ":" + std::to_string(at.column) + ")");
  }
  return netlist;
}

Netlist parse_netlist_file(const std::string& path, const ReadOptions& options) {
  std::string text;
  if (!parse::read_file(path, text, false)) throw FileError("cannot open netlist file '" + path + "'");
  return parse_netlist_string(text, path, options);
}

}  // namespace lcs
