#include "graph/cutset_sums.h"

#include <algorithm>

namespace lcs {

CutsetSums::CutsetSums(const CircuitGraph& graph, const SpanningTree& tree) : graph_(graph), tree_(tree) {
  const int n = static_cast<int>(tree.parent.size());
  int levels = 1;
  while ((1 << levels) < n) ++levels;
  // up[k][v]: the 2^k-th ancestor of v (ground is its own).
  std::vector<std::vector<int>> up(levels, std::vector<int>(n, 0));
  for (int v = 0; v < n; ++v) up[0][v] = tree.parent[v] < 0 ? 0 : tree.parent[v];
  for (int k = 1; k < levels; ++k)
    for (int v = 0; v < n; ++v) up[k][v] = up[k - 1][up[k - 1][v]];
  auto lca = [&](int a, int b) {
    if (tree.depth[a] < tree.depth[b]) std::swap(a, b);
    for (int k = levels - 1; k >= 0; --k)
      if (tree.depth[a] - (1 << k) >= tree.depth[b]) a = up[k][a];
    if (a == b) return a;
    for (int k = levels - 1; k >= 0; --k)
      if (up[k][a] != up[k][b]) {
        a = up[k][a];
        b = up[k][b];
      }
    return up[0][a];
  };
  for (int l : tree.links) lca_.push_back(lca(graph.branches[l].from, graph.branches[l].to));
  order_.resize(n);
  for (int v = 0; v < n; ++v) order_[v] = v;
  std::stable_sort(order_.begin(), order_.end(), [&](int a, int b) { return tree.depth[a] > tree.depth[b]; });
}

std::vector<double> CutsetSums::sums(const std::vector<double>& link_weight) const {
  // A link's loop runs from each end up to their common ancestor: it crosses the tree branch
  // above node c exactly when one end is below c. So the sum over the subtree of c of (weights
  // at link ends) - 2 (weights of links whose ancestor is there) is the cutset sum above c.
  std::vector<double> below(tree_.parent.size(), 0.0);
  for (size_t j = 0; j < tree_.links.size(); ++j) {
    const int l = tree_.links[j];
    const double w = link_weight[l];
    below[graph_.branches[l].from] += w;
    below[graph_.branches[l].to] += w;
    below[lca_[j]] -= 2 * w;
  }
  std::vector<double> out(graph_.branches.size(), 0.0);
  for (int c : order_) {
    if (tree_.parent[c] < 0) continue;
    out[tree_.to_parent[c].branch] = below[c];
    below[tree_.parent[c]] += below[c];
  }
  return out;
}

}  // namespace lcs
