// Classification of diodes by the paths through H between their nodes (Stewart 5.4.4):
// C diode: a path of capacitors only; R diode: else a path without inductors; L diode: neither.
// Voltage sources count as part of every such path (they add no impedance).
#pragma once

#include <vector>

#include "graph/circuit_graph.h"

namespace lcs {

struct DiodeClass {
  int branch = -1;
  char cls = 'L';                  // 'C', 'R' or 'L'
  bool joins_h_components = false; // its nodes lie in different components of H (5.4.6)
};

std::vector<DiodeClass> classify_diodes(const CircuitGraph& graph);

}  // namespace lcs
