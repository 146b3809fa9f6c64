// Every branch's voltage and current in the primary unknowns p (tree voltages, link currents):
// KVL v = Vmap p and KCL i = Imap p (Stewart 5.4.1, eq. 5.34). A link's voltage is minus the tree
// voltages around its fundamental loop and its current its own; a tree branch's voltage is its
// own and its current the link currents through its fundamental cutset.
//
// Held as sparse matrices once materialised, or read from the tree one row at a time: a
// multiplier's maps hold O(N^2) entries, and a formation that reads a few rows (the static
// equations, the probes) reads them so, O(loop length) for a link's voltage row and O(links) for
// a tree branch's current row. Both ways give the same entries in the same (increasing column)
// order.
#pragma once

#include <Eigen/Sparse>

#include "graph/circuit_graph.h"
#include "graph/spanning_tree.h"

namespace lcs {

class PrimaryMaps {
 public:
  using RowSparse = Eigen::SparseMatrix<double, Eigen::RowMajor>;

  PrimaryMaps(const CircuitGraph& graph, const SpanningTree& tree);
  // Forms Vmap and Imap: O(total loop length).
  void materialise();
  bool materialised() const { return materialised_; }
  const RowSparse& voltage_map() const { return vmap_; }  // materialised only
  const RowSparse& current_map() const { return imap_; }

  // Calls visit(column, value) for each entry of row b of Vmap (voltage) or Imap, in increasing
  // column order.
  template <class Visit>
  void visit_row(bool voltage, int b, Visit visit) const {
    if (materialised_) {
      for (RowSparse::InnerIterator it(voltage ? vmap_ : imap_, b); it; ++it) visit(static_cast<int>(it.col()), it.value());
      return;
    }
    const std::vector<std::pair<int, double>> row = voltage ? voltage_row(b) : current_row(b);
    for (const auto& [column, value] : row) visit(column, value);
  }

  const CircuitGraph& graph() const { return graph_; }
  const SpanningTree& tree() const { return tree_; }

 private:
  std::vector<std::pair<int, double>> voltage_row(int b) const;
  std::vector<std::pair<int, double>> current_row(int b) const;

  CircuitGraph graph_;
  SpanningTree tree_;
  bool materialised_ = false;
  RowSparse vmap_, imap_;
};

}  // namespace lcs
