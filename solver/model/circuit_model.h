// From a netlist to its linear complementarity system (Stewart 4.5, 5.4):
//
//   dx/dt = A x + B z + E u(t),   w = C x + D z + F u(t),   0 <= w ⟂ z >= 0,
//   y = G x + H z + J u(t) + K du/dt   (probed outputs)
//
// States are tree capacitor voltages and link inductor currents of the normal tree. Capacitors
// forced into links (capacitor/voltage-source loops) and inductors forced into the tree
// (inductor/current-source cutsets) are dependent and folded into the effective capacitance and
// inductance matrices; the source derivatives they bring are absorbed by the state shift
// x = x_phys - Gamma u, so the LCS state is x and the physical one x + Gamma u.
// Inputs: u[0] = 1 (carries the thresholds VON), u[k] = value of the k-th independent source.
// One complementarity pair per diode: a link diode is current-type (z = i, w = VON + RON i - v),
// a tree diode voltage-type (z = VON + RON i - v, w = i), the swap of 5.4.4.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Dense>

#include "graph/circuit_graph.h"
#include "graph/spanning_tree.h"
#include "graph/topology.h"
#include "netlist/netlist.h"

namespace lcs {

struct Lcs {
  Eigen::MatrixXd A, B, E, C, D, F;
  Eigen::MatrixXd Gamma;  // physical state = x + Gamma u
  int states() const { return static_cast<int>(A.rows()); }
  int pairs() const { return static_cast<int>(D.rows()); }
  int inputs() const { return static_cast<int>(E.cols()); }
};

// One affine output: value = g x + h z + j u + k du/dt (x the LCS state).
struct OutputRow {
  Eigen::RowVectorXd g, h, j, k;
};

struct OutputMap {
  std::vector<std::string> names;
  Eigen::MatrixXd G, H, J, K;
};

struct StateInfo {
  int element = -1;
  int branch = -1;
  std::string label;  // "v(c1)" or "i(l1)"
};

struct PairInfo {
  int element = -1;
  int branch = -1;
  bool voltage_type = false;  // tree diode: z is the reverse-voltage margin, w the current
  IdealDiodeLaw law;
  bool fitted = false;        // law fitted to the Shockley curve
};

struct InputInfo {
  int element = -1;           // -1: the constant input u[0] = 1
  std::string label;
};

struct ModelOptions {
  double ifit = 10e-3;        // diode fit current, `.options ifit=`
  double t0 = 0, t1 = 0;      // interval over which sources are checked (Figure 5.5 test)
};

class CircuitModel {
 public:
  // Runs the topology checks and forms the LCS. Throws TopologyError or NetlistError.
  static CircuitModel build(const Netlist& netlist, const ModelOptions& options);

  const Netlist& netlist() const { return netlist_; }
  const CircuitGraph& graph() const { return graph_; }
  const SpanningTree& tree() const { return tree_; }
  const Lcs& lcs() const { return lcs_; }
  const std::vector<StateInfo>& states() const { return states_; }
  const std::vector<PairInfo>& pairs() const { return pairs_; }
  const std::vector<InputInfo>& inputs() const { return inputs_; }

  Eigen::VectorXd input_values(double t) const;
  // The same into u (size inputs()), without allocating for DC and SIN sources.
  void input_values(double t, Eigen::Ref<Eigen::VectorXd> u) const;
  Eigen::VectorXd input_derivatives(double t) const;
  Eigen::VectorXd physical_state(const Eigen::VectorXd& x, double t) const;
  Eigen::VectorXd lcs_state(const Eigen::VectorXd& physical, double t) const;

  OutputRow branch_voltage(int branch) const;
  OutputRow branch_current(int branch) const;
  OutputRow node_voltage(int node) const;
  double evaluate(const OutputRow& row, const Eigen::VectorXd& x, const Eigen::VectorXd& z,
                  double t) const;
  // The same at DC (operating point): sources held at their value at t, du/dt = 0.
  double evaluate_dc(const OutputRow& row, const Eigen::VectorXd& x, const Eigen::VectorXd& z,
                     double t) const;

  // SPEC §3 defaults: every node voltage, then the current of every V, L and D element.
  std::vector<Probe> default_probes() const;
  // Throws NetlistError (at the probe's location) for unknown nodes or elements.
  OutputMap output_map(const std::vector<Probe>& probes) const;

 private:
  OutputRow row_from_physical(const Eigen::RowVectorXd& r) const;  // [x z u du] -> shifted row

  Netlist netlist_;
  CircuitGraph graph_;
  SpanningTree tree_;
  Lcs lcs_;
  std::vector<StateInfo> states_;
  std::vector<PairInfo> pairs_;
  std::vector<InputInfo> inputs_;
  // Branch voltages and currents as rows over [x_phys | z | u | du] (physical state).
  Eigen::MatrixXd branch_v_, branch_i_;
};

}  // namespace lcs
