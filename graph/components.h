// Connected components of sub-graphs of the circuit graph (Boost.Graph connected_components).
#pragma once

#include <functional>
#include <vector>

#include "graph/circuit_graph.h"

namespace lcs {

struct NodePartition {
  std::vector<int> component;  // per node
  int count = 0;
  bool same(int a, int b) const { return component[a] == component[b]; }
};

// Components of the graph on all nodes with only the branches for which `keep` is true.
NodePartition components(const CircuitGraph& graph, const std::function<bool(const Branch&)>& keep);

// H of 5.4.1/5.4.6: the circuit without its diodes and current sources.
NodePartition h_components(const CircuitGraph& graph);

}  // namespace lcs
