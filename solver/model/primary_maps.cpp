#include "solver/model/primary_maps.h"

#include <algorithm>

namespace lcs {

PrimaryMaps::PrimaryMaps(const CircuitGraph& graph, const SpanningTree& tree) : graph_(graph), tree_(tree) {}

void PrimaryMaps::materialise() {
  if (materialised_) return;
  // Both written straight into compressed storage from the loops (no triplets: a multiplier's
  // loops hold O(N^2) entries): Vmap by rows, Imap by columns, then one transpose.
  const int nb = static_cast<int>(graph_.branches.size());
  const std::vector<std::vector<LoopTerm>> loops = fundamental_loops(graph_, tree_);
  RowSparse Vmap(nb, nb);
  Eigen::Index entries = nb;
  for (const std::vector<LoopTerm>& loop : loops) entries += static_cast<Eigen::Index>(loop.size()) - 1;
  Vmap.reserve(entries);
  Eigen::SparseMatrix<double> Icols(nb, nb);  // column l: Imap(f, l) = b_{f,l}, and Imap(l, l) = 1
  Icols.reserve(entries);
  std::vector<LoopTerm> sorted;
  for (int b = 0; b < nb; ++b) {
    Vmap.startVec(b);
    Icols.startVec(b);
    if (tree_.in_tree[b]) {
      Vmap.insertBack(b, b) = 1.0;
      continue;
    }
    const std::vector<LoopTerm>& loop = loops[tree_.position[b]];
    sorted.assign(loop.begin() + 1, loop.end());
    sorted.push_back({b, 0});  // the link's own place in its column of Imap
    std::sort(sorted.begin(), sorted.end(), [](const LoopTerm& x, const LoopTerm& y) { return x.branch < y.branch; });
    for (const LoopTerm& f : sorted) {
      if (f.branch == b) {
        Icols.insertBack(b, b) = 1.0;
        continue;
      }
      Vmap.insertBack(b, f.branch) = -f.sign;  // Vmap(l, f) = -b_{f,l}
      Icols.insertBack(f.branch, b) = f.sign;
    }
  }
  Vmap.finalize();
  Icols.finalize();
  vmap_ = std::move(Vmap);
  imap_ = Icols;
  materialised_ = true;
}

std::vector<std::pair<int, double>> PrimaryMaps::voltage_row(int b) const {
  if (tree_.in_tree[b]) return {{b, 1.0}};
  std::vector<LoopTerm> loop = fundamental_loop(graph_, tree_, b);
  std::sort(loop.begin() + 1, loop.end(), [](const LoopTerm& x, const LoopTerm& y) { return x.branch < y.branch; });
  std::vector<std::pair<int, double>> row;
  row.reserve(loop.size() - 1);
  for (size_t k = 1; k < loop.size(); ++k) row.emplace_back(loop[k].branch, -loop[k].sign);
  return row;
}

std::vector<std::pair<int, double>> PrimaryMaps::current_row(int b) const {
  if (!tree_.in_tree[b]) return {{b, 1.0}};
  std::vector<std::pair<int, double>> row;
  for (const LoopTerm& l : fundamental_cutset(graph_, tree_, b)) row.emplace_back(l.branch, l.sign);
  return row;
}

}  // namespace lcs
