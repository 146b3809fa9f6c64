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
    const std::vector<NetlistError>& libs = deck.unopened_libraries;
    if (libs.empty()) throw;
    auto where = [](const SourceLocation& at, bool column) {
      return at.file + ":" + std::to_string(at.line) + (column ? ":" + std::to_string(at.column) : "");
    };
    std::string message = libs.front().message();
    for (std::size_t k = 1; k < libs.size(); ++k)
      message += (k == 1 ? "; nor " : ", nor ") + libs[k].message().substr(std::string("cannot open ").size()) +
                 " (" + where(libs[k].location(), false) + ")";
    throw NetlistError(libs.front().location(), message + (libs.size() == 1 ? "; the deck needs it: " : "; the deck needs one of them: ") +
                                                    e.message() + " (" + where(e.location(), true) + ")");
  }
  return netlist;
}

Netlist parse_netlist_file(const std::string& path, const ReadOptions& options) {
  std::string text;
  if (!parse::read_file(path, text, false)) throw FileError("cannot open netlist file '" + path + "'");
  return parse_netlist_string(text, path, options);
}

}  // namespace lcs
