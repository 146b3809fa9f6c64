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

CircuitGraph::CircuitGraph() {
  nodes.push_back("0");
  node_index_.emplace("0", 0);
}

int CircuitGraph::add_branch(int element, const std::string& name, BranchClass cls,
                             const std::string& from, const std::string& to) {
  auto intern = [this](const std::string& node) {
    auto it = node_index_.find(node);
    if (it != node_index_.end()) return it->second;
    const int index = static_cast<int>(nodes.size());
    nodes.push_back(node);
    node_index_.emplace(node, index);
    return index;
  };
  Branch b;
  b.element = element;
  b.name = name;
  b.cls = cls;
  b.from = intern(from);
  b.to = intern(to);
  const int index = static_cast<int>(branches.size());
  branch_of_element_.emplace(element, index);  // keeps the first
  branches.push_back(b);
  return index;
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
