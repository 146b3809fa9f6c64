// Sums over fundamental cutsets without forming them: for every tree branch, the sum of a weight
// over the links whose fundamental loops pass through it. A multiplier's cutsets (and loops) hold
// O(N^2) entries in all; their sizes, which formation needs to choose its path, cost O(N log N).
#pragma once

#include <vector>

#include "graph/spanning_tree.h"

namespace lcs {

class CutsetSums {
 public:
  // Finds each link's lowest common ancestor (binary lifting): O(N log N).
  CutsetSums(const CircuitGraph& graph, const SpanningTree& tree);
  // Per branch: for a tree branch, the sum of `link_weight` (indexed by branch; read at links)
  // over its fundamental cutset; 0 for a link. O(N).
  std::vector<double> sums(const std::vector<double>& link_weight) const;

 private:
  const CircuitGraph& graph_;
  const SpanningTree& tree_;
  std::vector<int> lca_;    // per link (by its position in tree.links)
  std::vector<int> order_;  // nodes by decreasing depth: children before parents
};

}  // namespace lcs
