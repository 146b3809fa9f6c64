// The waveform part of V and I cards: `[DC] value`, `SIN(...)` (or `SINE`), `PULSE(...)`,
// `PWL(...)`, `EXP(...)`, `SFFM(...)`, `AM(...)` (with or
// without a space before the parenthesis, or without parentheses), `DC x` together with a
// transient function, and `AC mag [phase]` (accepted, ignored with a warning).
// Internal to the netlist reader.
#pragma once

#include <string>
#include <vector>

#include "netlist/instance_parasitics.h"
#include "netlist/lexer.h"
#include "netlist/param_scope.h"
#include "netlist/waveform.h"

namespace lcs::parse {

// Reads the tokens from `first` to the end of the card. `name` is the element's (flat) name for
// messages. The result is not resolved yet (that needs .tran). `m=value` (a current source's
// multiplier) is read into *multiplier; without one (a voltage source) it is an error. A voltage
// source's LTspice parasitics (Rser=, Cpar=) are read into *parasitics when it is given.
Waveform parse_source_waveform(const Card& card, std::size_t first, const ParamScope& scope,
                               const std::string& name, std::vector<std::string>& warnings,
                               double* multiplier = nullptr, InstanceParasitics* parasitics = nullptr);

// LTspice's instance parasitics on an element that does not take the one written (Lser on an
// inductor, Rser on a resistor): the remedy to append to the unknown-parameter error, or "" for
// another name.
std::string ltspice_parasitic_hint(const std::string& lower_key);

}  // namespace lcs::parse
