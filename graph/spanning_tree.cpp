#include "graph/spanning_tree.h"

#include <algorithm>
#include <deque>
#include <iterator>
#include <stdexcept>
#include <utility>

#include <boost/graph/adjacency_list.hpp>
#include <boost/graph/kruskal_min_spanning_tree.hpp>

namespace lcs {

namespace {

using WeightProperty = boost::property<boost::edge_weight_t, double,
                                       boost::property<boost::edge_index_t, int>>;
using UndirectedGraph = boost::adjacency_list<boost::vecS, boost::vecS, boost::undirectedS,
                                              boost::no_property, WeightProperty>;

// Walking from node `from` to node `to` over branch b: +1 when that is b's n+ -> n- direction.
int traversal_sign(const Branch& b, int from) { return b.from == from ? +1 : -1; }

}  // namespace

SpanningTree build_normal_tree(const CircuitGraph& graph) {
  const int n_nodes = static_cast<int>(graph.nodes.size());
  const int n_branches = static_cast<int>(graph.branches.size());

  UndirectedGraph g(n_nodes);
  for (int b = 0; b < n_branches; ++b) {
    const Branch& br = graph.branches[b];
    // Class dominates; the card order breaks ties so that the tree is deterministic.
    double weight = static_cast<double>(br.cls) * 1e7 + b;
    boost::add_edge(br.from, br.to, WeightProperty(weight, b), g);
  }
  std::vector<boost::graph_traits<UndirectedGraph>::edge_descriptor> tree_edges;
  boost::kruskal_minimum_spanning_tree(g, std::back_inserter(tree_edges));
  if (static_cast<int>(tree_edges.size()) != n_nodes - 1)
    throw std::logic_error("build_normal_tree: circuit graph is not connected");

  SpanningTree t;
  t.in_tree.assign(n_branches, false);
  auto index = boost::get(boost::edge_index, g);
  for (auto e : tree_edges) t.in_tree[index[e]] = true;
  t.position.assign(n_branches, -1);
  for (int b = 0; b < n_branches; ++b) {
    auto& list = t.in_tree[b] ? t.tree : t.links;
    t.position[b] = static_cast<int>(list.size());
    list.push_back(b);
  }

  // Root the tree at ground: parent node, the branch to it, depth.
  std::vector<std::vector<int>> adjacent(n_nodes);
  for (int b : t.tree) {
    adjacent[graph.branches[b].from].push_back(b);
    adjacent[graph.branches[b].to].push_back(b);
  }
  std::vector<int> parent(n_nodes, -1), parent_branch(n_nodes, -1), depth(n_nodes, 0);
  std::vector<bool> seen(n_nodes, false);
  std::deque<int> queue{0};
  seen[0] = true;
  while (!queue.empty()) {
    int u = queue.front();
    queue.pop_front();
    for (int b : adjacent[u]) {
      const Branch& br = graph.branches[b];
      int v = br.from == u ? br.to : br.from;
      if (seen[v]) continue;
      seen[v] = true;
      parent[v] = u;
      parent_branch[v] = b;
      depth[v] = depth[u] + 1;
      queue.push_back(v);
    }
  }

  // Going down from parent[c] to c raises the potential by v(c) - v(parent[c]).
  t.to_parent.assign(n_nodes, {});
  for (int c = 1; c < n_nodes; ++c) t.to_parent[c] = {parent_branch[c], graph.branches[parent_branch[c]].from == c ? +1 : -1};
  t.parent = parent;
  t.depth = depth;

  // Preorder intervals (an iterative depth-first walk: a multiplier's tree is a chain).
  t.enter.assign(n_nodes, 0);
  t.leave.assign(n_nodes, 0);
  std::vector<std::vector<int>> children(n_nodes);
  for (int c = 1; c < n_nodes; ++c) children[parent[c]].push_back(c);
  std::vector<std::pair<int, size_t>> stack{{0, 0}};
  int clock = 0;
  t.preorder.assign(n_nodes, 0);
  t.preorder[clock] = 0;
  t.enter[0] = clock++;
  while (!stack.empty()) {
    auto& [u, next] = stack.back();
    if (next < children[u].size()) {
      const int c = children[u][next++];
      t.preorder[clock] = c;
      t.enter[c] = clock++;
      stack.push_back({c, 0});
    } else {
      t.leave[u] = clock;
      stack.pop_back();
    }
  }
  t.node_links.assign(n_nodes, {});
  for (int l : t.links) {
    t.node_links[graph.branches[l].from].push_back(l);
    if (graph.branches[l].to != graph.branches[l].from) t.node_links[graph.branches[l].to].push_back(l);
  }
  return t;
}

std::vector<LoopTerm> fundamental_loop(const CircuitGraph& graph, const SpanningTree& t, int e) {
  // a = n+, b = n-: a -e-> b, then back from b to a in the tree.
  const Branch& link = graph.branches[e];
  std::vector<LoopTerm> up_from_b, up_from_a;
  int x = link.to, y = link.from;
  while (x != y) {
    if (t.depth[x] >= t.depth[y]) {  // climb from the b side: traversed child -> parent
      const int fb = t.to_parent[x].branch;
      up_from_b.push_back({fb, traversal_sign(graph.branches[fb], x)});
      x = t.parent[x];
    } else {  // climb from the a side; later traversed parent -> child, so flip the sign
      const int fb = t.to_parent[y].branch;
      up_from_a.push_back({fb, -traversal_sign(graph.branches[fb], y)});
      y = t.parent[y];
    }
  }
  std::vector<LoopTerm> loop;
  loop.reserve(1 + up_from_b.size() + up_from_a.size());
  loop.push_back({e, +1});
  loop.insert(loop.end(), up_from_b.begin(), up_from_b.end());
  loop.insert(loop.end(), up_from_a.rbegin(), up_from_a.rend());
  return loop;
}

std::vector<std::vector<LoopTerm>> fundamental_loops(const CircuitGraph& graph, const SpanningTree& tree) {
  std::vector<std::vector<LoopTerm>> loops;
  loops.reserve(tree.links.size());
  for (int e : tree.links) loops.push_back(fundamental_loop(graph, tree, e));
  return loops;
}

std::vector<LoopTerm> fundamental_cutset(const CircuitGraph& graph, const SpanningTree& t, int tree_branch) {
  // The tree branch joins node c to its parent. A link's loop climbs from its n- to its n+: it
  // passes c -> parent (child to parent, the sign of walking from c) when its n- is below c, and
  // parent -> c when its n+ is.
  const Branch& f = graph.branches[tree_branch];
  const int c = t.to_parent[f.from].branch == tree_branch ? f.from : f.to;
  auto below = [&](int node) { return t.enter[c] <= t.enter[node] && t.enter[node] < t.leave[c]; };
  const int up = traversal_sign(f, c);
  // The links with exactly one end below c, read from the links at the nodes of the smaller
  // side: the subtree (preorder [enter, leave)) or the rest.
  const int n_nodes = static_cast<int>(t.preorder.size()), inside = t.leave[c] - t.enter[c];
  std::vector<int> crossing;
  auto scan = [&](int from, int to) {
    for (int k = from; k < to; ++k)
      for (int l : t.node_links[t.preorder[k]])
        if (below(graph.branches[l].from) != below(graph.branches[l].to)) crossing.push_back(l);
  };
  if (2 * inside <= n_nodes) {
    scan(t.enter[c], t.leave[c]);
  } else {
    scan(0, t.enter[c]);
    scan(t.leave[c], n_nodes);
  }
  std::sort(crossing.begin(), crossing.end());  // link order is branch order
  std::vector<LoopTerm> cutset;
  cutset.reserve(crossing.size());
  for (int l : crossing) cutset.push_back({l, below(graph.branches[l].to) ? up : -up});
  return cutset;
}

}  // namespace lcs
