// Normal spanning tree and fundamental loops (Stewart 5.4.1, eq. 5.34).
#pragma once

#include <vector>

#include "graph/circuit_graph.h"

namespace lcs {

struct LoopTerm {
  int branch = -1;
  int sign = 0;  // +1: traversed n+ -> n- along the loop; -1: against it
};

struct SpanningTree {
  std::vector<bool> in_tree;   // per branch
  std::vector<int> tree;       // tree branches, in branch order
  std::vector<int> links;      // link (co-tree) branches, in branch order
  std::vector<int> position;   // branch -> its index in `tree` or in `links`
  // Per node: the tree branch to its parent on the way to ground (ground: branch -1), so that
  // v(node) = v(parent) + sign * v_branch. (The whole path per node cost O(nodes x depth): a
  // multiplier's tree is a chain.)
  std::vector<LoopTerm> to_parent;
  std::vector<int> parent;  // per node; -1 for ground
  std::vector<int> depth;   // per node; ground 0
  // Per node: its subtree is the nodes whose `enter` lies in [enter, leave) (a preorder), and
  // preorder[k] is the node entered k-th.
  std::vector<int> enter, leave, preorder;
  std::vector<std::vector<int>> node_links;  // per node: the links at it, in branch order
  // The fundamental loops (B's columns) are not kept: a multiplier's hold O(N^2) entries, and a
  // formation that needs a few of them reads them below.
};

// Kruskal (Boost.Graph) with weights V < C < R < D < L < I, ties broken by card order: a normal
// tree (DESIGN.md). Requires a connected graph (check_floating_nodes first). By the cycle
// property of minimum spanning trees, the loop of a link holds only tree branches no heavier
// than the link, and the cutset of a tree branch only links no lighter than it; the model
// builder relies on this.
SpanningTree build_normal_tree(const CircuitGraph& graph);

// The fundamental loop of link `link` (Stewart 5.4.1): the link itself first with sign +1, then
// the tree path back from its n- to its n+. The tree path's signs are b_{f,e} of (5.34) (KCL:
// i_tree = B i_link; KVL: v_link = -B^T v_tree). O(its length).
std::vector<LoopTerm> fundamental_loop(const CircuitGraph& graph, const SpanningTree& tree, int link);

// Every link's fundamental loop, in link order: O(total loop length), O(N^2) for a multiplier.
std::vector<std::vector<LoopTerm>> fundamental_loops(const CircuitGraph& graph, const SpanningTree& tree);

// The fundamental cutset of tree branch `tree_branch`: the links whose loops pass through it
// (one end in the subtree below it), each with b_{f,l} (i_f = sum of b_{f,l} i_l), in link
// order. Found from the smaller side of the cut: O(its nodes and their links), O(1) for a
// branch with one node below it.
std::vector<LoopTerm> fundamental_cutset(const CircuitGraph& graph, const SpanningTree& tree, int tree_branch);

}  // namespace lcs
