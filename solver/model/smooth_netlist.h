// The circuit the smooth method (8.2) integrates: every diode card replaced by the smooth diode
// that stands in for it (solver/devices/diode.h: smooth_equivalent, the same mapping `validate` gives
// ngspice). The card's VON and RON become the series threshold and RS, so the circuit's LCS
// keeps its shape and w = VON + RS i - v of each pair is the voltage the Shockley junction
// does not take: i = IS (exp(-w / (N Vt)) - 1). IS and N stay on the card for the method.
#pragma once

#include "netlist/netlist.h"

namespace lcs {

struct SmoothingOptions {
  double emission = 0.05;             // N of the diodes standing in for ideal ones (`--emission`)
  double saturation_current = 1e-14;  // their IS
  double ifit = 10e-3;                // fit current of cards without VON/RON (`.options ifit=`)
};

// Throws NetlistError for a bad `.options` value (read_netlist_options).
Netlist smooth_netlist(const Netlist& netlist, const SmoothingOptions& options);

}  // namespace lcs
