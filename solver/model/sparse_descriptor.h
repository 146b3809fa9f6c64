// A large circuit in descriptor (node) form, for the time steps of circuits whose eliminated LCS
// is dense although the circuit is sparse (issue 12): a Cockcroft–Walton multiplier's diodes
// close loops down a chain of capacitors, so eliminating the static unknowns of the loop/cutset
// equations couples every pair to every state (C and D + hθ C (I - hθ A)^-1 B are dense), while
// each node of the circuit meets three or four branches.
//
// The unknowns are the node voltages e (ground excluded) and every branch current i; a branch
// voltage is e(n+) - e(n-). One row per node (KCL) and one per branch (its law):
//
//   KCL:        sum over branches at the node of ±i_b = 0
//   capacitor:  C v_b - hθ i_b = C v_b(t) + h(1-θ) i_b(t)            (every capacitor a state)
//   inductor:   sum_k Lf(b,k) i_k - hθ v_b = sum_k Lf(b,k) i_k(t) + h(1-θ) v_b(t)
//   static:     the device's relation over v, i and inputs (Stamps::Relation)
//   diode pair: tree (voltage-type) v_b - RON i_b + z = VON;  link (current-type) i_b - z = 0
//
// and the pair outputs w = VON + RON i_b - v_b (current-type) or w = i_b (voltage-type), as in
// formation (circuit_model.cpp). This is the θ-method of the LCS (Stewart 8.4) before the
// elimination: summing each tree capacitor's cutset and each link inductor's loop gives back the
// LCS step Mdyn (x+ - x) = h(θ R+ + (1-θ) R) exactly, and the static rows are the loop/cutset
// static equations written through node voltages (KVL by construction) and KCL rows (the cutset
// equations are sums of them). So it gives the dense path's states to rounding, on a system with
// a few entries per row: nodes + branches + pairs unknowns, O(1) nonzeros each.
//
// Scope: circuits where the LCS state is exactly the tree capacitor voltages and link inductor
// currents. Dependent capacitors and inductors (capacitor/voltage-source loops, inductor/current-
// source cutsets: the LCS shifts its state by Gamma u), perfectly coupled inductors (the flux
// reduction changes the states), lines (history inputs) and transistor junctions (several
// solutions are watched on the dense LCP, multistability.h) keep the dense path.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include <Eigen/Dense>
#include <Eigen/Sparse>

#include "graph/circuit_graph.h"
#include "solver/devices/device.h"
#include "solver/model/lcs_problem.h"

namespace lcs {

struct SparseDescriptor {
  using Sparse = Eigen::SparseMatrix<double>;
  int nodes = 0;     // unknown node voltages (ground excluded): y[0, nodes)
  int branches = 0;  // branch currents: y[nodes, nodes + branches)
  int unknowns() const { return nodes + branches; }
  // Rows of the step system  (K0 + hθ K1) y+ + Lz z+ = Sx x + h(1-θ) Sy y + Uin u+, over
  // y = [e | i]. K1 and Sy = -K1 live only in the storage rows; Sx maps the states into them.
  Sparse K0, K1, Lz, Sx, Sy;
  Eigen::MatrixXd Uin;          // rows x inputs (the relations' input terms, VON on u_0)
  Sparse X;                     // the LCS state read from y: x = X y (states x unknowns)
  Sparse P;                     // w = P y + Fw u
  Eigen::MatrixXd Fw;
  // The same circuit at one instant with x and z given (storage rows say v_b = x_j, i_b = x_j;
  // pair rows keep Lz): Kst y = Xst x + Uin u - Lz z. What the explicit part of θ < 1 needs.
  Sparse Kst, Xst;
  long nonzeros() const { return K0.nonZeros() + K1.nonZeros() + Lz.nonZeros() + P.nonZeros(); }
};

// Pairs from which a circuit with a dense LCS steps on its descriptor form. Measured on the
// Cockcroft–Walton family (`bench --scale cw`, euler, CPU per simulated second, shared machine):
// dense 0.034 / 0.27 / 4.1 and descriptor 0.14 / 0.44 / 1.1 at 50 / 100 / 200 pairs; the two
// power laws cross near 120 pairs. Formation defers the whole elimination of such a circuit
// (circuit_model.cpp).
constexpr int kDescriptorPairs = 128;

// The descriptor when the step should be solved on it (sparse_descriptor.cpp states the rule and
// its cost model), else null. The LCS formed from the same stamps has the states `states`, the
// pairs `pairs`, `inputs` inputs, `lcs_nonzeros` nonzeros in A, B, C, D (counted, or estimated
// from the circuit's loops and cutsets by a formation that has not formed them yet) and a state
// shift Gamma u unless `shift_free`. Formation calls this once.
std::unique_ptr<SparseDescriptor> sparse_descriptor_if_worth(
    const CircuitGraph& g, const Stamps& stamps,
    const std::vector<StateInfo>& states, const std::vector<PairInfo>& pairs, int inputs, long lcs_nonzeros,
    bool shift_free, bool has_history);

// The entries of A, B, C, D that are not exactly zero: what the dense matrices would hold.
long lcs_nonzeros(const SparseLcs& lcs);

}  // namespace lcs
