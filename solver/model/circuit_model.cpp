#include "solver/model/circuit_model.h"
#include "solver/model/empty_safe.h"
#include "solver/model/dense_budget.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <map>
#include <set>
#include <stdexcept>
#include <unordered_map>

#include "graph/cutset_sums.h"
#include "graph/topology.h"
#include "solver/devices/device_registry.h"
#include "solver/model/line_dc_loops.h"
#include "solver/model/netlist_options.h"
#include "solver/model/inductance_check.h"
#include "solver/model/perfect_coupling.h"
#include "solver/model/primary_maps.h"
#include "solver/model/sparse_descriptor.h"
#include "solver/model/sparse_lcs.h"
#include "solver/model/sparse_solve.h"
#include "solver/model/structural_zeros.h"

namespace lcs {

namespace {

enum class Role { State, Static, Forced };  // how a branch's primary unknown is determined

}  // namespace

namespace {

// A source whose value overflows somewhere in [0, t1] (a growing SIN, an EXP with a tiny time
// constant, parameters near the double range) is an error at its card, not a run that writes nan.
// Sampled at its corners, both ends and 256 points between: the waveforms are smooth between
// corners and monotone in their exponentials, so an overflow shows at an end or a corner.
void check_finite_inputs(const Netlist& netlist, const InputProvider& inputs, double t1) {
  for (int k = 1; k < inputs.size(); ++k) {
    const InputSignal& s = inputs[k];
    if (s.history >= 0) continue;  // a line's wave: the circuit's own values, checked as they come
    // A PULSE train (or a repeating PWL) repeats its corners and stays within its levels: its
    // first and last thousandth of [0, t1], at most its delay and four periods, are the evidence
    // (all 1e7 corners of a .tran of 1e7 periods made this check cost seconds, and a thousandth
    // of 2e13 periods, TSTOP 1 G s at 50 us, 36 s in the instrumented build; both found by
    // operating_point_fuzz). A repeating PWL's whole written list is read (its repeats start at
    // its last point).
    std::vector<double> times;
    const Waveform& w = s.waveform;
    const bool repeating_pwl = w.kind == Waveform::Kind::Pwl && w.repeat_from && w.params.size() >= 4;
    if ((w.kind == Waveform::Kind::Pulse || repeating_pwl) && t1 > 0) {
      const std::vector<double>& p = w.params;  // resolved: TD is p[2], PER p[6]
      const double end_point = repeating_pwl ? p[p.size() - 2] : 0.0;
      const double per = repeating_pwl ? end_point - *w.repeat_from : p.size() > 6 && p[6] > 0 ? p[6] : INFINITY;
      const double td = repeating_pwl ? std::max(0.0, end_point) : p.size() > 2 ? std::max(0.0, p[2]) : 0.0;
      const double first = repeating_pwl ? std::min(t1, td + 4 * per) : std::min(t1 / 1024, td + 4 * per);
      const double last = std::min(t1 / 1024, 4 * per);
      times = s.waveform.breakpoints(0, first);
      for (double t : s.waveform.breakpoints(t1 - last, t1)) times.push_back(t);
    } else {
      times = s.waveform.breakpoints(0, t1);
    }
    times.push_back(0);
    if (t1 > 0)
      for (int j = 1; j <= 256; ++j) times.push_back(t1 * j / 256);
    for (double t : times) {
      const double v = s.waveform.value(t), d = s.waveform.derivative(t);
      if (std::isfinite(v) && std::isfinite(d)) continue;
      char at[48];
      std::snprintf(at, sizeof at, "%.9g s", t);
      throw NetlistError(netlist.elements.at(s.element).loc,
                         "source " + s.label + ": its " + (std::isfinite(v) ? "slope" : "value") +
                             " at t = " + at + " is not a finite number");
    }
  }
}

// Frees a matrix formation no longer needs: a multiplier's loop and cutset products hold O(n^2)
// entries each, and keeping them all to the end set formation's peak memory.
template <class Matrix>
void release(Matrix& m) {
  m = Matrix();
}

// Mdyn's diagonal without cancellation, |Tc|^T C |Tc| + |Tl|^T |Lf| |Tl| (diagonal only): what
// tells two windings in series opposition (L1 + L2 - 2M = 0) from a small inductance.
Eigen::VectorXd uncancelled_diagonal(const SparseMatrixD& Tc, const Eigen::VectorXd& Cd,
                                     const SparseMatrixD& Tl, const SparseMatrixD& Lf) {
  Eigen::VectorXd out = Eigen::VectorXd::Zero(Tc.cols());
  for (int j = 0; j < Tc.outerSize(); ++j)
    for (SparseMatrixD::InnerIterator it(Tc, j); it; ++it) out(j) += Cd(it.row()) * it.value() * it.value();
  for (int j = 0; j < Tl.outerSize(); ++j)
    for (SparseMatrixD::InnerIterator a(Tl, j); a; ++a)
      for (SparseMatrixD::InnerIterator b(Tl, j); b; ++b) {
        const double l = Lf.coeff(a.row(), b.row());
        if (l != 0) out(j) += std::abs(l) * std::abs(a.value()) * std::abs(b.value());
      }
  return out;
}

// The inductors (rows of TlN over `inds`) that a flux-free current pattern moves.
std::vector<int> moved_inductors(const std::vector<int>& inds, const Eigen::MatrixXd& TlN) {
  std::vector<int> out;
  const double big = TlN.size() > 0 ? TlN.cwiseAbs().maxCoeff() : 0.0;
  for (int k = 0; k < static_cast<int>(inds.size()); ++k)
    if (TlN.row(k).cwiseAbs().maxCoeff() > 1e-12 * big) out.push_back(inds[k]);
  return out;
}

TopologyError flux_free_current_undetermined(const Netlist& netlist, const CircuitGraph& g,
                                             const std::vector<int>& inds, const Eigen::MatrixXd& TlN) {
  std::vector<int> elements;
  std::vector<std::string> names;
  for (int b : moved_inductors(inds, TlN)) {
    elements.push_back(g.branches[b].element);
    names.push_back(netlist.elements[g.branches[b].element].name);
  }
  return TopologyError("perfectly coupled inductors " + join_names(names) +
                           " (k = 1): the current that carries no flux between the windings meets "
                           "no resistance or diode, so the winding currents are not determined "
                           "(a higher-index circuit); put resistance in series with a winding or "
                           "use k < 1",
                       elements);
}

// The states after the flux reduction: a kept state that shares the flux of eliminated ones is
// its group's magnetising current referred to its own winding, xi_j = x_j - sum N(j, e) x_e.
std::vector<StateInfo> magnetising_states(const std::vector<StateInfo>& states,
                                          const FluxReduction& flux) {
  std::vector<StateInfo> out;
  for (int j : flux.kept) {
    StateInfo s = states[j];
    for (size_t e = 0; e < flux.eliminated.size(); ++e) {
      if (flux.N(j, e) == 0) continue;
      if (s.windings.empty()) s.windings.push_back({s.branch, 1.0});
      s.windings.push_back({states[flux.eliminated[e]].branch, -flux.N(j, e)});
    }
    if (!s.windings.empty()) s.label = "imag" + s.label.substr(1);  // i(l1) -> imag(l1)
    out.push_back(s);
  }
  return out;
}

// A link capacitor whose loop holds a controlled voltage source (E, H), or a tree inductor whose
// cutset holds a controlled current source (F, G, or a sensing branch): its voltage (current)
// would be the source's, a function of the circuit's own unknowns, and its current (voltage) a
// derivative of them; the loop equations of the normal tree give no state for that.
TopologyError storage_loop_with_controlled_source(const Netlist& netlist, const CircuitGraph& g,
                                                  const SpanningTree& t, int b, bool capacitor) {
  std::vector<int> branches{b};
  if (capacitor) {
    const std::vector<LoopTerm> loop = fundamental_loop(g, t, b);
    for (size_t j = 1; j < loop.size(); ++j) branches.push_back(loop[j].branch);
  } else {
    for (const LoopTerm& l : fundamental_cutset(g, t, b)) branches.push_back(l.branch);
  }
  std::sort(branches.begin() + 1, branches.end());
  branches.erase(std::unique(branches.begin() + 1, branches.end()), branches.end());
  // Named by branch: a transistor's inner capacitors are two branches of one element (q1:cbe,
  // q1:cbc). The notes point at each element once.
  std::vector<std::string> names;
  std::vector<int> elements;
  for (int k : branches) {
    names.push_back(g.branches[k].name);
    if (std::find(elements.begin(), elements.end(), g.branches[k].element) == elements.end())
      elements.push_back(g.branches[k].element);
  }
  const std::string what = capacitor ? "capacitor " : "inductor ";
  const std::string where = capacitor ? " is in a loop of capacitors and voltage sources with a controlled voltage source ("
                                      : " is in a cutset of inductors and current sources with a controlled current source (";
  std::string remedy = capacitor ? "resistance in series with it" : "resistance in parallel with it";
  const std::string& own = g.branches[b].name;
  if (const size_t colon = own.find(':'); colon != std::string::npos) {
    // Inside a device (a transistor's CJE or CJC): its terminals are where a resistance can go.
    const std::string device = netlist.elements[g.branches[b].element].name;
    remedy = "resistance in series with a terminal of " + device + " in that loop, or take the capacitance out of " +
             device + "'s model";
  }
  return TopologyError(what + names[0] + where + join_names(names) + "): its " +
                           (capacitor ? "voltage" : "current") + " would follow the controlled source, not be a state; add a " +
                           remedy,
                       elements);
}

using RowSparse = Eigen::SparseMatrix<double, Eigen::RowMajor>;

// Rp of the state equations Mdyn x' = Rp p (p the primary unknowns): per state, the links of its
// cutset that are not capacitors (a tree capacitor, KCL) or the tree branches of its loop that
// are not inductors (a link inductor, KVL), each with its sign. By rows, straight into compressed
// storage: a multiplier's cutsets hold O(n^2) entries.
SparseMatrixD state_equation_rows(const std::vector<StateInfo>& states, const PrimaryMaps& maps) {
  const CircuitGraph& g = maps.graph();
  const int n = static_cast<int>(states.size()), nb = static_cast<int>(g.branches.size());
  auto cls = [&](int b) { return g.branches[b].cls; };
  RowSparse rows(n, nb);
  std::vector<LoopTerm> path;
  for (int j = 0; j < n; ++j) {
    const int b = states[j].branch;
    rows.startVec(j);
    if (cls(b) == BranchClass::Capacitor) {  // its cutset: the links through it
      maps.visit_row(false, b, [&](int l, double value) {
        if (cls(l) != BranchClass::Capacitor) rows.insertBack(j, l) = value;
      });
    } else {  // its loop: the tree path
      const std::vector<LoopTerm> loop = fundamental_loop(g, maps.tree(), b);
      path.clear();
      for (size_t k = 1; k < loop.size(); ++k)
        if (cls(loop[k].branch) != BranchClass::Inductor) path.push_back(loop[k]);
      std::sort(path.begin(), path.end(), [](const LoopTerm& x, const LoopTerm& y) { return x.branch < y.branch; });
      for (const LoopTerm& f : path) rows.insertBack(j, f.branch) = -f.sign;
    }
  }
  rows.finalize();
  return SparseMatrixD(rows);
}

// Xdot = Mdyn^-1 R; false when Mdyn is singular.
bool solve_state_derivatives(const SparseMatrixD& MdynS, const SparseMatrixD& R, SparseMatrixD& Xdot) {
  if (MdynS.rows() < kSparseSolveSize) {  // small circuits keep the unscaled dense solve they always had
    Eigen::FullPivLU<Eigen::MatrixXd> m_lu{Eigen::MatrixXd(MdynS)};
    if (!m_lu.isInvertible()) return false;
    Xdot = Eigen::MatrixXd(solve_or_empty(m_lu, Eigen::MatrixXd(R))).sparseView();
    return true;
  }
  return solve_scaled(MdynS, R, false, Xdot);
}

// The complementarity outputs w as rows over the branch rows' columns: pair k reads the rows
// row[k] of bv and bi (its branch's voltage and current): w = i (voltage-type) or
// VON + RON i - v (current-type, VON on column von_column). By rows, each merged from its branch
// rows, then one transpose.
SparseMatrixD pair_output_rows(const std::vector<PairInfo>& pairs, const RowSparse& bv, const RowSparse& bi,
                               const std::vector<int>& row, int von_column) {
  const int mp = static_cast<int>(pairs.size());
  RowSparse rows(mp, bv.cols());
  std::vector<std::pair<int, double>> entries;
  for (int k = 0; k < mp; ++k) {
    const PairInfo& pr = pairs[k];
    const int r = row[k];
    entries.clear();
    if (pr.voltage_type) {
      for (RowSparse::InnerIterator it(bi, r); it; ++it) entries.emplace_back(it.col(), it.value());
    } else {
      for (RowSparse::InnerIterator it(bi, r); it; ++it) entries.emplace_back(it.col(), pr.law.ron * it.value());
      for (RowSparse::InnerIterator it(bv, r); it; ++it) entries.emplace_back(it.col(), -it.value());
      if (pr.law.von != 0) entries.emplace_back(von_column, pr.law.von);
    }
    std::stable_sort(entries.begin(), entries.end(),
                     [](const std::pair<int, double>& x, const std::pair<int, double>& y) { return x.first < y.first; });
    rows.startVec(k);
    for (size_t e = 0; e < entries.size();) {  // duplicates summed in the order written
      const int col = entries[e].first;
      double sum = 0;
      for (; e < entries.size() && entries[e].first == col; ++e) sum += entries[e].second;
      if (sum != 0) rows.insertBack(k, col) = sum;
    }
  }
  rows.finalize();
  return SparseMatrixD(rows);
}

// Every MdynS entry off the diagonal is zero and every diagonal one positive: uncoupled
// capacitors and inductors.
bool positive_diagonal(const SparseMatrixD& M) {
  for (int c = 0; c < M.outerSize(); ++c) {
    bool diagonal = false;
    for (SparseMatrixD::InnerIterator it(M, c); it; ++it) {
      if (it.row() != c && it.value() != 0) return false;
      if (it.row() == c) diagonal = it.value() > 0;
    }
    if (!diagonal) return false;
  }
  return true;
}

}  // namespace

struct CircuitModel::PrimaryRows {
  PrimaryMaps maps;  // rows read from the tree, not materialised
  RowSparse P_rows;  // P by rows
};

CircuitModel CircuitModel::build(const Netlist& netlist, const ModelOptions& options) {
  CircuitModel m;
  m.netlist_ = netlist;
  m.options_ = options;
  DeviceOptions device_options;
  device_options.switch_on = options.switch_on;
  const NetlistOptions netlist_options = read_netlist_options(netlist);  // NetlistError
  device_options.ifit = netlist_options.ifit.value_or(options.ifit);
  device_options.diode_ranges = options.diode_ranges;
  device_options.bjtcap = netlist_options.bjtcap;
  device_options.diodecap = netlist_options.diodecap;
  device_options.tstop = options.t1;
  device_options.tstep = netlist.tran ? netlist.tran->tstep : 0;
  m.devices_ = make_devices(m.netlist_, device_options);
  // Each switch configuration is its own model (switch_family.h) and a line's history lives in
  // one model's inputs: the two together are refused rather than run with a lost past.
  for (const std::shared_ptr<Device>& line : m.devices_) {
    if (!line->has_history()) continue;
    for (const Element& e : netlist.elements)
      if (e.kind == ElementKind::VSwitch || e.kind == ElementKind::CSwitch)
        throw NetlistError(e.loc, "switch " + e.name + ": switches in a circuit with transmission lines (" +
                                      line->name() + ") are not supported");
  }
  m.graph_ = graph_of_devices(m.devices_);
  const CircuitGraph& g = m.graph_;
  check_connected(netlist, g);
  m.tree_ = build_normal_tree(g);
  const SpanningTree& t = m.tree_;
  check_source_loops_and_cutsets(netlist, g, t);
  check_inductance_matrices(netlist);
  if (!(netlist.tran && netlist.tran->uic)) check_line_dc_loops(netlist);  // the run starts at DC

  // Collect the stamps: every device sees where its branches landed.
  Stamps stamps;
  {
    StampContext context{g, 0};
    for (const std::shared_ptr<Device>& d : m.devices_) {
      d->stamp(context, stamps);
      context.first_branch += static_cast<int>(d->branches().size());
    }
  }
  const int nb = static_cast<int>(g.branches.size());
  std::vector<const Stamps::Relation*> relation_of(nb, nullptr);
  for (const Stamps::Relation& r : stamps.relations) relation_of[r.branch] = &r;
  m.storage_.assign(nb, std::nullopt);
  for (const Stamps::Storage& s : stamps.storage) m.storage_[s.branch] = StorageInfo{s.value, s.ic};

  // Diode laws (per branch), checked for impedance-free loops (5.40).
  std::vector<IdealDiodeLaw> law(nb);
  std::vector<int> pair_of(nb, -1);
  for (const Stamps::Pair& p : stamps.pairs) {
    law[p.branch] = p.law.law;
    pair_of[p.branch] = static_cast<int>(m.pairs_.size());
    PairInfo info;
    static_cast<PairLaw&>(info) = p.law;
    info.branch = p.branch;
    info.voltage_type = t.in_tree[p.branch];
    m.pairs_.push_back(info);
  }
  // A Shockley junction conducts through an impedance at every current (issue 9, defect 2).
  if (!netlist.smooth_junctions) check_ideal_diode_loops(netlist, g, law, options.t0, options.t1);

  // A source branch's primary quantity is one input: v_b = u_k (tree) or i_b = u_k (link).
  std::vector<int> input_of(nb, -1);
  for (const Stamps::Relation& r : stamps.relations) {
    if (r.terms.size() != 2 || r.terms[1].of != Term::Of::Input || r.terms[1].coeff != -1.0) continue;
    const Term& own = r.terms[0];
    const Term::Of primary = t.in_tree[r.branch] ? Term::Of::Voltage : Term::Of::Current;
    if (own.of == primary && own.index == r.branch && own.coeff == 1.0) input_of[r.branch] = r.terms[1].index;
  }
  // History inputs (lines): wave i of the DelayHistory feeds input stamps.delayed[i].input.
  std::vector<double> delays;
  for (size_t i = 0; i < stamps.delayed.size(); ++i) {
    stamps.inputs.at(stamps.delayed[i].input - 1).history = static_cast<int>(i);
    delays.push_back(stamps.delayed[i].delay);
  }
  m.inputs_ = InputProvider(stamps.inputs);
  m.inputs_.attach_history(std::make_shared<DelayHistory>(delays));
  check_finite_inputs(netlist, m.inputs_, options.t1);
  for (const std::shared_ptr<Device>& d : m.devices_) m.max_step_ = std::min(m.max_step_, d->max_step());

  // Roles and state numbering (in branch order): storage branches are states where the normal
  // tree lets them be (tree capacitors, link inductors), forced otherwise; the rest are static.
  std::vector<Role> role(nb, Role::Static);
  std::vector<int> state_of(nb, -1);
  for (int b = 0; b < nb; ++b) {
    const Branch& br = g.branches[b];
    const bool tree = t.in_tree[b];
    if ((br.cls == BranchClass::Capacitor && tree) || (br.cls == BranchClass::Inductor && !tree)) {
      role[b] = Role::State;
    } else if ((br.cls == BranchClass::Capacitor && !tree) ||
               (br.cls == BranchClass::Inductor && tree)) {
      role[b] = Role::Forced;
    }
    if (role[b] != Role::Static && !m.storage_[b])
      throw std::logic_error("circuit model: " + br.name + " is a storage branch without a value");
    if (role[b] == Role::Static && !relation_of[b] && pair_of[b] < 0)
      throw std::logic_error("circuit model: " + br.name + " has no constitutive relation");
  }
  // Tree capacitors first, then link inductors.
  for (int pass = 0; pass < 2; ++pass)
    for (int b = 0; b < nb; ++b) {
      if (role[b] != Role::State) continue;
      const bool cap = g.branches[b].cls == BranchClass::Capacitor;
      if (cap != (pass == 0)) continue;
      state_of[b] = static_cast<int>(m.states_.size());
      m.states_.push_back({g.branches[b].element, b, (cap ? "v(" : "i(") + g.branches[b].name + ")", cap, {}});
    }

  int n = static_cast<int>(m.states_.size());  // fewer after perfect couplings (below)
  const int mp = static_cast<int>(m.pairs_.size());
  const int nu = static_cast<int>(m.inputs_.size());
  int ncol = n + mp + 2 * nu;  // columns of [x | z | u | du]
  auto col_z = [&](int k) { return n + k; };
  auto col_u = [&](int k) { return n + mp + k; };
  auto value = [&](int b) { return m.storage_[b]->value; };

  // Primary unknown p_b: the voltage of a tree branch, the current of a link. Every branch
  // voltage and current is linear in p: KCL i_tree = B i_link, KVL v_link = -B^T v_tree.
  // Sparse throughout (issue 12): a row holds one fundamental loop or cutset, not nb entries,
  // and the products below cost O(nnz * columns), not O(nb^2 * columns).
  using Triplets = std::vector<Eigen::Triplet<double>>;
  // Vmap and Imap (primary_maps.h) hold O(N^2) entries on a multiplier. A circuit that may step
  // on its descriptor form with its elimination deferred (below) reads a few of their rows, from
  // the tree; every other one forms them.
  const bool forced = std::find(role.begin(), role.end(), Role::Forced) != role.end();
  const bool may_defer = options.defer_elimination && mp >= kDescriptorPairs && stamps.delayed.empty() &&
                         stamps.dc_relations.empty() && stamps.couplings.empty() && !forced;
  auto maps = std::make_unique<PrimaryMaps>(g, t);  // freed once the branch rows are formed
  if (!may_defer) maps->materialise();

  // Static (resistive, source and diode) equations, one per Static branch:
  //   EqP p + EqR [x z u du] = 0   (EqR holds the z and u coefficients).
  std::vector<int> statics, static_of(nb, -1);
  for (int b = 0; b < nb; ++b)
    if (role[b] == Role::Static) {
      static_of[b] = static_cast<int>(statics.size());
      statics.push_back(b);
    }
  const int ns = static_cast<int>(statics.size());
  SparseMatrixD EqP(ns, nb);
  Triplets eqr;  // EqR, then the state columns of EqP: the right-hand side
  {
    Triplets eq;
    auto add_row = [&](int r, bool voltage, int b, double coeff) {
      if (coeff == 0) return;
      maps->visit_row(voltage, b, [&](int column, double value) { eq.emplace_back(r, column, coeff * value); });
    };
    for (int r = 0; r < ns; ++r) {
      const int b = statics[r];
      if (pair_of[b] >= 0) {               // the swap of 5.4.4
        if (t.in_tree[b]) {                // v - RON i + z - VON = 0
          add_row(r, true, b, 1.0);
          add_row(r, false, b, -law[b].ron);
          eqr.emplace_back(r, col_z(pair_of[b]), 1.0);
          if (law[b].von != 0) eqr.emplace_back(r, col_u(0), -law[b].von);
        } else {                           // i - z = 0
          eq.emplace_back(r, b, 1.0);
          eqr.emplace_back(r, col_z(pair_of[b]), -1.0);
        }
        continue;
      }
      for (const Term& term : relation_of[b]->terms) {  // the device's relation, sum = 0
        switch (term.of) {
          case Term::Of::Voltage: add_row(r, true, term.index, term.coeff); break;
          case Term::Of::Current: add_row(r, false, term.index, term.coeff); break;
          case Term::Of::Input: eqr.emplace_back(r, col_u(term.index), term.coeff); break;
        }
      }
    }
    EqP.setFromTriplets(eq.begin(), eq.end());
  }
  // Split EqP into the static unknowns (solved for) and the states; by the cycle property the
  // forced unknowns never appear here.
  SparseMatrixD Es(ns, ns), rhs(ns, ncol);
  {
    Triplets es;
    for (int b = 0; b < EqP.outerSize(); ++b)
      for (SparseMatrixD::InnerIterator it(EqP, b); it; ++it) {
        if (role[b] == Role::Static) es.emplace_back(it.row(), static_of[b], it.value());
        else if (role[b] == Role::State) eqr.emplace_back(it.row(), state_of[b], it.value());
        else if (it.value() != 0) throw std::logic_error("circuit model: forced branch in a static equation");
      }
    Es.setFromTriplets(es.begin(), es.end());
    rhs.setFromTriplets(eqr.begin(), eqr.end());
  }
  // P: every primary unknown as a row over [x_phys | z | u | du]; forced rows added below.
  Triplets p_entries;
  if (ns > 0) {
    SparseMatrixD sol;
    if (!solve_scaled(Es, rhs, true, sol)) {
      std::vector<int> elements;
      for (int b : statics) elements.push_back(g.branches[b].element);
      throw TopologyError("the resistive part of the circuit has no unique solution", elements);
    }
    for (int c = 0; c < sol.outerSize(); ++c)
      for (SparseMatrixD::InnerIterator it(sol, c); it; ++it)
        p_entries.emplace_back(statics[it.row()], c, -it.value());
  }
  for (int b = 0; b < nb; ++b)
    if (role[b] == Role::State) p_entries.emplace_back(b, state_of[b], 1.0);
  SparseMatrixD P(nb, ncol);
  P.setFromTriplets(p_entries.begin(), p_entries.end());

  // Capacitor and inductor voltages/currents in terms of states and sources:
  //   v_cap = Tc x + Tcu u,   i_ind = Tl x + Tlu u.
  std::vector<int> caps, inds;  // storage branches by tree class
  std::vector<int> cap_index(nb, -1), ind_index(nb, -1);
  for (int b = 0; b < nb; ++b) {
    if (g.branches[b].cls == BranchClass::Capacitor) { cap_index[b] = caps.size(); caps.push_back(b); }
    if (g.branches[b].cls == BranchClass::Inductor) { ind_index[b] = inds.size(); inds.push_back(b); }
  }
  const int nc = caps.size(), nl = inds.size();
  SparseMatrixD Tc(nc, n), Tl(nl, n), Lf(nl, nl);
  Eigen::MatrixXd Tcu = Eigen::MatrixXd::Zero(nc, nu), Tlu = Eigen::MatrixXd::Zero(nl, nu);
  Eigen::VectorXd Cd(nc);
  {
    Triplets tc, tl, lf;
    for (int k = 0; k < nc; ++k) {
      const int b = caps[k];
      Cd(k) = value(b);
      if (role[b] == Role::State) {
        tc.emplace_back(k, state_of[b], 1.0);
      } else {  // link capacitor: its loop holds only tree capacitors and voltage sources
        const std::vector<LoopTerm> loop = fundamental_loop(g, t, b);
        for (size_t j = 1; j < loop.size(); ++j) {
          const int f = loop[j].branch;
          const double s = loop[j].sign;  // b_{f,b}
          if (state_of[f] >= 0) tc.emplace_back(k, state_of[f], -s);
          else if (input_of[f] >= 0) Tcu(k, input_of[f]) -= s;
          else throw storage_loop_with_controlled_source(netlist, g, t, b, true);
        }
      }
    }
    for (int k = 0; k < nl; ++k) {
      const int b = inds[k];
      lf.emplace_back(k, k, value(b));
      if (role[b] == Role::State) {
        tl.emplace_back(k, state_of[b], 1.0);
      } else {  // tree inductor: its cutset holds only link inductors and current sources
        maps->visit_row(false, b, [&](int l, double s) {  // s = b_{b,l}
          if (state_of[l] >= 0) tl.emplace_back(k, state_of[l], s);
          else if (input_of[l] >= 0) Tlu(k, input_of[l]) += s;
          else throw storage_loop_with_controlled_source(netlist, g, t, b, false);
        });
      }
    }
    for (const Stamps::Coupling& k : stamps.couplings) {  // mutual inductance M = k sqrt(L1 L2)
      const int k1 = ind_index[k.branch_a], k2 = ind_index[k.branch_b];
      const double mutual = k.k * std::sqrt(value(k.branch_a) * value(k.branch_b));
      lf.emplace_back(k1, k2, mutual);
      lf.emplace_back(k2, k1, mutual);
    }
    Tc.setFromTriplets(tc.begin(), tc.end());
    Tl.setFromTriplets(tl.begin(), tl.end());
    Lf.setFromTriplets(lf.begin(), lf.end());
  }

  // State equations. Cutset of each tree capacitor f (KCL) and loop of each link inductor e
  // (KVL), with the dependent capacitors/inductors moved to the left:
  //   Tc^T diag(C) (Tc x' + Tcu u') = sum over R, D, L, I links l of b_{f,l} i_l
  //   Tl^T Lf (Tl x' + Tlu u')      = -sum over V, C, R, D tree branches f of b_{f,e} v_f
  const SparseMatrixD CdTc = Cd.asDiagonal() * Tc, LfTl = Lf * Tl;
  SparseMatrixD MdynS = SparseMatrixD(Tc.transpose() * CdTc) + SparseMatrixD(Tl.transpose() * LfTl);
  Eigen::MatrixXd Kdu = -(CdTc.transpose() * Tcu + LfTl.transpose() * Tlu);
  std::vector<bool> inductor_state(n, false);
  for (int j = 0; j < n; ++j) inductor_state[j] = !m.states_[j].capacitor;
  // Without inductor states nothing can be flux-free (capacitances are positive): no dense Mdyn.
  const bool inductors = std::find(inductor_state.begin(), inductor_state.end(), true) != inductor_state.end();
  const FluxReduction flux = inductors ? flux_reduction(Eigen::MatrixXd(MdynS), uncancelled_diagonal(Tc, Cd, Tl, Lf), inductor_state)
                                       : FluxReduction{};

  // A circuit that will step on its descriptor form (sparse_descriptor.h) reads no eliminated LCS
  // on its run path, and a multiplier's holds O(n^2) entries (every diode's loop runs down both
  // capacitor chains): forming it was two thirds of a 1000-diode run's CPU and most of its memory.
  // Such a circuit is recognised from its loops and cutsets before anything O(n^2) is formed, and
  // eliminated when something asks for its LCS (lcs(): event, radau, analyze, a dense fallback),
  // to the same numbers. Only where nothing below would change the states or add rows: no perfect
  // couplings (flux), dependent storage (Kdu, forced roles), lines or transistor junctions, and a
  // diagonal Mdyn (uncoupled capacitors and inductors: invertible, no error left to raise later).
  if (may_defer && flux.empty() && Kdu.isZero(0) && positive_diagonal(MdynS)) {
    // The LCS's nonzeros, estimated for the rule without forming it: Rp's entries stand for A
    // and B's, the pairs' loop and cutset rows for C and D's (close where P reads most primary
    // unknowns once, as on a multiplier, whose only other row is its load resistor's). Counted
    // from cutset sums (cutset_sums.h), O(N log N): a tree capacitor's state row holds the links
    // of its cutset that are not capacitors; a link inductor's the tree branches of its loop that
    // are not inductors (the tree branches f not inductors whose cutsets hold it); a link pair's
    // voltage row its loop's tree branches and its current row itself; a tree pair's voltage row
    // itself and its current row its cutset.
    const int nb_all = static_cast<int>(g.branches.size());
    std::vector<double> not_capacitor(nb_all, 0.0), inductor_state(nb_all, 0.0), pair_link(nb_all, 0.0),
        every_link(nb_all, 1.0);
    for (int b = 0; b < nb_all; ++b) not_capacitor[b] = g.branches[b].cls != BranchClass::Capacitor;
    for (const StateInfo& state : m.states_)
      if (!state.capacitor) inductor_state[state.branch] = 1.0;
    for (const PairInfo& pr : m.pairs_)
      if (!t.in_tree[pr.branch]) pair_link[pr.branch] = 1.0;
    const CutsetSums cutsets(g, t);
    const std::vector<double> through_capacitors = cutsets.sums(not_capacitor), through_trees = cutsets.sums(inductor_state),
                              through_pairs = cutsets.sums(pair_link), through_any = cutsets.sums(every_link);
    double estimate = 0;
    for (const StateInfo& state : m.states_)
      if (state.capacitor) estimate += through_capacitors[state.branch];
    for (int f : t.tree) {
      estimate += through_pairs[f];
      if (g.branches[f].cls != BranchClass::Inductor) estimate += through_trees[f];
    }
    for (const PairInfo& pr : m.pairs_) estimate += 1.0 + (t.in_tree[pr.branch] ? through_any[pr.branch] : 0.0);
    const double dense = kSparseDensity * static_cast<double>(n + mp) * static_cast<double>(n + mp);
    std::unique_ptr<SparseDescriptor> descriptor;
    if (estimate > dense)
      descriptor = sparse_descriptor_if_worth(g, stamps, m.states_, m.pairs_, nu, static_cast<long>(estimate), true, false);
    if (descriptor) {
      m.sparse_descriptor_ = std::move(descriptor);
      m.energy_xx_ = MdynS;
      m.energy_xu_ = -Kdu;
      m.lcs_.Gamma = Eigen::MatrixXd::Zero(n, nu);
      auto rows = std::make_shared<PrimaryRows>(PrimaryRows{std::move(*maps), P});
      m.primary_rows_ = rows;
      m.defer_elimination([rows, states = m.states_, pairs = m.pairs_, MdynS, n, mp, nu, ncol, nb] {
        // What the formation below does for such a circuit: R = Rp P, Mdyn x' = R, the pairs'
        // branch rows and their outputs W.
        const PrimaryRows& r = *rows;
        const SparseMatrixD Rp = state_equation_rows(states, r.maps);
        SparseMatrixD Xdot(n, ncol);
        if (n > 0 && !solve_state_derivatives(MdynS, SparseMatrixD(Rp * SparseMatrixD(r.P_rows)), Xdot))
          throw std::logic_error("circuit model: a positive diagonal Mdyn was singular");
        RowSparse pair_v(mp, nb), pair_i(mp, nb);
        for (int k = 0; k < mp; ++k) {
          pair_v.startVec(k);
          r.maps.visit_row(true, pairs[k].branch, [&](int column, double value) { pair_v.insertBack(k, column) = value; });
          pair_i.startVec(k);
          r.maps.visit_row(false, pairs[k].branch, [&](int column, double value) { pair_i.insertBack(k, column) = value; });
        }
        pair_v.finalize();
        pair_i.finalize();
        std::vector<int> own_row(mp);
        for (int k = 0; k < mp; ++k) own_row[k] = k;
        const SparseMatrixD W = pair_output_rows(pairs, RowSparse(pair_v * r.P_rows), RowSparse(pair_i * r.P_rows),
                                                 own_row, n + mp);  // column of u_0
        auto lcs = std::make_shared<SparseLcs>();
        lcs->A = Xdot.leftCols(n);
        lcs->B = Xdot.middleCols(n, mp);
        lcs->C = W.leftCols(n);
        lcs->D = W.middleCols(n, mp);
        lcs->E = Xdot.middleCols(n + mp, nu);
        lcs->F = W.middleCols(n + mp, nu);
        return std::shared_ptr<const SparseLcs>(std::move(lcs));
      });
      return m;
    }
  }
  maps->materialise();
  SparseMatrixD Rp = state_equation_rows(m.states_, *maps);
  SparseMatrixD Rfull = Rp * P;  // forced rows of P are still zero and Rp never uses them
  release(Rp);

  // Perfectly coupled inductors (k = 1): Mdyn is singular and the flux-free currents are
  // algebraic (perfect_coupling.h). Change to the kept states xi, x = T xi + N eta(xi, z, u):
  // every row over [x z u du] becomes a row over [xi z u du], and the equations are projected
  // on T^T. Lf Tl N = 0 and Tc N = 0, so the forced rows below need only xi'.
  if (!flux.empty()) {  // small circuits (transformers): dense
    Eigen::MatrixXd Cmap;
    const Eigen::MatrixXd Rdense(Rfull);
    if (!substitute_flux_free(flux, Rdense, n, Cmap))
      throw flux_free_current_undetermined(netlist, g, inds, Eigen::MatrixXd(Tl * flux.N));
    const Eigen::MatrixXd& T = flux.T;
    P = (Eigen::MatrixXd(P) * Cmap).sparseView();
    p_entries.clear();
    for (int c = 0; c < P.outerSize(); ++c)
      for (SparseMatrixD::InnerIterator it(P, c); it; ++it) p_entries.emplace_back(it.row(), c, it.value());
    Rfull = (T.transpose() * Rdense * Cmap).sparseView();
    MdynS = (T.transpose() * Eigen::MatrixXd(MdynS) * T).sparseView();
    Kdu = T.transpose() * Kdu;
    Tc = Eigen::MatrixXd(Tc * T).sparseView();
    Tl = Eigen::MatrixXd(Tl * T).sparseView();
    m.states_ = magnetising_states(m.states_, flux);
    n = static_cast<int>(flux.kept.size());
    ncol = n + mp + 2 * nu;
  }
  // Stored energy over the (kept) states: the flux-free currents of a perfect coupling store none.
  m.energy_xx_ = MdynS;
  m.energy_xu_ = -Kdu;
  // Physical x' = A x + B z + E u + Gamma u': Mdyn x' = Rfull, whose du columns are Kdu (Rp never
  // reads du).
  SparseMatrixD Xdot(n, ncol);
  if (n > 0) {
    // Without source derivatives (no dependent storage: Kdu = 0, Rfull's du columns empty) R is
    // Rfull itself, taken without triplets (a multiplier's holds O(n^2) entries).
    bool du_free = Kdu.isZero(0) && Rfull.rows() == n && Rfull.cols() == ncol;
    for (int c = ncol - nu; c < ncol && du_free; ++c)
      du_free = !SparseMatrixD::InnerIterator(Rfull, c);
    SparseMatrixD R(n, ncol);
    if (du_free) {
      R = Rfull;
    } else {
      Triplets r;
      for (int c = 0; c < ncol - nu; ++c)
        for (SparseMatrixD::InnerIterator it(Rfull, c); it; ++it) r.emplace_back(it.row(), c, it.value());
      for (int c = 0; c < nu; ++c)
        for (int j = 0; j < n; ++j)
          if (Kdu(j, c) != 0) r.emplace_back(j, ncol - nu + c, Kdu(j, c));
      R.setFromTriplets(r.begin(), r.end());
    }
    if (!solve_state_derivatives(MdynS, R, Xdot)) {  // not expected once perfect couplings are reduced
      std::vector<int> elements;
      for (int b : inds) elements.push_back(g.branches[b].element);
      throw TopologyError("the inductance matrix is singular", elements);
    }
  }
  release(Rfull);
  Lcs& s = m.lcs_;
  s.E = Xdot.middleCols(n + mp, nu);
  s.Gamma = Xdot.rightCols(nu);

  // Forced unknowns: link capacitor currents C v', tree inductor voltages Lf i'. Only a circuit
  // with some pays for Xdot by rows (O(n^2) entries for a multiplier).
  if (std::find(role.begin(), role.end(), Role::Forced) != role.end()) {
    const RowSparse TcRows = Tc, LfRows = Lf, XdotRows = Xdot;
    RowSparse TlRows = Tl;
    Eigen::RowVectorXd row(ncol);
    for (int b = 0; b < nb; ++b) {
      if (role[b] != Role::Forced) continue;
      row.setZero();
      if (g.branches[b].cls == BranchClass::Capacitor) {
        const int k = cap_index[b];
        row.tail(nu) = Cd(k) * Tcu.row(k);
        for (RowSparse::InnerIterator it(TcRows, k); it; ++it)
          row += Cd(k) * it.value() * Eigen::RowVectorXd(XdotRows.row(it.col()));
      } else {  // Lf_k (Tl x' + Tlu u')
        const int k = ind_index[b];
        for (RowSparse::InnerIterator l(LfRows, k); l; ++l) {
          row.tail(nu) += l.value() * Tlu.row(l.col());
          for (RowSparse::InnerIterator it(TlRows, l.col()); it; ++it)
            row += l.value() * it.value() * Eigen::RowVectorXd(XdotRows.row(it.col()));
        }
      }
      for (int c = 0; c < ncol; ++c)
        if (row(c) != 0) p_entries.emplace_back(b, c, row(c));
    }
    P.setFromTriplets(p_entries.begin(), p_entries.end());
  }
  {  // by rows throughout: a multiplier's link voltages hold O(n^2) entries, converted never
    const RowSparse Prows = P;
    m.branch_v_ = maps->voltage_map() * Prows;
    m.branch_i_ = maps->current_map() * Prows;
  }
  maps.reset();

  // Complementarity outputs w, sparse like the branch rows.
  std::vector<int> pair_branch(mp);
  for (int k = 0; k < mp; ++k) pair_branch[k] = m.pairs_[k].branch;
  SparseMatrixD W = pair_output_rows(m.pairs_, m.branch_v_, m.branch_i_, pair_branch, col_u(0));
  s.F = W.middleCols(n + mp, nu);
  // The shift x_lcs = x_phys - Gamma u: x_lcs' = A x_lcs + B z + (E + A Gamma) u.
  SparseMatrixD A_sparse = Xdot.leftCols(n), C_sparse = W.leftCols(n);
  if (!s.Gamma.isZero(0)) {  // O(nnz(A) + nnz(C)) per input; nothing to add without dependent storage
    s.E += A_sparse * s.Gamma;
    s.F += C_sparse * s.Gamma;
  }
  // A, B, C, D: kept sparse for a large sparse circuit and for a circuit that steps on its
  // descriptor form (lcs() forms the dense ones when asked), dense for the others. Moved, not
  // copied: a multiplier's A and C hold O(n^2) entries.
  SparseLcs formed{std::move(A_sparse), SparseMatrixD(Xdot.middleCols(n, mp)), std::move(C_sparse),
                   SparseMatrixD(W.middleCols(n, mp)), s.E, s.F};
  release(Xdot);
  release(W);
  if (sparse_lcs_worth(formed)) {
    m.sparse_lcs_ = std::make_shared<const SparseLcs>(std::move(formed));
    m.defer_dense(m.sparse_lcs_);
  } else {  // a dense LCS of a sparse circuit: its steps keep the static unknowns
    m.sparse_descriptor_ = sparse_descriptor_if_worth(g, stamps, m.states_, m.pairs_, nu, lcs_nonzeros(formed),
                                                      s.Gamma.size() == 0 || s.Gamma.cwiseAbs().maxCoeff() == 0,
                                                      !stamps.delayed.empty());
    if (m.sparse_descriptor_ || !dense_within_budget(n, mp, 1)) {
      // Over the dense budget: lcs() refuses, and so do the methods that would ask (dense_budget.h).
      m.defer_dense(std::make_shared<const SparseLcs>(std::move(formed)));
    } else {
      s.A = formed.A;
      s.B = formed.B;
      s.C = formed.C;
      s.D = formed.D;
    }
  }

  // The waves the line ports send, and the lines' DC relations, as rows like the probes'.
  auto row_of = [&](const std::vector<Term>& terms) {
    Eigen::RowVectorXd r = Eigen::RowVectorXd::Zero(ncol);
    for (const Term& term : terms) {
      switch (term.of) {
        case Term::Of::Voltage: r += term.coeff * Eigen::RowVectorXd(m.branch_v_.row(term.index)); break;
        case Term::Of::Current: r += term.coeff * Eigen::RowVectorXd(m.branch_i_.row(term.index)); break;
        case Term::Of::Input: r(col_u(term.index)) += term.coeff; break;
      }
    }
    return m.row_from_physical(r);
  };
  for (const Stamps::Delayed& d : stamps.delayed) {
    const OutputRow row = row_of(d.wave);
    m.delayed_.push_back({d.input, d.delay, row.g, row.h, row.j, d.before});
  }
  for (const std::vector<Term>& terms : stamps.dc_relations) {
    const OutputRow row = row_of(terms);
    m.dc_relations_.push_back({-1, 0, row.g, row.h, row.j, 0});
  }
  if (m.dc_relations_.size() != m.delayed_.size())
    throw std::logic_error("circuit model: devices with history owe one DC relation per history input");
  return m;
}

OutputRow CircuitModel::row_from_physical(const Eigen::RowVectorXd& r) const {
  const int n = state_count(), mp = pair_count(), nu = input_count();
  OutputRow o;
  o.g = r.segment(0, n);
  o.h = r.segment(n, mp);
  o.j = r.segment(n + mp, nu) + o.g * lcs_.Gamma;
  o.k = r.segment(n + mp + nu, nu);
  return o;
}

Eigen::RowVectorXd CircuitModel::branch_row(int branch, bool voltage) const {
  if (!primary_rows_) return Eigen::RowVectorXd((voltage ? branch_v_ : branch_i_).row(branch));
  const PrimaryRows& r = *primary_rows_;  // the row of the product (Vmap or Imap) P, summed as there
  Eigen::RowVectorXd out = Eigen::RowVectorXd::Zero(r.P_rows.cols());
  r.maps.visit_row(voltage, branch, [&](int column, double value) {
    for (RowSparse::InnerIterator p(r.P_rows, column); p; ++p) out(p.col()) += value * p.value();
  });
  return out;
}

OutputRow CircuitModel::branch_voltage(int branch) const {
  return row_from_physical(branch_row(branch, true));
}

OutputRow CircuitModel::branch_current(int branch) const {
  return row_from_physical(branch_row(branch, false));
}

// v(node) = v(parent) + sign * v(the tree branch from the parent), memoised: summing each node's
// whole tree path cost O(depth * columns) per node, O(n^3) for a chain-like tree (a multiplier).
Eigen::RowVectorXd CircuitModel::node_row(int node) const {
  if (node_rows_.empty()) {
    node_rows_.assign(graph_.nodes.size(), Eigen::SparseVector<double>(row_columns()));
    node_row_known_.assign(graph_.nodes.size(), false);
    node_row_known_[0] = true;  // ground
  }
  std::vector<int> pending;  // node, then its ancestors, up to the first known one
  for (int v = node; !node_row_known_.at(v); v = tree_.parent[v]) pending.push_back(v);
  for (auto it = pending.rbegin(); it != pending.rend(); ++it) {
    const LoopTerm& last = tree_.to_parent[*it];
    const Eigen::SparseVector<double> step = primary_rows_ ? Eigen::SparseVector<double>(branch_row(last.branch, true).transpose().sparseView())
                                                            : Eigen::SparseVector<double>(branch_v_.row(last.branch).transpose());
    node_rows_[*it] = node_rows_[tree_.parent[*it]] + static_cast<double>(last.sign) * step;
    node_row_known_[*it] = true;
  }
  return Eigen::RowVectorXd(node_rows_[node].transpose());
}

OutputRow CircuitModel::node_voltage(int node) const {
  return row_from_physical(node_row(node));
}

double CircuitModel::evaluate(const OutputRow& row, const Eigen::VectorXd& x,
                              const Eigen::VectorXd& z, double t) const {
  return row.g.dot(x) + row.h.dot(z) + row.j.dot(input_values(t)) +
         row.k.dot(input_derivatives(t));
}

double CircuitModel::evaluate_dc(const OutputRow& row, const Eigen::VectorXd& x,
                                 const Eigen::VectorXd& z, double t) const {
  return row.g.dot(x) + row.h.dot(z) + row.j.dot(input_values(t));
}

std::vector<Probe> CircuitModel::default_probes() const {
  std::vector<Probe> probes;
  // Nodes inside a device (a lossy line's state nodes, "o1#y1_0") are not the circuit's.
  for (size_t node = 1; node < graph_.nodes.size(); ++node)
    if (graph_.nodes[node].find('#') == std::string::npos)
      probes.push_back({Probe::Kind::NodeVoltage, graph_.nodes[node], "", {}});
  for (const std::shared_ptr<Device>& d : devices_) {
    if (d->name().find('#') != std::string::npos) continue;  // an element's parasitic ("l1#rser")
    if (d->current_probed_by_default()) probes.push_back({Probe::Kind::ElementCurrent, d->name(), "", {}});
    for (char terminal : d->terminals_probed_by_default()) {
      Probe p{Probe::Kind::TerminalCurrent, d->name(), "", {}};
      p.terminal = terminal;
      probes.push_back(p);
    }
  }
  return probes;
}

OutputRow CircuitModel::device_current(const Device& d, const std::vector<std::pair<int, double>>& terms) const {
  int first = -1;  // the device's branches are consecutive in the graph
  for (int b = 0; b < static_cast<int>(graph_.branches.size()) && first < 0; ++b)
    if (graph_.branches[b].element == d.element_index()) first = b;
  Eigen::RowVectorXd r = Eigen::RowVectorXd::Zero(row_columns());
  for (auto [local, coeff] : terms) r += coeff * branch_row(first + local, false);
  return row_from_physical(r);
}

OutputRow CircuitModel::terminal_current(const Probe& p) const {
  for (const std::shared_ptr<Device>& d : devices_) {
    if (d->name() != p.a) continue;
    const std::vector<std::pair<int, double>> terms = d->terminal_current(p.terminal);
    if (terms.empty()) break;
    return device_current(*d, terms);
  }
  throw NetlistError(p.loc, "probe " + p.name() + ": no transistor '" + p.a + "'");
}

OutputMap CircuitModel::output_map(const std::vector<Probe>& probes) const {
  const int n = state_count(), mp = pair_count(), nu = input_count();
  const int rows = static_cast<int>(probes.size());
  OutputMap out;
  std::vector<Eigen::Triplet<double>> g_entries, h_entries;
  std::unordered_map<std::string, int> branch_by_name;  // made at the first current probe
  out.J = Eigen::MatrixXd::Zero(rows, nu);
  out.K = Eigen::MatrixXd::Zero(rows, nu);
  auto node = [&](const Probe& p, const std::string& name) {
    int index = graph_.node_index(name);
    if (index < 0) throw NetlistError(p.loc, "probe " + p.name() + ": no node '" + name + "'");
    return index;
  };
  for (int r = 0; r < rows; ++r) {
    const Probe& p = probes[r];
    OutputRow row;
    switch (p.kind) {
      case Probe::Kind::NodeVoltage:
        row = node_voltage(node(p, p.a));
        break;
      case Probe::Kind::NodePairVoltage: {
        OutputRow a = node_voltage(node(p, p.a)), b = node_voltage(node(p, p.b));
        row = {a.g - b.g, a.h - b.h, a.j - b.j, a.k - b.k};
        break;
      }
      case Probe::Kind::TerminalCurrent:
        row = terminal_current(p);
        break;
      case Probe::Kind::ElementCurrent: {
        if (branch_by_name.empty())  // the last branch of a name, as a scan from the front finds
          for (int b = 0; b < static_cast<int>(graph_.branches.size()); ++b) branch_by_name[graph_.branches[b].name] = b;
        const auto found = branch_by_name.find(p.a);
        const int branch = found == branch_by_name.end() ? -1 : found->second;
        if (branch < 0)
          throw NetlistError(p.loc, "probe " + p.name() + ": no two-terminal element '" + p.a + "'");
        const int element = graph_.branches[branch].element;
        // A device's own name is its i(element) (a diode with breakdown: both branches); its
        // other branches ("d1:bv") are probed alone.
        const bool whole = element >= 0 && devices_[element]->name() == p.a;
        const std::vector<std::pair<int, double>> terms =
            whole ? devices_[element]->element_current() : std::vector<std::pair<int, double>>{};
        row = terms.empty() ? branch_current(branch) : device_current(*devices_[element], terms);
        break;
      }
    }
    out.names.push_back(p.name());
    // Row blocks of a 0-column matrix point at null (UBSan): only non-empty ones are copied.
    for (int c = 0; c < n; ++c)
      if (row.g(c) != 0) g_entries.emplace_back(r, c, row.g(c));
    for (int c = 0; c < mp; ++c)
      if (row.h(c) != 0) h_entries.emplace_back(r, c, row.h(c));
    out.J.row(r) = row.j;  // nu >= 1: u[0] = 1 is always an input
    out.K.row(r) = row.k;
  }
  out.G.resize(rows, n);
  out.G.setFromTriplets(g_entries.begin(), g_entries.end());
  out.H.resize(rows, mp);
  out.H.setFromTriplets(h_entries.begin(), h_entries.end());
  return out;
}

}  // namespace lcs
