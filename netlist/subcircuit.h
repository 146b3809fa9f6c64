// `.subckt NAME ports... [params: a=1 ...]` ... `.ends [NAME]`: the tree of subcircuit
// definitions, and the body of cards of each one (and of the top level). Internal to the netlist
// reader; expansion of `X` instances is the elaborator's.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "netlist/lexer.h"

namespace lcs::parse {

struct SubcktDef {
  std::string name;                   // lower-case; empty for the top level
  const Card* card = nullptr;         // the .subckt card (nullptr for the top level)
  std::vector<std::string> ports;     // lower-case port node names
  struct Param {
    std::string name;
    std::size_t name_token;
    std::size_t value_first, value_last;  // tokens of the default value
  };
  std::vector<Param> params;          // `params:` defaults, in order
  std::vector<const Card*> body;      // the cards inside, nested definitions taken out
  std::map<std::string, std::unique_ptr<SubcktDef>> children;  // definitions nested in this one
  const SubcktDef* parent = nullptr;

  // The definition `name` visible from inside this one: a child, or one visible from the parent.
  const SubcktDef* find(const std::string& name) const;
  const Param* param(const std::string& name) const;
};

// Splits the deck into the top level and the subcircuit definitions. Checks `.subckt` and `.ends`
// cards (names, ports, params, nesting) and rejects control cards inside a definition. A ground
// port (`gnd`, `0`, as in vendor libraries) is accepted with a warning: inside it is ground.
std::unique_ptr<SubcktDef> build_definitions(const std::vector<Card>& cards, std::vector<std::string>& warnings);

}  // namespace lcs::parse
