// The law of one complementarity pair, as its device states it (Stewart 5.4):
// the ideal law 0 <= i ⟂ VON + RON i - v >= 0, and the smooth junction the smooth method (8.2)
// integrates in its place, i = IS (exp(m / (N Vt)) - 1) with m the voltage the ideal law calls
// the margin's complement (shockley_dae.h).
#pragma once

#include <string>

#include "graph/topology.h"

namespace lcs {

// Thermal voltage kT/q at ngspice's nominal 27 °C (300.15 K), with the constants ngspice 39 uses
// (CODATA 2014: k = 1.38064852e-23 J/K, q = 1.6021766208e-19 C). Measured: a diode with IS = 1e-14
// at 1 mA in ngspice 39 sits at 0.6551178957 V = 0.0258649170 ln(1 + 1e11). The SPICE3 constants
// (1.3806226e-23, 1.6021918e-19: 0.025864186) put every junction 2.8e-5 of its voltage lower, 23 uV
// at 0.8 V: in rca3040 v(13)'s offset from ngspice's operating point, 3.6 % of that node's range.
constexpr double kThermalVoltage = 1.38064852e-23 * 300.15 / 1.6021766208e-19;

struct SmoothJunction {
  double is = 1e-14;  // saturation current [A]
  double n = 1.0;     // emission coefficient
};

struct PairLaw {
  std::string name;     // the device's name, for messages ("d1", "x1.d3")
  int element = -1;     // index into Netlist::elements
  IdealDiodeLaw law;    // VON [V], RON [ohm]
  bool fitted = false;  // VON/RON fitted to the card's Shockley curve
  // The fit (when `fitted`): the current range [A] and the line's worst voltage error over it
  // [V, and as a fraction of the junction's voltage at fit_i1]; circuit_fit: the range is the
  // one this circuit's run carried (diode_refit.h), not the `.options ifit` decade pair.
  double fit_i1 = 0, fit_i2 = 0, fit_error = 0, fit_error_fraction = 0;
  bool circuit_fit = false;
  SmoothJunction smooth;
  // A transistor junction: its current drives a transfer source, which couples the pairs
  // non-symmetrically; only such circuits can have several operating points (5.4.7).
  bool transfer = false;
};

}  // namespace lcs
