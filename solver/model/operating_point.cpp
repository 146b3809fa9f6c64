#include "solver/model/operating_point.h"

#include "solver/lcp/sparse_active_set.h"
#include "solver/model/sparse_lcs.h"
#include "solver/model/descriptor_operating_point.h"
#include "solver/model/empty_safe.h"

#include <algorithm>
#include <map>
#include <optional>
#include <set>

#include "solver/lcp/lcp.h"
#include "solver/lcp/p_matrix.h"
#include "solver/model/numerical_failure.h"

namespace lcs {

namespace {

double max_abs(const Eigen::VectorXd& v) { return v.size() > 0 ? v.cwiseAbs().maxCoeff() : 0.0; }

struct StaticProblem {
  Eigen::MatrixXd M;        // D - C A^-1 B
  Eigen::VectorXd q;        // (F - C A^-1 E) u
  Eigen::MatrixXd XofZ;     // x = XofZ z + x0
  Eigen::VectorXd x0;
  std::vector<std::string> undetermined;
};

// The DC form of the LCS. A line at DC carries constant waves; its history inputs u_h join the
// states as unknowns of the static problem, fixed by the line's DC relations (rows Rx x + Rz z +
// Ru u = 0: the through connection v1 = v2, i1 = -i2 of a lossless line, the DC two-port of a
// lossy one). (The waves' own delay equations u_h = a(x, z, u) say the same for a lossless
// line but are degenerate for a lossy one with G = 0: its fitted kernel knows the DC resistance
// only as a limit.)
//   [A  E_h; Rx  Ru_h] [x; u_h] + [B; Rz] z + [E_o u_o; Ru_o u_o] = 0,   w = [C F_h][x; u_h] + D z + F_o u_o
// with the other inputs u_o at their value at t.
struct DcForm {
  Eigen::MatrixXd A, B, C, D;
  Eigen::VectorXd e, f;  // the inputs' part of the state rows and of w
  int n = 0;             // LCS states; the unknowns are the n states, then the history inputs
};

DcForm dc_form(const CircuitModel& model, double t) {
  const Lcs& s = model.lcs();
  const int n = s.states(), m = s.pairs();
  const std::vector<DelayedWave>& waves = model.delayed();
  const int nh = static_cast<int>(waves.size());
  Eigen::VectorXd u = model.input_values(t);
  for (const DelayedWave& w : waves) u(w.input) = 0;  // u_o: the history inputs are unknowns
  DcForm f;
  f.n = n;
  f.A = Eigen::MatrixXd::Zero(n + nh, n + nh);
  f.B = Eigen::MatrixXd::Zero(n + nh, m);
  f.C = Eigen::MatrixXd::Zero(m, n + nh);
  f.D = s.D;
  f.e = Eigen::VectorXd::Zero(n + nh);
  f.f = s.F * u;
  if (n > 0) {  // blocks of empty matrices point past null (UBSan)
    f.A.topLeftCorner(n, n) = s.A;
    if (m > 0) f.B.topRows(n) = s.B;
    if (m > 0) f.C.leftCols(n) = s.C;
    f.e.head(n) = s.E * u;
  }
  for (int k = 0; k < nh; ++k) {
    const DelayedWave& w = waves[k];
    if (n > 0) f.A.block(0, n + k, n, 1) = s.E.col(w.input);
    if (m > 0) f.C.col(n + k) = s.F.col(w.input);
    const DelayedWave& r = model.dc_relations()[k];
    if (n > 0) f.A.block(n + k, 0, 1, n) = r.g;
    for (int j = 0; j < nh; ++j) f.A(n + k, n + j) = r.j(waves[j].input);
    if (m > 0) f.B.row(n + k) = r.h;
    f.e(n + k) = r.j.dot(u);
  }
  return f;
}

std::string unknown_label(const CircuitModel& model, int j) {
  const int n = model.state_count();
  if (j < n) return model.states()[j].label;
  return "the DC wave " + model.inputs()[model.delayed()[j - n].input].label;
}

StaticProblem static_problem(const CircuitModel& model, double t, double regularisation = 1e-9) {
  const DcForm f = dc_form(model, t);
  const int n = static_cast<int>(f.A.rows());
  StaticProblem p;
  Eigen::MatrixXd A = f.A;
  if (n > 0) {
    Eigen::FullPivLU<Eigen::MatrixXd> lu(A);
    if (!lu.isInvertible()) {
      Eigen::MatrixXd kernel = lu.kernel();
      for (int j = 0; j < n; ++j)
        if (kernel.row(j).cwiseAbs().maxCoeff() > 1e-9) p.undetermined.push_back(unknown_label(model, j));
      // A leak across each capacitor on the scale of the largest state coefficient (a GMIN); a
      // line's DC-relation rows (i1 + i2 = 0, v1 - v2 = R len i1: coefficients ~1) on their own
      // scale: on the states' (a fitted line's poles, ~1e10 s^-1) they read i1 + i2 = 10 S x wave.
      const double states = f.n > 0 ? A.topRows(f.n).cwiseAbs().maxCoeff() : 0.0;
      for (int j = 0; j < n; ++j) {
        const double row = A.row(j).cwiseAbs().maxCoeff();
        const double scale = j < f.n ? states : row;
        A(j, j) -= regularisation * (scale > 0 ? scale : 1.0);
      }
    }
    Eigen::PartialPivLU<Eigen::MatrixXd> lu_reg(A);
    p.XofZ = -solve_or_empty(lu_reg, f.B);
    p.x0 = -solve_or_empty(lu_reg, Eigen::MatrixXd(f.e));
  } else {
    p.XofZ = Eigen::MatrixXd::Zero(0, f.D.rows());
    p.x0 = Eigen::VectorXd::Zero(0);
  }
  p.M = f.D + f.C * p.XofZ;
  p.q = f.f + f.C * p.x0;
  return p;
}

// Splits the unknowns [x; u_h] of a polished point into the LCS state and the lines' DC waves,
// and makes those the lines' past (history inputs read at t are then this point's).
void finish(const CircuitModel& model, OperatingPoint& op) {
  const int n = model.state_count();
  if (op.x.size() == n) return;
  op.history.assign(op.x.data() + n, op.x.data() + op.x.size());
  op.x = Eigen::VectorXd(op.x.head(n));
  model.begin_history(op.history);
}

OperatingPoint point_from(const StaticProblem& p, const Eigen::VectorXd& z) {
  OperatingPoint op;
  op.z = z;
  op.x = p.XofZ * z + p.x0;
  op.undetermined = p.undetermined;
  return op;
}

// Moves sol = [x; z_J] within the solutions sol + N c of the DC equations (N: their kernel) to
// the one of least stored energy W(x) (CircuitModel::energy_xx/xu). A loop of inductors only
// carries a circulating current, and capacitors in series share a charge, that DC does not fix;
// of all of them, least energy is the one a circuit switched on from rest reaches (inductors in
// parallel take currents inversely proportional to L, series capacitors the capacitive divider),
// and it is one choice shared by `op` and every method (SPEC §2; issue 9, defect 5).
//   min_c W(x + N_x c)  <=>  (N_x^T Wxx N_x) c = -N_x^T (Wxx (x + Gamma u) + Wxu u)
Eigen::VectorXd least_energy(const CircuitModel& model, const Eigen::VectorXd& u,
                             const Eigen::MatrixXd& N, const Eigen::VectorXd& sol) {
  const int n = model.lcs().states();
  if (n == 0 || N.cols() == 0) return sol;
  const Eigen::MatrixXd Nx = N.topRows(n);
  const Eigen::VectorXd x_phys = sol.head(n) + model.lcs().Gamma * u;
  const Eigen::MatrixXd H = Nx.transpose() * model.energy_xx() * Nx;
  const Eigen::VectorXd g = Nx.transpose() * (model.energy_xx() * x_phys + model.energy_xu() * u);
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(H);
  cod.setThreshold(1e-12);
  return sol - N * cod.solve(g);
}

// With the conducting set J = {z_i > 0} known, the operating point solves the linear system
//   A x + B_J z_J = -E u,   C_J x + D_JJ z_J = -F_J u
// exactly. This replaces the regularised solution, whose x = (B z + E u)/eps loses every digit
// when A is singular only because a diode current is what holds a state (a capacitor charged
// through a diode). States the system leaves free take the values of least stored energy
// (least_energy). Returns false when the result is not complementary.
bool polish(const CircuitModel& model, double t, OperatingPoint& op) {
  const DcForm s = dc_form(model, t);
  const int n = static_cast<int>(s.A.rows()), m = static_cast<int>(s.D.rows());
  std::vector<int> J;
  for (int i = 0; i < m; ++i)
    if (op.z(i) > 0) J.push_back(i);
  const int k = static_cast<int>(J.size());
  if (n + k == 0) return true;
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n + k, n + k);
  Eigen::VectorXd rhs(n + k);
  K.topLeftCorner(n, n) = s.A;
  rhs.head(n) = -s.e;
  for (int a = 0; a < k; ++a) {
    if (n > 0) {  // a row or column block of an empty matrix points past null (UBSan)
      K.block(0, n + a, n, 1) = s.B.col(J[a]);
      K.block(n + a, 0, 1, n) = s.C.row(J[a]);
    }
    for (int c = 0; c < k; ++c) K(n + a, n + c) = s.D(J[a], J[c]);
    rhs(n + a) = -s.f(J[a]);
  }
  // Row scaling: the rows mix 1/C-sized and ohm-sized coefficients.
  Eigen::VectorXd scale = K.cwiseAbs().rowwise().maxCoeff();
  for (int r = 0; r < n + k; ++r) scale(r) = scale(r) > 0 ? 1.0 / scale(r) : 1.0;
  Eigen::MatrixXd Ks = scale.asDiagonal() * K;
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(Ks);
  cod.setThreshold(1e-12);
  const Eigen::VectorXd min_norm = cod.solve(scale.asDiagonal() * rhs);
  const double residual = (Ks * min_norm - scale.asDiagonal() * rhs).cwiseAbs().maxCoeff();
  if (!(residual <= 1e-9 * std::max(1.0, max_abs(scale.asDiagonal() * rhs))))
    return false;
  std::vector<std::string> undetermined;
  std::vector<Eigen::VectorXd> candidates;
  if (cod.rank() < n + k) {
    Eigen::FullPivLU<Eigen::MatrixXd> lu(Ks);
    lu.setThreshold(1e-12);
    const Eigen::MatrixXd kernel = lu.rank() < n + k ? Eigen::MatrixXd(lu.kernel())
                                                     : Eigen::MatrixXd(n + k, 0);
    for (int j = 0; j < n; ++j)
      if (kernel.cols() > 0 && kernel.row(j).cwiseAbs().maxCoeff() > 1e-9)
        undetermined.push_back(unknown_label(model, j));
    candidates.push_back(least_energy(model, model.input_values(t), kernel, min_norm));
  }
  candidates.push_back(min_norm);  // when least energy would turn a diode current negative
  for (const Eigen::VectorXd& sol : candidates) {
    Eigen::VectorXd z = Eigen::VectorXd::Zero(m);
    for (int a = 0; a < k; ++a) z(J[a]) = sol(n + a);
    const Eigen::VectorXd x = sol.head(n);
    const Eigen::VectorXd w = s.C * x + s.D * z + s.f;
    const double tol = 1e-9 * std::max({1.0, max_abs(w), max_abs(z)});
    bool complementary = true;
    for (int i = 0; i < m; ++i)
      if (z(i) < -tol || w(i) < -tol) complementary = false;
    if (!complementary) continue;
    op.x = x;
    op.z = z.cwiseMax(0.0);
    op.undetermined = undetermined;
    return true;
  }
  return false;
}

// Lemke's numerical failure on the static LCP. Where the DC network ties nodes only through
// junctions (the emitters of a differential pair fed by a transistor's collector, the node
// between two diode-connected transistors), A is singular and the regularised M = D - C A^-1 B
// carries entries ~1/eps (1e12 next to 1e3, condition ~1e13): Lemke's tableau on it drifts and
// ends on a complementary basis a pivot or two from the solution. The regularisation is a
// conductance eps across each capacitor (a GMIN); a larger one keeps M well conditioned, and the
// conducting set Lemke finds with it is then solved exactly on the unreduced DC equations (no
// regularisation) by polish, which accepts it only if the result is complementary.
bool repair_numerical_failure(const CircuitModel& model, double t, OperatingPoint& op) {
  if (polish(model, t, op)) return true;
  for (double regularisation : {1e-7, 1e-5, 1e-3}) {
    const StaticProblem p = static_problem(model, t, regularisation);
    if (p.undetermined.empty()) return false;  // A regular: no regularisation to relax
    const LcpSolution sol = solve_lemke(p.M, p.q);
    if (sol.status != LcpStatus::Solved && sol.status != LcpStatus::NumericalFailure) continue;
    OperatingPoint trial = point_from(p, sol.z);
    if (!polish(model, t, trial)) continue;
    op = trial;
    return true;
  }
  return false;
}

// Where A is singular the regularised M has solutions of its own: a junction held "off" by the
// 1e-9 leak the regularisation puts across a capacitor (a differential pair's emitter node, fed
// only by a transistor's collector, lets either side take the whole tail current). Only the
// solutions whose conducting set solves the unreduced DC equations complementarily (polish) are
// the circuit's; if none does, the enumeration is kept as it is.
// Two of them may be one point: a pair at a degenerate vertex given a current of rounding (a diode
// between two junctions of a DTL gate's level shifter, its middle node reached only through them)
// is at zero current once polished, as in the solution that had it off. Such solutions count once
// (equal polished x and z, entry by entry), with A regular or not.
std::vector<Eigen::VectorXd> exact_solutions(const CircuitModel& model, double t, const StaticProblem& p,
                                             const std::vector<Eigen::VectorXd>& zs) {
  std::vector<Eigen::VectorXd> exact;
  std::vector<OperatingPoint> points;
  // Entry by entry, to 1e-9 of the entry, above a floor of 1e-12 of the largest (the rounding a
  // degenerate vertex leaves) and of each entry's own rounding (`rounding`, where given): a floor
  // of 1e-9 of the largest let a -1e10 V source elsewhere in the deck merge a flip-flop's two
  // latch states.
  auto same = [](const Eigen::VectorXd& a, const Eigen::VectorXd& b, const Eigen::VectorXd& rounding) {
    if (a.size() != b.size()) return false;
    if (a.size() == 0) return true;
    const double floor = 1e-12 * std::max({1e-300, max_abs(a), max_abs(b)});
    for (Eigen::Index i = 0; i < a.size(); ++i) {
      const double level = i < rounding.size() ? std::max(floor, rounding(i)) : floor;
      if (std::abs(a(i) - b(i)) > 1e-9 * std::max(std::abs(a(i)), std::abs(b(i))) + level) return false;
    }
    return true;
  };
  // Two points with the same states and the same pair currents are one: they differ only in the
  // potential of a node reached only through pairs that carry nothing (a Darlington's middle node
  // with both transistors off, anywhere between its junctions' thresholds), which the run warns
  // about on its own. A pair's current is z, or w for a voltage-type (tree) pair, w = M z + q; its
  // rounding there, 1e-12 of the terms that make it. Before, such a node at either end of its
  // range read as two operating points, and the run stopped.
  const std::vector<PairInfo>& pairs = model.pairs();
  auto currents = [&](const Eigen::VectorXd& z, Eigen::VectorXd& rounding) {
    Eigen::VectorXd c = z;
    rounding = Eigen::VectorXd::Zero(z.size());
    if (p.M.rows() != z.size() || static_cast<Eigen::Index>(pairs.size()) != z.size()) return c;
    const Eigen::VectorXd w = p.M * z + p.q;
    for (Eigen::Index i = 0; i < z.size(); ++i)
      if (pairs[i].voltage_type) {
        c(i) = w(i);
        rounding(i) = 1e-12 * (std::abs(p.q(i)) + p.M.row(i).cwiseAbs().dot(z.cwiseAbs()));
      }
    return c;
  };
  std::vector<std::pair<Eigen::VectorXd, Eigen::VectorXd>> point_currents;  // per kept point, with rounding
  // Not where an element reads a node's potential (E, G, a switch's control): there the free
  // potential is an input, and the points differ (a G source on a Darlington's middle node).
  const bool reads_potentials =
      std::any_of(model.netlist().elements.begin(), model.netlist().elements.end(), [](const Element& e) {
        return e.kind == ElementKind::Vcvs || e.kind == ElementKind::Vccs || e.kind == ElementKind::VSwitch;
      });
  std::vector<bool> free_state(model.state_count(), false);  // the states p.undetermined names
  for (int j = 0; j < model.state_count(); ++j)
    free_state[j] = std::find(p.undetermined.begin(), p.undetermined.end(), model.states()[j].label) !=
                    p.undetermined.end();
  // A state's rounding, x = XofZ z + x0: 1e-12 of the terms that make it, and of the sources'
  // scale (a Zener reference's collector capacitance at 1.3e-15 V in one point, 0 in the other).
  const double source_scale = std::max(p.q.size() > 0 ? max_abs(p.q) : 0.0, p.x0.size() > 0 ? max_abs(p.x0) : 0.0);
  auto state_rounding = [&](const Eigen::VectorXd& z) -> Eigen::VectorXd {
    if (p.XofZ.cols() != z.size() || p.XofZ.rows() != p.x0.size()) return {};
    return 1e-12 * (p.XofZ.cwiseAbs() * z.cwiseAbs() + p.x0.cwiseAbs() +
                    Eigen::VectorXd::Constant(p.x0.size(), source_scale));
  };
  for (const Eigen::VectorXd& z : zs) {
    OperatingPoint op = point_from(p, z);
    if (!polish(model, t, op) && !p.undetermined.empty()) continue;  // regular: the solution stands as it is
    Eigen::VectorXd rounding;
    const Eigen::VectorXd c = currents(op.z, rounding);
    bool seen = false;
    for (std::size_t k = 0; k < points.size() && !seen; ++k) {
      const Eigen::VectorXd both = rounding.cwiseMax(point_currents[k].second);
      const Eigen::VectorXd x_rounding = state_rounding(op.z).cwiseMax(state_rounding(points[k].z));
      if (same(points[k].x, op.x, x_rounding) && same(points[k].z, op.z, {})) {
        seen = true;
      } else if (!reads_potentials && same(point_currents[k].first, c, both)) {
        // The same currents: the states the DC equations leave free (a junction capacitance on
        // the floating node, which least energy sets from the node's potential) may differ too.
        Eigen::VectorXd xa = points[k].x, xb = op.x;
        for (Eigen::Index j = 0; j < xa.size() && j < static_cast<Eigen::Index>(free_state.size()); ++j)
          if (free_state[j]) xa(j) = xb(j) = 0;
        seen = same(xa, xb, x_rounding);
      }
    }
    if (seen) continue;
    points.push_back(op);
    point_currents.push_back({c, rounding});
    exact.push_back(z);
  }
  return exact.empty() ? zs : exact;
}

// The elements (transistors) whose pairs are on in some solutions and off in others.
std::vector<std::string> elements_that_differ(const CircuitModel& model, const std::vector<Eigen::VectorXd>& zs) {
  std::vector<std::string> names;
  const double scale = std::max(1e-300, [&] {
    double big = 0;
    for (const Eigen::VectorXd& z : zs) big = std::max(big, max_abs(z));
    return big;
  }());
  for (int i = 0; i < static_cast<int>(model.pairs().size()); ++i) {
    bool on = false, off = false;
    for (const Eigen::VectorXd& z : zs) (z(i) > 1e-9 * scale ? on : off) = true;
    if (!(on && off)) continue;
    const std::string& name = model.netlist().elements.at(model.pairs()[i].element).name;
    if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
  }
  return names;
}

// OFF on a D or Q card is ngspice's start of its DC iteration with that device off; here it
// keeps, of several operating points, those in which every such device carries no pair current.
// If none has them all off the card is no guide, and every point stays.
std::vector<Eigen::VectorXd> with_off_devices_off(const CircuitModel& model, const std::vector<Eigen::VectorXd>& zs,
                                                  std::vector<std::string>& off_names) {
  const Netlist& netlist = model.netlist();
  std::vector<int> off_pairs;
  for (int i = 0; i < static_cast<int>(model.pairs().size()); ++i) {
    const Element& e = netlist.elements.at(model.pairs()[i].element);
    if (e.kind != ElementKind::Bjt && e.kind != ElementKind::Diode) continue;
    if (e.initially_on.value_or(true)) continue;
    off_pairs.push_back(i);
    if (std::find(off_names.begin(), off_names.end(), e.name) == off_names.end()) off_names.push_back(e.name);
  }
  if (off_pairs.empty()) return zs;
  double scale = 1e-300;
  for (const Eigen::VectorXd& z : zs) scale = std::max(scale, max_abs(z));
  std::vector<Eigen::VectorXd> kept;
  for (const Eigen::VectorXd& z : zs)
    if (std::all_of(off_pairs.begin(), off_pairs.end(), [&](int i) { return z(i) <= 1e-9 * scale; })) kept.push_back(z);
  if (kept.empty()) off_names.clear();
  return kept.empty() ? zs : kept;
}

// The operating point of solution z, polished and finished.
OperatingPoint finished_point(const CircuitModel& model, const StaticProblem& p, double t, const Eigen::VectorXd& z) {
  OperatingPoint op = point_from(p, z);
  polish(model, t, op);
  finish(model, op);
  return op;
}

OperatingPoint choose_among(const CircuitModel& model, const StaticProblem& p, double t,
                            const std::vector<Eigen::VectorXd>& all) {
  const std::vector<std::string> differ = elements_that_differ(model, all);
  const Netlist& netlist = model.netlist();
  const bool transistors = std::all_of(differ.begin(), differ.end(), [&](const std::string& name) {
    return std::any_of(netlist.elements.begin(), netlist.elements.end(),
                       [&](const Element& e) { return e.name == name && e.kind == ElementKind::Bjt; });
  });
  const char* kind = transistors ? (differ.size() == 1 ? "transistor " : "transistors ")
                                 : (differ.size() == 1 ? "element " : "elements ");
  const std::string who = differ.empty() ? std::string("the circuit") : kind + join_names(differ);
  const std::string count = std::to_string(all.size()) + " operating points";
  std::vector<std::string> off_names;
  const std::vector<Eigen::VectorXd> zs = with_off_devices_off(model, all, off_names);
  if (zs.size() == 1) {
    OperatingPoint op = finished_point(model, p, t, zs[0]);
    op.warnings.push_back("the circuit has " + count + " (" + who + "); the one with " + join_names(off_names) +
                          " off (OFF on the card) is taken (`op --all` lists them)");
    return op;
  }
  const std::map<std::string, double> hints = node_hints(model.netlist());
  // The smoothed circuit's ideal start (its junctions' lines at VON = 0, RON = RS: parallel
  // junctions share any split, chains of them tie) is only Newton's first guess for the Shockley
  // junctions' own operating point (smooth_method.h). A DTL gate's input diodes, both at 0 V,
  // gave 2 such points, and `--method smooth` (and `--diode auto`, which chose it) stopped at
  // t = 0. The first is taken and the others kept: the smooth method seeks the Shockley point
  // from each and stops only if they differ (a flip-flop).
  if (hints.empty() && model.netlist().smooth_junctions) {
    OperatingPoint op = finished_point(model, p, t, zs[0]);
    for (std::size_t k = 1; k < zs.size(); ++k) {
      const OperatingPoint other = finished_point(model, p, t, zs[k]);
      op.other_starts.push_back({other.x, other.z});
    }
    return op;
  }
  if (hints.empty())
    throw NumericalFailure(t, "the operating point is not unique: " + count + " (" + who +
                                  " on in some, off in others); list them with `op --all` and choose "
                                  "one with .ic or .nodeset node voltages (the nearest is taken)");
  std::vector<std::pair<double, int>> distance;
  for (int k = 0; k < static_cast<int>(zs.size()); ++k) {
    const OperatingPoint op = finished_point(model, p, t, zs[k]);
    distance.push_back({hint_distance(model, hints, op.x, op.z, t), k});
  }
  std::sort(distance.begin(), distance.end());
  if (distance[1].first - distance[0].first <= 1e-12 * std::max(1.0, distance[0].first))
    throw NumericalFailure(t, "the operating point is not unique: " + count + " (" + who +
                                  "), and the .ic/.nodeset values are as near to two of them; give "
                                  "values nearer to the one wanted (`op --all` lists them)");
  OperatingPoint op = finished_point(model, p, t, zs[distance[0].second]);
  for (const auto& [node, value] : hints)
    if (model.graph().node_index(node) >= 0) op.chosen_by.push_back(node);
  op.warnings.push_back("the circuit has " + count + " (" + who + "); the one nearest to the .ic/.nodeset "
                        "values of " + join_names(op.chosen_by) + " is taken (`op --all` lists them)");
  return op;
}


// The operating point of a large circuit without transistors on the sparse system (issue 12):
// the DC equations A x + B z = -e, w = C x + D z + f as a mixed LCP whose modes are sparse
// linear systems (sparse_active_set.h), each solved exactly, as polish does for the dense path.
// False (the dense path decides) when the LCS is small or dense, or A or a mode's system is
// singular: then states may be undetermined, and least_energy chooses them.
bool sparse_operating_point(const CircuitModel& model, double t, OperatingPoint& op) {
  const SparseLcs* s = model.sparse_lcs().get();
  if (s == nullptr || model.has_history()) return false;  // lines: their DC waves are unknowns too
  const Eigen::VectorXd u = model.input_values(t);
  SparseActiveSetLcp lcp(s->A, s->B, s->C, s->D);
  Eigen::VectorXd w;
  return lcp.solve(-(s->E * u), s->F * u, op.x, op.z, w);
}
}  // namespace

