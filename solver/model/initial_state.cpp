#include "solver/model/initial_state.h"

#include <map>
#include <set>

#include "solver/model/operating_point.h"

namespace lcs {

InitialState initial_state(const CircuitModel& model, bool uic, double t0) {
  const Netlist& netlist = model.netlist();
  const CircuitGraph& g = model.graph();
  const int n = model.lcs().states();
  InitialState init;
  Eigen::VectorXd physical = Eigen::VectorXd::Zero(n);
  Eigen::VectorXd z = Eigen::VectorXd::Zero(model.lcs().pairs());
  if (!uic) {
    OperatingPoint op = solve_operating_point(model, t0);
    physical = model.physical_state(op.x, t0);
    z = op.z;
    if (!op.undetermined.empty()) init.warnings.push_back(undetermined_state_warning(op.undetermined));
  }
  Eigen::VectorXd x_lcs = model.lcs_state(physical, t0);

  std::map<std::string, double> node_ic;
  for (const NodeIc& ic : netlist.node_ics) node_ic[ic.node] = ic.value;
  auto node_value = [&](int node) {
    auto it = node_ic.find(g.nodes[node]);
    if (it != node_ic.end()) return it->second;
    if (node == 0 || uic) return 0.0;
    return model.evaluate_dc(model.node_voltage(node), x_lcs, z, t0);
  };

  std::set<std::string> used_node_ics;
  std::vector<int> state_of_branch(g.branches.size(), -1);
  for (int j = 0; j < n; ++j) state_of_branch[model.states()[j].branch] = j;
  for (int b = 0; b < static_cast<int>(g.branches.size()); ++b) {
    const Branch& br = g.branches[b];
    if (!model.storage()[b]) continue;
    const std::optional<double>& ic = model.storage()[b]->ic;
    const bool cap = br.cls == BranchClass::Capacitor;
    const int j = state_of_branch[b];
    if (j < 0) {
      if (ic)
        init.warnings.push_back("IC= on " + br.name + " ignored: its " +
                                (cap ? "voltage is fixed by a loop of capacitors and voltage sources"
                                     : "current is fixed by a cutset of inductors and current sources"));
      continue;
    }
    if (ic) {
      physical(j) = *ic;
    } else if (cap && (node_ic.count(g.nodes[br.from]) || node_ic.count(g.nodes[br.to]))) {
      physical(j) = node_value(br.from) - node_value(br.to);
      used_node_ics.insert(g.nodes[br.from]);
      used_node_ics.insert(g.nodes[br.to]);
    }
  }
  for (const NodeIc& ic : netlist.node_ics)
    if (!used_node_ics.count(ic.node))
      init.warnings.push_back(".ic v(" + ic.node + ") ignored: no capacitor whose voltage is a "
                              "state of the circuit connects to node '" + ic.node + "'");
  init.x = model.lcs_state(physical, t0);
  return init;
}

}  // namespace lcs
