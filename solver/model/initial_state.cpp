#include "solver/model/initial_state.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <optional>
#include <set>

#include "solver/integrators/start_complementarity.h"
#include "solver/lcp/p_matrix.h"
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

// The complementarity state at t0+ for the state x, when the instantaneous problem (states held,
// LCP(C x + F u, D + eta C B), eta tiny: a pair with D_ii = 0 is decided by its effect on the
// state) has several solutions (transistor feedback) and x alone does not choose: the one nearest
// to the .ic/.nodeset node voltages, as for the operating point. Unchanged (the operating point's
// z, or zeros) when the problem is unique, no values are given, or two are as near.
void choose_start_mode(const CircuitModel& model, double t0, const Eigen::VectorXd& x, Eigen::VectorXd& z,
                       std::vector<std::string>& warnings) {
  const int m = model.pair_count();
  if (m == 0 || m > kMaxCheckedPairs || !model.has_transfer_pairs()) return;
  const Lcs& s = model.lcs();
  const double rate = s.A.size() > 0 ? s.A.cwiseAbs().rowwise().sum().maxCoeff() : 0.0;
  const double eta = 1e-9 / (rate > 0 ? rate : 1.0);
  const Eigen::MatrixXd M = s.D + eta * s.C * s.B;
  const PMatrixReport report = p_matrix_report(M, 0);
  if (report.symmetric_psd || report.verdict == PMatrixReport::Verdict::P) return;
  const Eigen::VectorXd u = model.input_values(t0);
  const Eigen::VectorXd q = s.C * x + s.F * u;
  const std::vector<Eigen::VectorXd> all = distinct_in_w(M, q, enumerate_lcp_solutions(M, q));
  if (all.size() < 2) return;
  const std::map<std::string, double> hints = node_hints(model.netlist());
  if (hints.empty()) return;
  // If the operating point's mode is among them, it continues: nothing to choose.
  for (const Eigen::VectorXd& sol : all) {
    bool same = true;
    for (int i = 0; i < m && same; ++i) same = (sol(i) > 0) == (z(i) > 0);
    if (same) return;
  }
  std::vector<std::pair<double, int>> distance;
  for (int k = 0; k < static_cast<int>(all.size()); ++k)
    distance.push_back({hint_distance(model, hints, x, all[k], t0), k});
  std::sort(distance.begin(), distance.end());
  if (distance[1].first - distance[0].first <= 1e-12 * std::max(1.0, distance[0].first)) return;
  z = all[distance[0].second];
  warnings.push_back("the initial state admits " + std::to_string(all.size()) +
                     " complementarity states (transistor feedback); the one nearest to the "
                     ".ic/.nodeset values is taken");
}

}  // namespace

InitialState initial_state(const CircuitModel& model, bool uic, double t0) {
  const Netlist& netlist = model.netlist();
  const CircuitGraph& g = model.graph();
  const int n = model.state_count();
  InitialState init;
  std::vector<std::string> chosen_by;  // .ic nodes that chose the operating point
  Eigen::VectorXd physical = Eigen::VectorXd::Zero(n);
  Eigen::VectorXd z = Eigen::VectorXd::Zero(model.pair_count());
  if (!uic) {
    OperatingPoint op = solve_operating_point(model, t0);
    physical = model.physical_state(op.x, t0);
    z = op.z;
    if (!op.undetermined.empty()) init.warnings.push_back(undetermined_state_warning(op.undetermined));
    for (const std::string& w : op.warnings) init.warnings.push_back(w);
    chosen_by = op.chosen_by;
    for (const auto& [x, oz] : op.other_starts) init.other_starts.push_back({model.physical_state(x, t0), oz});
  } else {
    // From rest, lines carry the waves of their IC= port values (zero without).
    std::vector<double> before;
    for (const DelayedWave& w : model.delayed()) before.push_back(w.before);
    model.begin_history(before);
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

  init.held.assign(n, false);
  std::set<std::string> used_node_ics(chosen_by.begin(), chosen_by.end());
  std::map<std::string, std::string> card_ic_at;  // node -> a state capacitor there with IC=
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
      init.held[j] = true;
      if (cap) {
        card_ic_at.emplace(g.nodes[br.from], br.name);
        card_ic_at.emplace(g.nodes[br.to], br.name);
      }
    } else if (cap && (node_ic.count(g.nodes[br.from]) || node_ic.count(g.nodes[br.to]))) {
      physical(j) = node_value(br.from) - node_value(br.to);
      init.held[j] = true;
      used_node_ics.insert(g.nodes[br.from]);
      used_node_ics.insert(g.nodes[br.to]);
    }
  }
  // A device's IC= takes precedence over .ic (SPICE3's manual, .IC).
  for (const NodeIc& ic : netlist.node_ics) {
    if (used_node_ics.count(ic.node)) continue;
    const auto card = card_ic_at.find(ic.node);
    if (card != card_ic_at.end())
      init.warnings.push_back(".ic v(" + ic.node + ") ignored: IC= on " + card->second +
                              " sets the voltage of the capacitor at node '" + ic.node +
                              "' (a device's IC= takes precedence over .ic)");
    else
      init.warnings.push_back(".ic v(" + ic.node + ") ignored: no capacitor whose voltage is a "
                              "state of the circuit connects to node '" + ic.node + "'");
  }
  std::vector<int> set_by_ic;
  for (int j = 0; j < n; ++j) {
    if (model.states()[j].windings.empty()) continue;
    auto current = [&](int b) {
      return uic ? 0.0 : model.evaluate_dc(model.branch_current(b), x_lcs, z, t0);
    };
    if (std::optional<double> value = magnetising_ic(model, model.states()[j], current)) {
      physical(j) = *value;
      set_by_ic.push_back(j);
      init.held[j] = true;
    }
  }
  init.x = model.lcs_state(physical, t0);
  init.z = z;
  choose_start_mode(model, t0, init.x, init.z, init.warnings);
  for (int j : set_by_ic)
    if (std::optional<std::string> w = winding_ics_not_held(model, j, init.x, t0)) init.warnings.push_back(*w);
  return init;
}

}  // namespace lcs