OperatingPoint solve_operating_point(const CircuitModel& model, double t) {
  if (!model.has_transfer_pairs()) {
    OperatingPoint op;
    if (sparse_operating_point(model, t, op) || descriptor_operating_point(model, t, op)) {
      finish(model, op);
      return op;
    }
  }
  StaticProblem p = static_problem(model, t);
  const int m = static_cast<int>(p.M.rows());
  std::vector<std::string> notes;
  const PMatrixReport report = model.has_transfer_pairs() ? p_matrix_report(p.M, 0) : PMatrixReport{};
  std::optional<Eigen::VectorXd> only_solution;  // the enumeration's one solution, when it found one
  if (model.has_transfer_pairs() && !report.symmetric_psd && report.verdict != PMatrixReport::Verdict::P) {
    if (m <= kMaxCheckedPairs) {
      const std::vector<Eigen::VectorXd> zs =
          exact_solutions(model, t, p, distinct_in_w(p.M, p.q, enumerate_lcp_solutions(p.M, p.q)));
      if (zs.size() > 1) return choose_among(model, p, t, zs);
      if (zs.size() == 1) only_solution = zs.front();
    } else {
      notes.push_back("the static problem of this transistor circuit is not checked for several "
                      "operating points (" + std::to_string(m) + " pairs, more than " +
                      std::to_string(kMaxCheckedPairs) + "): `op` reports the one Lemke's method finds");
    }
  }
  LcpSolution sol = solve_lemke(p.M, p.q);
  // Where the DC equations needed the regularisation (a singular A), M is as ill-conditioned as
  // repair_numerical_failure says, and Lemke's path on it can end on a ray as well as on a basis
  // that misses the residual: measured on the TTL adder (adder_bip.cir) with its junctions
  // refitted, a ray after 300 pivots where Lemke with other covering vectors (rows scaled by
  // factors in [1, 2)) reached complementary bases within 2e-7 of a solution. Both are repaired
  // alike; a ray that survives the repair is reported as before.
  const bool rounding_ray = sol.status == LcpStatus::RayTermination && !p.undetermined.empty();
  if (sol.status == LcpStatus::NumericalFailure || rounding_ray) {
    OperatingPoint op = point_from(p, sol.z);
    if (repair_numerical_failure(model, t, op)) {
      op.pivots = sol.pivots;
      op.warnings = notes;
      finish(model, op);
      return op;
    }
  }
  if (sol.status != LcpStatus::Solved) {
    // At a ray termination the pairs growing along the ray are the ones no current through them
    // can satisfy: the elements the sources drive against (a current source into a reverse
    // junction, 5.4.7).
    std::vector<std::string> names;
    for (int i : sol.ray) {
      const std::string& name = model.netlist().elements.at(model.pairs()[i].element).name;
      if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
    }
    throw NumericalFailure(t, std::string("the operating point has no solution (Lemke: ") +
                                  lcp_status_name(sol.status) + ")" +
                                  (names.empty() ? "" : "; the sources drive current against " + join_names(names)));
  }
  OperatingPoint op = point_from(p, sol.z);
  op.pivots = sol.pivots;
  op.warnings = notes;
  if (!polish(model, t, op) && only_solution) {
    // Lemke's conducting set on the regularised problem can carry currents only the
    // regularisation lets flow (the leak across each capacitor closes DC paths the circuit does
    // not have): polish then finds no exact point with it. The enumeration's one exact solution
    // is the circuit's. Emitter followers into a lossy line open at its far end (the driver of
    // ltra4_1_line.sp): 0.43 mA into the line at DC, its two ports' currents unequal, before.
    OperatingPoint exact = point_from(p, *only_solution);
    if (polish(model, t, exact)) {
      exact.pivots = sol.pivots;
      exact.warnings = notes;
      op = exact;
    }
  }
  finish(model, op);
  return op;
}

