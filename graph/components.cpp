#include "graph/components.h"

#include <boost/graph/adjacency_list.hpp>
#include <boost/graph/connected_components.hpp>

namespace lcs {

NodePartition components(const CircuitGraph& graph,
                         const std::function<bool(const Branch&)>& keep) {
  boost::adjacency_list<boost::vecS, boost::vecS, boost::undirectedS> g(graph.nodes.size());
  for (const Branch& b : graph.branches)
    if (keep(b)) boost::add_edge(b.from, b.to, g);
  NodePartition p;
  p.component.resize(graph.nodes.size());
  p.count = boost::connected_components(g, p.component.data());
  return p;
}

NodePartition h_components(const CircuitGraph& graph) {
  return components(graph, [](const Branch& b) {
    return b.cls != BranchClass::Diode && b.cls != BranchClass::CurrentSource;
  });
}

}  // namespace lcs
