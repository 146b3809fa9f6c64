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
// Perfectly coupled inductors (k = 1) make the inductance matrix singular: their currents that
// carry no flux are algebraic and solved for, and only the flux stays a state, as the
// magnetising current imag(l1) (perfect_coupling.h); branch rows still give every winding.
// Inputs: u[0] = 1 (carries the thresholds VON), u[k] = value of the k-th independent source.
// One complementarity pair per diode: a link diode is current-type (z = i, w = VON + RON i - v),
// a tree diode voltage-type (z = VON + RON i - v, w = i), the swap of 5.4.4.
// The elements come in as devices (solver/devices): formation collects their stamps (branches,
// constitutive relations, storage, pairs, inputs) and eliminates; it knows no element kind.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Dense>
#include <Eigen/Sparse>

#include "graph/circuit_graph.h"
#include "graph/spanning_tree.h"
#include "graph/topology.h"
#include "netlist/netlist.h"
#include "solver/devices/junction_fit.h"
#include "solver/model/lcs_problem.h"

namespace lcs {

// One affine output: value = g x + h z + j u + k du/dt (x the LCS state).
struct OutputRow {
  Eigen::RowVectorXd g, h, j, k;
};

struct OutputMap {
  std::vector<std::string> names;
  // Sparse: a probe reads a few states and pairs (a 1000-diode circuit's 3000 default probes made
  // dense G and H a quarter of its set-up). J, K: the few inputs.
  Eigen::SparseMatrix<double, Eigen::RowMajor> G, H;
  Eigen::MatrixXd J, K;
};

// An energy-storing branch as its device stamped it (capacitance or inductance, IC=).
struct StorageInfo {
  double value = 0;
  std::optional<double> ic;
};

struct ModelOptions {
  double ifit = 10e-3;        // diode fit current, `.options ifit=`
  std::map<std::string, DiodeCurrentRanges> diode_ranges{};  // DeviceOptions::diode_ranges
  double t0 = 0, t1 = 0;      // interval over which sources are checked (Figure 5.5 test)
  // Switches: the configuration to form (switch name -> on); see DeviceOptions::switch_on.
  std::map<std::string, bool> switch_on;
  // A circuit that will step on its descriptor form (sparse_descriptor.h) is eliminated to its
  // LCS only when something asks for it (lcs_problem.h); false eliminates at once (tests).
  bool defer_elimination = true;
};

// The model of one netlist: its devices, graph, normal tree, and the LCS they form, which the
// integrators see as an LcsProblem.
class CircuitModel : public LcsProblem {
 public:
  // Makes the devices, runs the topology checks and forms the LCS from the devices' stamps.
  // Throws TopologyError or NetlistError.
  static CircuitModel build(const Netlist& netlist, const ModelOptions& options);

  const Netlist& netlist() const { return netlist_; }
  const ModelOptions& options() const { return options_; }  // what it was built with
  const CircuitGraph& graph() const { return graph_; }
  const SpanningTree& tree() const { return tree_; }
  // The devices in card order: devices()[e] is the device of Netlist::elements[e].
  const std::vector<std::shared_ptr<Device>>& devices() const { return devices_; }
  // Per branch: its storage (capacitors and inductors), empty for the others.
  const std::vector<std::optional<StorageInfo>>& storage() const { return storage_; }

  // Energy stored in capacitors and inductors over the physical state x (u the inputs):
  //   W(x) = 1/2 x^T energy_xx x + x^T energy_xu u + (terms in u alone),
  // since every capacitor voltage and inductor current is Tc x + Tcu u, Tl x + Tlu u.
  const Eigen::SparseMatrix<double>& energy_xx() const { return energy_xx_; }
  const Eigen::MatrixXd& energy_xu() const { return energy_xu_; }

  OutputRow branch_voltage(int branch) const;
  OutputRow branch_current(int branch) const;
  // A multi-terminal device's terminal current (`ic(q1)`); NetlistError at the probe if none.
  OutputRow terminal_current(const Probe& probe) const;
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
  OutputRow row_from_physical(const Eigen::RowVectorXd& r) const;
  OutputRow device_current(const Device& d, const std::vector<std::pair<int, double>>& terms) const;  // [x z u du] -> shifted row
  Eigen::RowVectorXd node_row(int node) const;                     // physical, memoised
  // A branch's voltage or current over [x_phys | z | u | du]: branch_v_/branch_i_'s row, or made
  // from the loop/cutset map and the primary unknowns' rows where formation deferred them.
  Eigen::RowVectorXd branch_row(int branch, bool voltage) const;
  int row_columns() const { return state_count() + pair_count() + 2 * input_count(); }

  Netlist netlist_;
  ModelOptions options_;
  CircuitGraph graph_;
  SpanningTree tree_;
  std::vector<std::shared_ptr<Device>> devices_;
  std::vector<std::optional<StorageInfo>> storage_;
  // Branch voltages and currents as rows over [x_phys | z | u | du] (physical state), sparse: a
  // branch reads a few states, pairs and inputs.
  Eigen::SparseMatrix<double, Eigen::RowMajor> branch_v_, branch_i_;
  // Where formation deferred the elimination: Vmap, Imap (every branch voltage and current over
  // the primary unknowns, rows) and P (the primary unknowns over [x_phys | z | u | du]), so that
  // branch rows are made one at a time (branch_v_ and branch_i_ stay empty).
  struct PrimaryRows;
  std::shared_ptr<const PrimaryRows> primary_rows_;
  Eigen::SparseMatrix<double> energy_xx_;  // Mdyn: as sparse as the capacitor and inductor loops
  Eigen::MatrixXd energy_xu_;
  // node_row's memo, sparse like the branch rows (an empty vector: not yet). Not thread-safe.
  mutable std::vector<Eigen::SparseVector<double>> node_rows_;
  mutable std::vector<bool> node_row_known_;
};

}  // namespace lcs