std::map<std::string, double> node_hints(const Netlist& netlist) {
  std::map<std::string, double> hints;
  for (const NodeIc& h : netlist.node_sets) hints[h.node] = h.value;
  for (const NodeIc& h : netlist.node_ics) hints[h.node] = h.value;
  return hints;
}

double hint_distance(const CircuitModel& model, const std::map<std::string, double>& hints,
                     const Eigen::VectorXd& x, const Eigen::VectorXd& z, double t) {
  double d = 0;
  for (const auto& [node, value] : hints) {
    const int index = model.graph().node_index(node);
    if (index < 0) continue;
    const double v = model.evaluate_dc(model.node_voltage(index), x, z, t);
    d += (v - value) * (v - value);
  }
  return d;
}

Eigen::MatrixXd static_lcp_matrix(const CircuitModel& model, double t) { return static_problem(model, t).M; }

std::string undetermined_state_warning(const std::vector<std::string>& labels) {
  std::string list;
  for (const std::string& l : labels) list += (list.empty() ? "" : ", ") + l;
  return "the operating point does not determine " + list +
         " (a loop of inductors, or capacitors with no DC path): they start at the values of "
         "least stored energy (set IC= with UIC, or .ic, to choose them)";
}

std::vector<OperatingPoint> enumerate_operating_points(const CircuitModel& model, double t) {
  StaticProblem p = static_problem(model, t);
  std::vector<OperatingPoint> out;
  // The solutions `op` counts: distinct, and exact where the DC problem needed regularising.
  for (const Eigen::VectorXd& z : exact_solutions(model, t, p, distinct_in_w(p.M, p.q, enumerate_lcp_solutions(p.M, p.q)))) {
    out.push_back(point_from(p, z));
    polish(model, t, out.back());
    finish(model, out.back());
  }
  return out;
}

}  // namespace lcs
