// `.measure` / `.meas` cards (ngspice's `.measure tran`). Internal to the netlist reader; the
// measures are evaluated on the run's waveforms by cli/measure.h.
//
//   .meas [tran] NAME AVG|RMS|MIN|MAX|PP|INTEG|INTEGRAL|MIN_AT|MAX_AT probe [FROM=t] [TO=t]
//   .meas [tran] NAME FIND probe AT=t
//   .meas [tran] NAME FIND probe WHEN probe=value|probe2 [crossing]
//   .meas [tran] NAME WHEN probe=value|probe2 [crossing]
//   .meas [tran] NAME TRIG probe VAL=v [crossing] | TRIG AT=t   TARG probe VAL=v [crossing] | TARG AT=t
//   .meas [tran] NAME PARAM='expression' | PARAM={expression} | PARAM=expression | PARAM expression
//
// A PARAM's expression reads other measures' results and the deck's parameters and .func
// functions (a result hides a parameter of its name); the run computes it after the other
// measures, PARAMs in card order, as ngspice 39 does.
//
// crossing: RISE=n|LAST, FALL=n|LAST, CROSS=n|LAST or a bare LAST (CROSS=LAST, as ngspice reads
// it; one of them; TRIG and TARG need one),
// TD=t, FROM=t, TO=t. Values are numbers with SPICE suffixes or {expressions} of the deck's
// parameters. Without an analysis name the measure is a transient one (LTspice).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "netlist/lexer.h"
#include "netlist/netlist.h"
#include "netlist/param_scope.h"

namespace lcs::parse {

// The measure a card asks for; nullopt for one lcspice skips with a located warning in
// `warnings` (`.meas ac/dc/op ...`, DERIV, ERR, expressions of probes). Its probes are
// parsed, not yet checked against the circuit (the elaborator does that). Throws NetlistError
// for bad syntax.
std::optional<Measure> parse_measure(const Card& card, const ParamScope& scope, std::vector<std::string>& warnings);

}  // namespace lcs::parse
