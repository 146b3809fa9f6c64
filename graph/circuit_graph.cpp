#include "graph/circuit_graph.h"

namespace lcs {

const char* branch_class_name(BranchClass c) {
  switch (c) {
    case BranchClass::VoltageSource: return "V";
    case BranchClass::Capacitor: return "C";
    case BranchClass::Resistor: return "R";
    case BranchClass::Diode: return "D";
    case BranchClass::Inductor: return "L";
    case BranchClass::CurrentSource: return "I";
  }
  return "?";
}

static BranchClass class_of(ElementKind kind) {
  switch (kind) {
    case ElementKind::VoltageSource: return BranchClass::VoltageSource;
    case ElementKind::Capacitor: return BranchClass::Capacitor;
    case ElementKind::Resistor: return BranchClass::Resistor;
    case ElementKind::Diode: return BranchClass::Diode;
    case ElementKind::Inductor: return BranchClass::Inductor;
    case ElementKind::CurrentSource: return BranchClass::CurrentSource;
    case ElementKind::Coupling: break;
  }
  return BranchClass::Resistor;  // unreachable: couplings are not branches
}

CircuitGraph CircuitGraph::from_netlist(const Netlist& netlist) {
  CircuitGraph g;
  auto intern = [&g](const std::string& name) {
    auto it = g.node_index_.find(name);
    if (it != g.node_index_.end()) return it->second;
    int index = static_cast<int>(g.nodes.size());
    g.nodes.push_back(name);
    g.node_index_.emplace(name, index);
    return index;
  };
  intern("0");
  for (int e = 0; e < static_cast<int>(netlist.elements.size()); ++e) {
    const Element& el = netlist.elements[e];
    if (el.kind == ElementKind::Coupling) continue;
    Branch b;
    b.element = e;
    b.name = el.name;
    b.cls = class_of(el.kind);
    b.from = intern(el.nodes.at(0));
    b.to = intern(el.nodes.at(1));
    g.branch_of_element_[e] = static_cast<int>(g.branches.size());
    g.branches.push_back(b);
  }
  return g;
}

int CircuitGraph::node_index(const std::string& name) const {
  auto it = node_index_.find(name);
  return it == node_index_.end() ? -1 : it->second;
}

int CircuitGraph::branch_of_element(int element) const {
  auto it = branch_of_element_.find(element);
  return it == branch_of_element_.end() ? -1 : it->second;
}

}  // namespace lcs
