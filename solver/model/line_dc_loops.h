// At DC a line without series resistance (a lossless T line, an LTRA line with R = 0) is a
// through connection, v(p1+) - v(p1-) = v(p2+) - v(p2-) with i1 = -i2, so voltage sources joined
// through it, or a line whose two ports close a loop by themselves, leave the operating point
// without a solution or with a current it cannot determine. Not an error with UIC (the run starts
// from rest and the line decouples its ports for a delay), so checked only where the operating
// point is needed.
#pragma once

#include "graph/topology.h"
#include "netlist/netlist.h"

namespace lcs {

// Throws TopologyError naming the line(s) and voltage sources of the first such loop.
void check_line_dc_loops(const Netlist& netlist);

}  // namespace lcs
