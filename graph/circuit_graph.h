// The circuit as a graph: one node per circuit node, one branch per two-terminal branch of a
// device (solver/devices: a multi-terminal device is a composite of branches).
// Orientation (DESIGN.md): a branch runs n+ -> n-; v_b = v(n+) - v(n-); i_b flows n+ -> n-.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "netlist/netlist.h"

namespace lcs {

// Ordered by normal-tree preference (lighter enters the spanning tree first), DESIGN.md.
enum class BranchClass { VoltageSource = 0, Capacitor = 1, Resistor = 2, Diode = 3, Inductor = 4,
                         CurrentSource = 5 };
const char* branch_class_name(BranchClass c);

struct Branch {
  int element = -1;     // the device's element: index into Netlist::elements
  std::string name;     // element name
  BranchClass cls = BranchClass::Resistor;
  int from = 0, to = 0; // node indices of n+ and n-
};

struct CircuitGraph {
  std::vector<std::string> nodes;  // nodes[0] is ground "0"
  std::vector<Branch> branches;

  CircuitGraph();  // ground "0" only
  // Adds a branch from node `from` to node `to` (nodes are created on first use).
  int add_branch(int element, const std::string& name, BranchClass cls, const std::string& from,
                 const std::string& to);
  int node_index(const std::string& name) const;  // -1 when the circuit has no such node
  int branch_of_element(int element) const;       // its first branch; -1 for none (K)

 private:
  std::map<std::string, int> node_index_;
  std::map<int, int> branch_of_element_;
};

}  // namespace lcs
