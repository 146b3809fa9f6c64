// What ngspice decks use that lcspice does not simulate (it simulates ideal diodes and bipolar
// transistors): element cards, model types, behavioural expressions, thermal diodes. Each comes
// with the reason printed when a deck needs it. Internal to the netlist reader.
#pragma once

#include <string>

#include "netlist/lexer.h"
#include "netlist/subcircuit.h"

namespace lcs::parse {

// What a model type ngspice (or XSPICE) knows but lcspice does not simulate is ("MOSFET",
// "CIDER numerical device", ...); "" for any other type.
std::string unsimulated_model_kind(const std::string& lower_type);

// The refusal for an element that uses a model of such a type.
std::string unsimulated_model_reason(const std::string& lower_type);

// Throws NetlistError, at the offending token, when an element card needs something outside
// lcspice's scope: a MOSFET, JFET, XSPICE `A` instance, behavioural `B` source, ...; an expression
// of node voltages or branch currents (`{ ... I(EOUT) ... }`, `VALUE=`); a thermal diode.
void refuse_out_of_scope(const Card& card);

// The same for every element card the deck can reach (the top level and the subcircuits its X
// cards name, transitively), first in deck order, before anything is elaborated: a deck that
// needs what lcspice does not simulate is told so before the errors of its parameters or models.
void refuse_out_of_scope_elements(const SubcktDef& top);

}  // namespace lcs::parse
