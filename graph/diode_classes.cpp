#include "graph/diode_classes.h"

#include "graph/components.h"

namespace lcs {

std::vector<DiodeClass> classify_diodes(const CircuitGraph& graph) {
  NodePartition capacitive = components(graph, [](const Branch& b) {
    return b.cls == BranchClass::Capacitor || b.cls == BranchClass::VoltageSource;
  });
  NodePartition inductor_free = components(graph, [](const Branch& b) {
    return b.cls == BranchClass::Capacitor || b.cls == BranchClass::VoltageSource ||
           b.cls == BranchClass::Resistor;
  });
  NodePartition h = h_components(graph);
  std::vector<DiodeClass> out;
  for (int b = 0; b < static_cast<int>(graph.branches.size()); ++b) {
    const Branch& br = graph.branches[b];
    if (br.cls != BranchClass::Diode) continue;
    DiodeClass c;
    c.branch = b;
    c.cls = capacitive.same(br.from, br.to) ? 'C' : inductor_free.same(br.from, br.to) ? 'R' : 'L';
    c.joins_h_components = !h.same(br.from, br.to);
    out.push_back(c);
  }
  return out;
}

}  // namespace lcs
