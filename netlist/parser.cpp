// Entry points of the netlist reader: read (with includes), split into subcircuit definitions,
// elaborate into the flat Netlist.
#include "netlist/deck_reader.h"
#include "netlist/elaborate.h"
#include "netlist/netlist.h"
#include "netlist/subcircuit.h"

namespace lcs {

Netlist parse_netlist_string(const std::string& text, const std::string& file_name) {
  Netlist netlist;
  netlist.file = file_name;
  parse::SourceFilePtr file = parse::make_source_file(file_name, text);
  parse::Deck deck = parse::read_deck(file, netlist.warnings);
  netlist.title = deck.title;
  std::unique_ptr<parse::SubcktDef> top = parse::build_definitions(deck.cards);
  parse::elaborate(*top, netlist);
  return netlist;
}

Netlist parse_netlist_file(const std::string& path) {
  std::string text;
  if (!parse::read_file(path, text, false)) throw FileError("cannot open netlist file '" + path + "'");
  return parse_netlist_string(text, path);
}

}  // namespace lcs
