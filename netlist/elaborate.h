// Expands the top level and every X instance into the flat Netlist (parameters, models, elements,
// control cards), then resolves diode models and inductor couplings, checks probes and `.ic` nodes
// against the circuit, and resolves source waveforms. Internal to the netlist reader.
#pragma once

#include "netlist/netlist.h"
#include "netlist/subcircuit.h"

namespace lcs::parse {

// A model or subcircuit a card names that the deck does not define (a library the deck could not
// open may have: parser.cpp then reports the library).
class UndefinedNameError : public NetlistError {
 public:
  using NetlistError::NetlistError;
};

// Fills everything but `file` and `title` (a `.title` card does set `title`). `control_tran`, when
// not null, is the `.control` block's `tran` command, read like a `.tran` card. Throws NetlistError.
void elaborate(const SubcktDef& top, Netlist& netlist, const Card* control_tran = nullptr);

}  // namespace lcs::parse
