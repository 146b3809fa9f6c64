// ngspice's multiplier `m`: an element written once that stands for m copies in parallel, on
// an element card (`R1 a b 1k m=2`) or on a subcircuit instance (`X1 a b sub m=2`, which scales
// every element inside that takes m, nested instances multiplying, as the ngspice manual's
// "Paralleling devices with multiplier m" says).
#pragma once

#include "netlist/netlist.h"

namespace lcs::parse {

// Scales `e` into the single element equivalent to m copies in parallel: R and L divided by m,
// C, a diode's or a transistor's area and a current source's waveform multiplied by m. Kinds
// ngspice gives no multiplier (V, K, T, O) are left as they are: parallel copies of a voltage
// source are the same source, a coupling coefficient is a ratio, and ngspice leaves lines inside
// an instance with m unscaled. m > 0 (checked by the caller, at its token).
void scale_for_parallel_copies(Element& e, double m);

}  // namespace lcs::parse
