#include "solver/model/initial_state.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <optional>
#include <set>

#include "solver/integrators/start_complementarity.h"
#include "solver/model/numerical_failure.h"
#include "solver/model/operating_point.h"

namespace lcs {

namespace {

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

// Perfectly coupled windings share one state, their flux: IC= currents give it as the flux
// they carry together, sum of ratio * i over the windings, where a winding without IC= carries
// `current(branch)` (its operating-point current, or 0 with UIC). Empty when no winding has IC=.
template <class Current>
std::optional<double> magnetising_ic(const CircuitModel& model, const StateInfo& state, Current current) {
  bool any = false;
  double value = 0;
  for (const auto& [b, ratio] : state.windings) {
    const std::optional<double>& ic = model.storage()[b]->ic;
    any = any || ic.has_value();
    value += ratio * (ic ? *ic : current(b));
  }
  return any ? std::optional<double>(value) : std::nullopt;
}

// The winding currents themselves are what the circuit makes of that flux at t0+ (the
// complementarity state there decides, say, whether a secondary diode takes a share): a warning
// when they are not the IC= values, none when they are (e.g. IC= on the primary of a transformer
// whose secondary diode blocks).
std::optional<std::string> winding_ics_not_held(const CircuitModel& model, int j,
                                                const Eigen::VectorXd& x, double t0) {
  const StateInfo& state = model.states()[j];
  Eigen::VectorXd z;
  try {
    StepperStats ignored;
    z = consistent_start_z(model, t0, 1.0, x, ignored);
  } catch (const NumericalFailure&) {
    return std::nullopt;  // the run itself reports this
  }
  const double value = model.physical_state(x, t0)(j);
  double scale = std::max(std::abs(value), 1e-9);
  for (const auto& [b, ratio] : state.windings)
    if (const std::optional<double>& ic = model.storage()[b]->ic) scale = std::max(scale, std::abs(*ic));
  const double tolerance = 1e-6 * scale;  // the start's own z is only this exact (start_complementarity.h)
  std::vector<std::string> with_ic;
  std::string formula, start;
  bool held = true;
  for (const auto& [b, ratio] : state.windings) {
    const std::string& name = model.graph().branches[b].name;
    const std::optional<double>& ic = model.storage()[b]->ic;
    double i = model.evaluate(model.branch_current(b), x, z, t0);
    if (std::abs(i) <= tolerance) i = 0;
    formula += formula.empty() ? "i(" + name + ")" : " + " + number(ratio) + "*i(" + name + ")";
    start += (start.empty() ? "i(" : ", i(") + name + ") = " + number(i) + " A";
    if (!ic) continue;
    with_ic.push_back(name);
    if (std::abs(i - *ic) > tolerance) held = false;
  }
  if (held) return std::nullopt;
  std::string names;
  for (size_t k = 0; k < with_ic.size(); ++k)
    names += (k == 0 ? "" : k + 1 == with_ic.size() ? " and " : ", ") + with_ic[k];
  return "IC= on " + names + ": perfectly coupled windings (k = 1) share one state, " + state.label +
         " = " + formula + ", set to " + number(value) + " A by the IC=s; the circuit starts with " +
         start;
}

}  // namespace

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
  std::vector<int> state_of_branch(g.branches.size(), -1);  // windings: their magnetising state
  for (int j = 0; j < n; ++j) {
    state_of_branch[model.states()[j].branch] = j;
    for (const auto& [winding, ratio] : model.states()[j].windings) state_of_branch[winding] = j;
  }
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
    if (!model.states()[j].windings.empty()) continue;  // below
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
  std::vector<int> set_by_ic;
  for (int j = 0; j < n; ++j) {
    if (model.states()[j].windings.empty()) continue;
    auto current = [&](int b) {
      return uic ? 0.0 : model.evaluate_dc(model.branch_current(b), x_lcs, z, t0);
    };
    if (std::optional<double> value = magnetising_ic(model, model.states()[j], current)) {
      physical(j) = *value;
      set_by_ic.push_back(j);
    }
  }
  init.x = model.lcs_state(physical, t0);
  for (int j : set_by_ic)
    if (std::optional<std::string> w = winding_ics_not_held(model, j, init.x, t0)) init.warnings.push_back(*w);
  return init;
}

}  // namespace lcs
