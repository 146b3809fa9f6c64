// Element cards R, L, C, K, V, I, D, Q, T, O, E, F, G, H (X instances are the subcircuit expander's). Rejects
// unknown element letters. Internal to the netlist reader.
#pragma once

#include <array>
#include <functional>
#include <string>
#include <vector>

#include "netlist/lexer.h"
#include "netlist/netlist.h"
#include "netlist/param_scope.h"

namespace lcs::parse {

// Where an element card is read: the top level or one subcircuit instance.
struct ElementScope {
  const ParamScope* params = nullptr;
  std::string prefix;                                    // "" or "x1.", prepended to names
  std::function<std::string(const std::string&)> node;   // local node name -> flat node name
  std::function<bool(const std::string&)> is_model;      // a model of this name is in scope
};

struct ParsedElement {
  Element element;         // names and nodes flat; D, Q, O: `model` still the local name as written
                           // (D without a model name: empty)
  std::size_t model_token = 0;               // D, Q, O: token of the model name
  std::size_t coupled_tokens[2] = {0, 0};    // K: tokens of the two inductor names
  // K with more than two inductors (LTspice): the other pairs' couplings are in `parasitics`
  // (named K#2, K#3, ...), their inductor names' tokens here, in the same order.
  std::vector<std::array<std::size_t, 2>> extra_coupled_tokens;
  // R, L, C: the token of a nonzero temperature coefficient (TC=, tc1=, tc2=), 0 when none. It
  // changes nothing at the nominal temperature; the elaborator warns when `.options temp=` or
  // `tnom=` sets another.
  std::size_t temperature_coefficient_token = 0;
  std::size_t control_token = 0;             // F, H: token of the controlling source's name
  // R, C, D with both terminals on one node: no current flows through it and it changes nothing.
  bool shorted = false;
  // L, C, V: LTspice's instance parasitics (Rser=, ...) as their own elements, the card's nodes
  // already moved onto them (instance_parasitics.h).
  std::vector<Element> parasitics;
};

ParsedElement parse_element(const Card& card, const ElementScope& scope,
                            std::vector<std::string>& warnings);

// "0" and "gnd" are ground.
bool is_ground(const std::string& lower_node);

}  // namespace lcs::parse
