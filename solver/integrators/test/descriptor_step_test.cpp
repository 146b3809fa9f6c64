// Circuits whose eliminated LCS is dense but whose circuit is sparse (a Cockcroft–Walton
// multiplier, a random tree of capacitors bridged by diodes) step on the descriptor form
// (solver/model/sparse_descriptor.h): every state of every step as the dense LCP's to rounding,
// each step's answer a solution of the dense LCS's step (its θ-method equation and its
// complementarity), and the path visibly taken.
#include <algorithm>
#include <cmath>
#include <random>
#include <string>

#include <set>

#include <gtest/gtest.h>

#include "netlist/netlist.h"
#include "solver/integrators/theta_method.h"
#include "solver/integrators/transient.h"
#include "solver/model/circuit_model.h"
#include "solver/model/operating_point.h"
#include "solver/model/sparse_descriptor.h"

namespace lcs {
namespace {

// `bench --scale cw`'s multiplier (cli/scale_family.cpp): N stages, 2N diodes, 100 V 50 Hz from
// rest, over `periods` source periods at 200 steps a period.
std::string multiplier(int n, int periods) {
  std::string s = "multiplier\nV1 in 0 SIN(0 100 50)\n";
  for (int k = 1; k <= n; ++k) {
    const std::string a_prev = k == 1 ? "in" : "a" + std::to_string(k - 1);
    const std::string b_prev = k == 1 ? "0" : "b" + std::to_string(k - 1);
    const std::string a = "a" + std::to_string(k), b = "b" + std::to_string(k);
    s += "C" + std::to_string(2 * k - 1) + " " + a_prev + " " + a + " 10u\n";
    s += "D" + std::to_string(2 * k - 1) + " " + b_prev + " " + a + " dcw\n";
    s += "D" + std::to_string(2 * k) + " " + a + " " + b + " dcw\n";
    s += "C" + std::to_string(2 * k) + " " + b_prev + " " + b + " 10u\n";
  }
  s += "RL b" + std::to_string(n) + " 0 1g\n.model dcw D(VON=0.7 RON=1)\n";
  s += ".tran 100u " + std::to_string(periods * 20) + "m UIC\n.end\n";
  return s;
}

// A random tree of capacitors hung from the source node (every diode loop runs down its paths:
// a dense LCS), diodes of random law between random nodes and to ground or a second source,
// resistors to ground, and some diodes behind an inductor with its own resistance.
std::string capacitor_tree(unsigned seed, int nodes) {
  std::mt19937 rng(seed);
  auto pick = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
  auto node = [](int k) { return "n" + std::to_string(k); };
  // One pick per statement: the order in which a compiler evaluates the operands of `+` is
  // unspecified: gcc and clang built different trees from the same seed. These picks are in gcc's
  // order (right to left), the trees the bounds below were measured on.
  const int pulse = pick(1, 5);
  const int frequency = pick(1, 5);
  const int amplitude = pick(5, 20);
  std::string s = "capacitor tree\nV1 n1 0 SIN(0 " + std::to_string(amplitude) + " " + std::to_string(frequency) +
                  "k)\nV2 ref 0 PULSE(0 " + std::to_string(pulse) + " 0.2m 10u 10u 0.3m 1m)\n";
  int diodes = 0, inductors = 0;
  for (int k = 2; k <= nodes; ++k) {
    const std::string id = std::to_string(k);
    const int nanofarads = pick(1, 100);
    const int from = pick(std::max(1, k - 4), k - 1);
    s += "C" + id + " " + node(from) + " " + node(k) + " " + std::to_string(nanofarads) + "n\n";
    if (pick(0, 3) == 0) s += "R" + id + " " + node(k) + " 0 " + std::to_string(pick(100, 5000)) + "\n";
    for (int d = pick(1, 2); d > 0; --d) {
      const int other = pick(0, 4) == 0 ? -1 : pick(0, nodes);
      std::string a = node(k), b = other < 0 ? std::string("ref") : other == 0 ? std::string("0") : node(other);
      if (b == a) continue;
      if (pick(0, 1)) std::swap(a, b);
      const std::string did = std::to_string(++diodes);
      if (pick(0, 9) == 0) {  // behind an inductor (with its own resistance)
        const std::string mid = "m" + did;
        s += "L" + std::to_string(++inductors) + " " + a + " " + mid + " " + std::to_string(pick(1, 100)) + "u\n";
        s += "RL" + did + " " + mid + " " + mid + "x 10\n";
        a = mid + "x";
      }
      s += "D" + did + " " + a + " " + b + " d" + std::to_string(pick(0, 2)) + "\n";
    }
  }
  s += ".model d0 D(VON=0.7 RON=0.5)\n.model d1 D(VON=0.3 RON=2)\n.model d2 D(VON=0 RON=0.1)\n";
  s += ".tran 5u 1m UIC\n.end\n";
  return s;
}

CircuitModel build(const std::string& text, bool defer_elimination = true) {
  const Netlist netlist = parse_netlist_string(text, "generated.cir");
  ModelOptions mo;
  mo.t1 = netlist.tran->tstop;
  mo.defer_elimination = defer_elimination;
  return CircuitModel::build(netlist, mo);
}

// Steps the descriptor path and the dense path side by side from rest, and checks at every step:
// the states of the two agree; the descriptor's (x+, z+) satisfies the dense LCS's θ-method
// equation and the complementarity of w+ = C x+ + D z+ + F u+. Returns the number of steps whose
// active pairs changed (so that a case that never switches proves nothing and says so).
struct Agreement {
  double state = 0;          // max |x_descriptor - x_dense| / max |x|
  double step_equation = 0;  // max residual of the θ-equation / max |x|
  double complementarity = 0;  // max |min(z, w)| over the sizes that meet in w
  long mode_changes = 0;
  std::set<int> switched;    // the pairs that changed mode at least once
  StepperStats stats;
};

Agreement step_both(const CircuitModel& model, double theta, double h, int steps) {
  const Lcs& s = model.lcs();
  // Either path at any size; every step the θ-method's (the step equation below is its own).
  ThetaMethod descriptor(model, theta, true, 0, false), dense(model, theta, false, kDescriptorPairs, false);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(s.states()), z = Eigen::VectorXd::Zero(s.pairs());
  descriptor.Start(0.0, h, x, z);
  Eigen::VectorXd xd = x, zd = z;
  Agreement a;
  double size = 1e-300;
  for (int k = 0; k < steps; ++k) {
    const double t = k * h;
    const Eigen::VectorXd x0 = x, z0 = z;
    descriptor.Step(t, h, x, z);
    dense.Step(t, h, xd, zd);
    size = std::max(size, x.cwiseAbs().maxCoeff());
    a.state = std::max(a.state, (x - xd).cwiseAbs().maxCoeff());
    const Eigen::VectorXd u0 = model.input_values(t), u1 = model.input_values(t + h);
    const Eigen::VectorXd rate0 = s.A * x0 + s.B * z0 + s.E * u0, rate1 = s.A * x + s.B * z + s.E * u1;
    a.step_equation = std::max(a.step_equation, (x - x0 - h * theta * rate1 - h * (1 - theta) * rate0).cwiseAbs().maxCoeff());
    const Eigen::VectorXd w = s.C * x + s.D * z + s.F * u1;
    const double w_size = (s.C.cwiseAbs() * x.cwiseAbs() + s.D.cwiseAbs() * z.cwiseAbs() + s.F.cwiseAbs() * u1.cwiseAbs()).maxCoeff();
    // A pair changes mode when its current crosses 1e-9 of the largest (a z at rounding level
    // is not a conducting diode: KLU and SparseLU leave different ones at degenerate steps).
    const double z_floor = 1e-9 * std::max({z.cwiseAbs().maxCoeff(), z0.cwiseAbs().maxCoeff(), 1e-300});
    for (int i = 0; i < s.pairs(); ++i) {
      EXPECT_GE(z(i), 0.0);
      a.complementarity = std::max(a.complementarity, std::abs(std::min(z(i), w(i))) / std::max(w_size, 1e-300));
      if ((z(i) > z_floor) != (z0(i) > z_floor)) {
        ++a.mode_changes;
        a.switched.insert(i);
      }
    }
  }
  a.state /= size;
  a.step_equation /= size;
  a.stats = descriptor.stats();
  EXPECT_EQ(dense.stats().descriptor_unknowns, 0);  // the dense option keeps the dense LCP
  EXPECT_EQ(dense.stats().sparse.solves, 0);
  return a;
}

// Multipliers of 25, 50 and 100 stages (50-200 diodes) over two periods at 100 us, implicit
// Euler and the trapezoidal rule. The dense path's LCP carries the elimination's conditioning
// (entries from RON = 1 to sums down a chain of capacitors): the two agree to 1e-9 of the largest
// state (measured 1.6e-13 to 2.0e-11). Each descriptor step solves the dense LCS's step to
// rounding: its θ-equation residual (measured <= 3.6e-14) and complementarity (<= 3.5e-16).
TEST(DescriptorStep, MultipliersStepAsTheDenseLcpToRounding) {
  struct Case { int stages; double theta; };
  for (const Case c : {Case{25, 1.0}, Case{50, 1.0}, Case{100, 1.0}, Case{25, 0.5}, Case{50, 0.5}}) {
    const CircuitModel model = build(multiplier(c.stages, 2));
    ASSERT_NE(model.sparse_descriptor(), nullptr) << c.stages;
    EXPECT_EQ(model.sparse_lcs(), nullptr) << c.stages;  // the LCS is dense: the old sparse path declined
    const Agreement a = step_both(model, c.theta, 1e-4, 400);
    SCOPED_TRACE(std::to_string(c.stages) + " stages, theta " + std::to_string(c.theta));
    // The diodes switched, so the search was exercised. Two periods carry the charge through
    // the first 11 stages whatever the length: measured 93 changes of 22 pairs (θ = 1) and 121
    // of 26 (θ = 0.5) at every length. Counted at z = 0 exactly, rounding-level currents at
    // degenerate steps added hundreds more, which differ between sparse LUs.
    EXPECT_GE(a.mode_changes, 90);
    EXPECT_GE(a.switched.size(), 22u);
    EXPECT_EQ(a.stats.sparse_fallbacks, 0);
    EXPECT_EQ(a.stats.sparse.solves, 401);  // the start (descriptor_start.h) and 400 steps
    EXPECT_EQ(a.stats.descriptor_unknowns, model.sparse_descriptor()->unknowns());
    EXPECT_LT(a.state, 1e-9);
    EXPECT_LT(a.step_equation, 1e-12);
    EXPECT_LT(a.complementarity, 1e-13);
  }
}

// A run on the descriptor form never forms the dense A, B, C, D (issue 12: formation deferred
// them; at 2000 diodes they were 128 MB) and writes the dense path's waveforms: every default
// probe (node voltages, source and diode currents) of a 100-stage multiplier (200 diodes) over one
// period, implicit Euler and the trapezoidal rule, within 1e-9 of the largest probe's range
// (200 V; measured 1.3e-11 for Euler, 5.1e-13 for the trapezoidal rule).
TEST(DescriptorStep, ARunOnItNeverFormsTheDenseLcsAndWritesTheDensePathsWaveforms) {
  const int stages = 100;
  for (const std::string method : {"euler", "theta"}) {  // theta: 0.5 by default
    SCOPED_TRACE(method);
    const CircuitModel model = build(multiplier(stages, 1)), dense_model = build(multiplier(stages, 1));
    ASSERT_NE(model.sparse_descriptor(), nullptr);
    EXPECT_TRUE(model.dense_deferred());
    EXPECT_FALSE(model.dense_formed_from_sparse());
    auto run = [&](const CircuitModel& m, bool sparse, TransientSummary& summary) {
      TransientOptions o;
      o.method = method;
      o.method_options.sparse = sparse;
      o.step = m.netlist().tran->tstep;
      o.tstop = m.netlist().tran->tstop;
      o.uic = true;
      MemorySink sink;
      summary = run_transient(m, m.output_map(m.default_probes()), o, sink);
      return sink;
    };
    TransientSummary on_descriptor, on_dense;
    const MemorySink rows = run(model, true, on_descriptor), dense_rows = run(dense_model, false, on_dense);
    EXPECT_EQ(on_descriptor.stepper.descriptor_unknowns, model.sparse_descriptor()->unknowns());
    EXPECT_EQ(on_descriptor.stepper.sparse_fallbacks, 0);
    EXPECT_FALSE(model.dense_formed_from_sparse());
    EXPECT_TRUE(dense_model.dense_formed_from_sparse());  // the dense path formed them on first use
    EXPECT_GT(on_dense.stepper.lcp.lemke_calls, 0);       // and stepped on them, switching
    ASSERT_EQ(rows.rows.size(), 201u);
    ASSERT_EQ(dense_rows.rows.size(), rows.rows.size());
    const Eigen::Index probes = rows.rows[0].size();
    Eigen::VectorXd lo = rows.rows[0], hi = rows.rows[0];
    double diff = 0;
    for (size_t r = 0; r < rows.rows.size(); ++r) {
      lo = lo.cwiseMin(dense_rows.rows[r]);
      hi = hi.cwiseMax(dense_rows.rows[r]);
      diff = std::max(diff, (rows.rows[r] - dense_rows.rows[r]).cwiseAbs().maxCoeff());
    }
    EXPECT_EQ(probes, (1 + 2 * stages) + 1 + 2 * stages);  // nodes, V1, the diodes
    const double range = (hi - lo).maxCoeff();
    EXPECT_GT(range, 100.0);  // the multiplier charged
    EXPECT_LT(diff, 1e-9 * range);
  }
}

// A circuit that will step on its descriptor form is not eliminated to its LCS at formation
// (a multiplier's holds O(n^2) entries: two thirds of a 1000-diode run's CPU); its output rows
// are made from its loops and cutsets, and its LCS when something asks for it. Both are the ones
// formation makes at once, to the last bit: every default probe's row and A, B, C, D, E, F, on
// a multiplier and on capacitor trees with resistors and inductors (230 and 290 pairs).
TEST(DeferredElimination, GivesTheOutputRowsAndTheLcsOfTheImmediateOne) {
  for (const std::string& text : {multiplier(100, 1), capacitor_tree(2, 120), capacitor_tree(3, 150)}) {
    const CircuitModel deferred = build(text), immediate = build(text, false);
    SCOPED_TRACE(text.substr(0, text.find('\n')) + ", " + std::to_string(immediate.pair_count()) + " pairs");
    ASSERT_NE(deferred.sparse_descriptor(), nullptr);
    ASSERT_NE(immediate.sparse_descriptor(), nullptr);
    EXPECT_GE(immediate.pair_count(), kDescriptorPairs);
    EXPECT_FALSE(deferred.eliminated());
    EXPECT_TRUE(immediate.eliminated());
    EXPECT_EQ(deferred.state_count(), immediate.state_count());
    EXPECT_EQ(deferred.pair_count(), immediate.pair_count());
    EXPECT_EQ(deferred.input_count(), immediate.input_count());
    EXPECT_EQ(deferred.sparse_descriptor()->nonzeros(), immediate.sparse_descriptor()->nonzeros());
    const OutputMap rows = deferred.output_map(deferred.default_probes());
    const OutputMap immediate_rows = immediate.output_map(immediate.default_probes());
    EXPECT_FALSE(deferred.eliminated());  // the rows did not need the LCS
    EXPECT_TRUE(Eigen::MatrixXd(rows.G) == Eigen::MatrixXd(immediate_rows.G));
    EXPECT_TRUE(Eigen::MatrixXd(rows.H) == Eigen::MatrixXd(immediate_rows.H));
    EXPECT_TRUE(rows.J == immediate_rows.J);
    EXPECT_TRUE(rows.K == immediate_rows.K);
    EXPECT_GT(rows.G.nonZeros(), 0);
    const Lcs& a = deferred.lcs();
    const Lcs& b = immediate.lcs();
    EXPECT_TRUE(deferred.eliminated());
    EXPECT_TRUE(a.A == b.A);
    EXPECT_TRUE(a.B == b.B);
    EXPECT_TRUE(a.C == b.C);
    EXPECT_TRUE(a.D == b.D);
    EXPECT_TRUE(a.E == b.E);
    EXPECT_TRUE(a.F == b.F);
    EXPECT_TRUE(a.Gamma == b.Gamma);
    EXPECT_GT(a.B.cwiseAbs().sum(), 0);
    EXPECT_TRUE(Eigen::MatrixXd(deferred.energy_xx()) == Eigen::MatrixXd(immediate.energy_xx()));
  }
}

// Random capacitor trees of 90-150 nodes (one or two diodes a node, some behind inductors: about
// 130-230 pairs): irregular modes that change in many places at once (measured: 390-2180 pair
// changes in 100-200 steps, warm hits 0-50 %). Measured: states 1.1e-13 to 1.1e-12 apart,
// θ-equation residuals <= 2.2e-12, complementarity <= 3.1e-16.
TEST(DescriptorStep, RandomCapacitorTreesStepAsTheDenseLcp) {
  for (unsigned seed = 1; seed <= 3; ++seed) {
    const CircuitModel model = build(capacitor_tree(seed, 60 + 30 * static_cast<int>(seed)));
    ASSERT_NE(model.sparse_descriptor(), nullptr) << seed;
    for (double theta : {1.0, 0.5}) {
      const Agreement a = step_both(model, theta, 5e-6, 120);
      SCOPED_TRACE("seed " + std::to_string(seed) + ", theta " + std::to_string(theta));
      EXPECT_GT(a.mode_changes, 100);
      EXPECT_EQ(a.stats.sparse_fallbacks, 0);
      EXPECT_LT(a.state, 1e-9);
      EXPECT_LT(a.step_equation, 1e-10);
      EXPECT_LT(a.complementarity, 1e-13);
    }
  }
}

// `--stats` names the path on a multiplier above kDescriptorPairs; below it the θ-method keeps
// the dense LCP, and a multiplier with fewer pairs than kSparsePairs has no descriptor.
TEST(DescriptorStep, StatsReportThePath) {
  const int stages = 75;
  const Netlist netlist = parse_netlist_string(multiplier(stages, 1), "cw.cir");
  ModelOptions mo;
  mo.t1 = netlist.tran->tstop;
  const CircuitModel model = CircuitModel::build(netlist, mo);
  ASSERT_NE(model.sparse_descriptor(), nullptr);
  TransientOptions o;
  o.method = "euler";
  o.step = netlist.tran->tstep;
  o.tstop = netlist.tran->tstop;
  MemorySink sink;
  const TransientSummary summary = run_transient(model, model.output_map(model.default_probes()), o, sink);
  // nodes but ground (in, a_k, b_k), branches (V1, C and D of every stage, RL)
  const int unknowns = model.sparse_descriptor()->unknowns();
  EXPECT_EQ(unknowns, (1 + 2 * stages) + (2 + 4 * stages));
  EXPECT_NE(summary.BriefReport().find("step path: descriptor (node) form, " + std::to_string(unknowns) + " unknowns"),
            std::string::npos) << summary.BriefReport();
  EXPECT_EQ(summary.stepper.sparse.solves, 201);  // the start (descriptor_start.h) and 200 steps
  EXPECT_EQ(summary.stepper.sparse_fallbacks, 0);

  const CircuitModel below = build(multiplier(kDescriptorPairs / 2 - 1, 1));
  ASSERT_NE(below.sparse_descriptor(), nullptr);
  EXPECT_EQ(ThetaMethod(below, 1.0).stats().descriptor_unknowns, 0);
  EXPECT_EQ(build(multiplier(20, 1)).sparse_descriptor(), nullptr);  // 40 pairs: dense
}

// The operating point of a circuit that steps on its descriptor form is solved on it where every
// pair is off (descriptor_operating_point.h), never forming the dense LCS; elsewhere the dense
// path decides. The dense path's answer is the reference: the same circuit with a capacitor across
// its source (a dependent capacitor: no descriptor form, and no change at DC). States DC leaves
// free (a multiplier's capacitors have no DC path) take the values of least stored energy on
// both. Checked: every physical state and pair current, the list of free states, and the path.
void expect_operating_points_agree(const std::string& text, const std::string& source_node, double t,
                                   bool on_descriptor) {
  const CircuitModel model = build(text);
  ASSERT_NE(model.sparse_descriptor(), nullptr);
  const size_t cut = text.find('\n', text.find("\nV1 ") + 1);
  const CircuitModel reference = build(text.substr(0, cut + 1) + "CX " + source_node + " 0 1n\n" + text.substr(cut + 1));
  ASSERT_EQ(reference.sparse_descriptor(), nullptr);
  ASSERT_EQ(reference.state_count(), model.state_count());
  const OperatingPoint op = solve_operating_point(model, t), ref = solve_operating_point(reference, t);
  EXPECT_EQ(model.dense_formed_from_sparse(), !on_descriptor);
  const Eigen::VectorXd x = model.physical_state(op.x, t), x_ref = reference.physical_state(ref.x, t);
  const double x_scale = std::max(1.0, x_ref.cwiseAbs().maxCoeff());
  const double z_scale = std::max(1e-6, ref.z.cwiseAbs().maxCoeff());
  EXPECT_LT((x - x_ref).cwiseAbs().maxCoeff(), 1e-6 * x_scale);
  EXPECT_LT((op.z - ref.z).cwiseAbs().maxCoeff(), 1e-6 * z_scale);
  EXPECT_EQ(op.undetermined, ref.undetermined);
}

TEST(DescriptorOperatingPoint, AMultiplierAtRestIsSolvedOnItsDescriptor) {
  const std::string at_rest = multiplier(30, 1);  // 60 pairs, every capacitor free
  expect_operating_points_agree(at_rest, "in", 0.0, true);
  // With the source at 30 V or -70 V the first diode conducts (its capacitor at least energy
  // would put a1 at the source's potential): the dense path decides.
  std::string offset = at_rest;
  offset.replace(offset.find("SIN(0 100 50)"), 13, "SIN(30 100 50)");
  expect_operating_points_agree(offset, "in", 0.0, false);
  expect_operating_points_agree(offset, "in", 15e-3, false);
}

// DC sources and every diode reverse-biased, so the answer is not zero: a chain of capacitors
// hung from a 5 V source, a 1 Mohm resistor to ground at every third node (those nodes and the
// capacitors into them are fixed; the others float: least energy), and at every node a clamp
// diode (RON 1 ohm, so the largest conductance is 1e6 times the resistors') to a 10 V rail it
// never reaches. A leak sized against the largest conductance alone (1e-9 S) moved the resistor
// nodes by 1e-3 of their value; the answer must not depend on the leak.
std::string reverse_biased_chain(int nodes) {
  std::string s = "reverse-biased clamps on a capacitor chain\nV1 in 0 DC 5\nV2 rail 0 DC 10\n";
  for (int k = 1; k <= nodes; ++k) {
    const std::string prev = k == 1 ? "in" : "n" + std::to_string(k - 1), node = "n" + std::to_string(k);
    s += "C" + std::to_string(k) + " " + prev + " " + node + " " + std::to_string(10 + k % 7) + "n\n";
    if (k % 3 == 0) s += "R" + std::to_string(k) + " " + node + " 0 1meg\n";
    s += "D" + std::to_string(k) + " " + node + " rail dclamp\n";
  }
  s += ".model dclamp D(VON=0.7 RON=1)\n.tran 1u 1m\n.end\n";
  return s;
}

TEST(DescriptorOperatingPoint, ReverseBiasedClampsOnACapacitorChainAgreeWithTheDensePath) {
  expect_operating_points_agree(reverse_biased_chain(70), "in", 0.0, true);
}

// The trees' third diode model has VON = 0: at rest those diodes sit on their threshold (not
// strictly off), and the dense path decides; with VON = 0.1 every pair is strictly off.
TEST(DescriptorOperatingPoint, RandomCapacitorTreesAtRestAgreeWithTheDensePath) {
  for (unsigned seed : {3u, 11u, 29u}) {
    SCOPED_TRACE(seed);
    std::string tree = capacitor_tree(seed, 60);
    expect_operating_points_agree(tree, "n1", 0.0, false);
    tree.replace(tree.find("d2 D(VON=0 "), 11, "d2 D(VON=0.1 ");
    expect_operating_points_agree(tree, "n1", 0.0, true);
  }
}

}  // namespace
}  // namespace lcs
