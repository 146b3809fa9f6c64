// Topology checks: circuits that have no solution or no unique one are rejected before any
// simulation, naming every element involved (SPEC §4, exit code 2).
#pragma once

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "graph/circuit_graph.h"
#include "graph/spanning_tree.h"

namespace lcs {

class TopologyError : public std::runtime_error {
 public:
  TopologyError(std::string message, std::vector<int> elements)
      : std::runtime_error(message), message_(std::move(message)), elements_(std::move(elements)) {}
  const std::string& message() const { return message_; }
  const std::vector<int>& elements() const { return elements_; }  // indices into Netlist::elements
  // "FILE: error: message", then a note with line and caret for each element involved.
  std::string formatted(const Netlist& netlist) const;

 private:
  std::string message_;
  std::vector<int> elements_;
};

// Every node reaches ground through some element. Throws naming the floating nodes' elements.
void check_connected(const Netlist& netlist, const CircuitGraph& graph);

// Voltage-source loops (a V link) and current-source cutsets (an I tree branch).
void check_source_loops_and_cutsets(const Netlist& netlist, const CircuitGraph& graph,
                                    const SpanningTree& tree);

struct IdealDiodeLaw {  // 0 <= i  ⟂  von + ron*i - v >= 0
  double von = 0, ron = 0;
};

// Loops with no impedance through ideal diodes (ron = 0), assumption (5.40): a loop of ideal
// diodes and voltage sources in which current could circulate in every diode's forward
// direction, and whose sources can overcome the diodes' summed thresholds VON at some time in
// [t0, t1]:
//  - with other diodes in the loop the loop current is undefined (Figure 5.4);
//  - with only sources, the diode is forward-biased by them directly: no solution (Figure 5.5).
// Loops blocked by a diode's orientation (bridge rectifiers) or by thresholds (anti-parallel
// clamps with VON > 0, a supply that keeps a diode reverse-biased) are accepted.
// `law` is indexed by branch (entries of non-diode branches are ignored).
// Called by check_ideal_diode_loops: RON = 0 diodes in parallel with equal VON (their currents
// are not unique). Throws TopologyError.
void check_balanced_ideal_diode_loops(const Netlist& netlist, const CircuitGraph& graph,
                                      const std::vector<IdealDiodeLaw>& law);
void check_ideal_diode_loops(const Netlist& netlist, const CircuitGraph& graph,
                             const std::vector<IdealDiodeLaw>& law, double t0, double t1);

// Names joined as "d1, d2 and v1" for messages.
std::string join_names(const std::vector<std::string>& names);

}  // namespace lcs
