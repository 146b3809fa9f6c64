#include "solver/model/circuit_model.h"

#include <gtest/gtest.h>

#include "solver/model/lcs_index.h"
#include "solver/model/operating_point.h"
#include "tests/support/netlist_builder.h"

namespace lcs {
namespace {

using testing::NetlistBuilder;

CircuitModel build(const NetlistBuilder& b, double t1 = 0.0) {
  ModelOptions o;
  o.t1 = t1;
  return CircuitModel::build(b.build(), o);
}

// Figure 1.6: V -> D -> L -> (C || R). The diode is the only way to reach the inductor's node,
// so it enters the tree and becomes voltage-type (an "L diode", 5.4.4). With z = VON + RON i - v:
//   dv/dt = (i - v/R)/C,  L di/dt = u - VON - RON i + z - v,  w = i.
TEST(CircuitModel, HalfWaveRectifierMatchesTheBooksEquations) {
  const double R = 100, L = 10e-3, C = 100e-6, VON = 0.7, RON = 0.05;
  NetlistBuilder b;
  b.v("v1", "in", "0", NetlistBuilder::sin(0, 10, 50)).d("d1", "in", "n1", VON, RON);
  b.l("l1", "n1", "out", L).c("c1", "out", "0", C).r("r1", "out", "0", R);
  CircuitModel m = build(b);
  const Lcs& s = m.lcs();
  ASSERT_EQ(s.states(), 2);
  EXPECT_EQ(m.states()[0].label, "v(c1)");
  EXPECT_EQ(m.states()[1].label, "i(l1)");
  ASSERT_EQ(s.pairs(), 1);
  EXPECT_TRUE(m.pairs()[0].voltage_type);
  Eigen::MatrixXd A(2, 2), B(2, 1), Cm(1, 2), E(2, 2);
  A << -1 / (R * C), 1 / C, -1 / L, -RON / L;
  B << 0, 1 / L;
  Cm << 0, 1;
  E << 0, 0, -VON / L, 1 / L;
  EXPECT_LT((s.A - A).norm(), 1e-9 * A.norm());
  EXPECT_LT((s.B - B).norm(), 1e-9 * B.norm());
  EXPECT_LT((s.C - Cm).norm(), 1e-12);
  EXPECT_LT(s.D.norm(), 1e-12);
  EXPECT_LT((s.E - E).norm(), 1e-9 * E.norm());
  EXPECT_LT(s.F.norm(), 1e-12);
  EXPECT_EQ(lcs_index(s).index, 1);
}

// Figure 5.6: H has two components (source; load), so exactly one diode enters the tree (a
// spanning tree of the quotient G/H, 5.4.6) and the other three are current-type links.
TEST(CircuitModel, BridgeRectifierHasOneTreeDiode) {
  NetlistBuilder b;
  b.v("v1", "a", "0", NetlistBuilder::sin(0, 10, 50));
  b.d("d1", "a", "p").d("d2", "n", "a").d("d3", "0", "p").d("d4", "n", "0");
  b.r("rl", "p", "n", 100).c("cl", "p", "n", 100e-6);
  CircuitModel m = build(b);
  int voltage_type = 0;
  for (const PairInfo& p : m.pairs()) voltage_type += p.voltage_type;
  EXPECT_EQ(m.lcs().pairs(), 4);
  EXPECT_EQ(voltage_type, 1);
  EXPECT_EQ(m.lcs().states(), 1);
}

// A capacitor across a voltage source is forced into the links: no state, and its current is
// C du/dt through the output map's derivative term.
TEST(CircuitModel, CapacitorAcrossSourceIsDependent) {
  NetlistBuilder b;
  b.v("v1", "a", "0", NetlistBuilder::sin(0, 2, 1000)).c("c1", "a", "0", 1e-6).r("r1", "a", "0", 1e3);
  CircuitModel m = build(b);
  EXPECT_EQ(m.lcs().states(), 0);
  OutputMap out = m.output_map({{Probe::Kind::ElementCurrent, "c1", "", {}}});
  const double t = 1.3e-4;
  Eigen::VectorXd x(0), z(0);
  const double expected = 1e-6 * 2 * 2 * M_PI * 1000 * std::cos(2 * M_PI * 1000 * t);
  EXPECT_NEAR(m.evaluate(m.branch_current(m.graph().branch_of_element(1)), x, z, t), expected, 1e-12);
}

// Two capacitors in series across a source with a resistor from their middle node m: c1 (card
// order) is the tree capacitor, c2 is forced into a link (loop v1-c1-c2). With v(m) = u - v(c1),
//   (C1 + C2) dv(m)/dt = C1 du/dt - v(m)/R   =>   dv(c1)/dt = (u - v(c1))/tau + C2/(C1+C2) du/dt
// so A = -1/tau and the state shift Gamma = C2/(C1 + C2): a step of u is shared instantly.
TEST(CircuitModel, CapacitorLoopFoldsIntoEffectiveCapacitance) {
  NetlistBuilder b;
  b.v("v1", "a", "0", NetlistBuilder::dc(1)).c("c1", "a", "m", 1e-6).c("c2", "m", "0", 3e-6);
  b.r("r1", "m", "0", 1e3);
  CircuitModel m = build(b);
  ASSERT_EQ(m.lcs().states(), 1);
  EXPECT_EQ(m.states()[0].label, "v(c1)");
  const double tau = 1e3 * 4e-6;
  EXPECT_NEAR(m.lcs().A(0, 0), -1 / tau, 1e-9 / tau);
  EXPECT_NEAR(m.lcs().Gamma(0, 1), 0.75, 1e-12);
  // In LCS coordinates x = v(c1) - 0.75 u: dx/dt = A x + (1/tau + A 0.75) u.
  EXPECT_NEAR(m.lcs().E(0, 1), 0.25 / tau, 1e-9 / tau);
}

TEST(CircuitModel, MutualInductanceEntersTheInductanceMatrix) {
  // Two coupled inductors, each with its own resistor to ground, driven by a current source
  // through a resistor on the primary.
  const double L1 = 1e-3, L2 = 4e-3, k = 0.5;
  NetlistBuilder b;
  b.v("v1", "a", "0", NetlistBuilder::dc(1)).r("r1", "a", "p", 10).l("l1", "p", "0", L1);
  b.l("l2", "s", "0", L2).r("r2", "s", "0", 20).k("k1", "l1", "l2", k);
  CircuitModel m = build(b);
  ASSERT_EQ(m.lcs().states(), 2);
  const double M = k * std::sqrt(L1 * L2);
  Eigen::Matrix2d Lm;
  Lm << L1, M, M, L2;
  Eigen::Matrix2d Rm;  // L di/dt = -R i + [u; 0]
  Rm << 10, 0, 0, 20;
  Eigen::Matrix2d expected = -Lm.inverse() * Rm;
  EXPECT_LT((m.lcs().A - expected).norm(), 1e-9 * expected.norm());
}

TEST(Topology, VoltageSourceLoopNamesTheSources) {
  NetlistBuilder b;
  b.v("v1", "a", "0", NetlistBuilder::dc(1)).v("v2", "a", "0", NetlistBuilder::dc(2)).r("r1", "a", "0", 1);
  try {
    build(b);
    FAIL() << "expected a topology error";
  } catch (const TopologyError& e) {
    EXPECT_EQ(e.message(),
              "voltage sources form a loop: v2 and v1 (KVL cannot hold for arbitrary source values)");
    EXPECT_EQ(e.elements().size(), 2u);
  }
}

TEST(Topology, CurrentSourceCutsetNamesTheSources) {
  NetlistBuilder b;
  b.i("i1", "0", "a", NetlistBuilder::dc(1)).i("i2", "a", "b", NetlistBuilder::dc(1)).r("r1", "b", "0", 1);
  try {
    build(b);
    FAIL() << "expected a topology error";
  } catch (const TopologyError& e) {
    EXPECT_EQ(e.message(),
              "current sources form a cutset: i1 and i2 (KCL cannot hold for arbitrary source values)");
  }
}

TEST(Topology, FloatingNodesAreNamed) {
  NetlistBuilder b;
  b.v("v1", "a", "0", NetlistBuilder::dc(1)).r("r1", "a", "0", 1).r("r2", "x", "y", 1);
  try {
    build(b);
    FAIL() << "expected a topology error";
  } catch (const TopologyError& e) {
    EXPECT_EQ(e.message(), "nodes 'x' and 'y' have no path to ground (floating: r2)");
  }
}

TEST(Topology, AntiParallelIdealDiodesWithoutThresholdAreRejected) {
  NetlistBuilder b;
  b.v("v1", "a", "0", NetlistBuilder::dc(1)).r("r1", "a", "b", 1).d("d1", "b", "0").d("d2", "0", "b");
  try {
    build(b);
    FAIL() << "expected a topology error";
  } catch (const TopologyError& e) {
    EXPECT_NE(e.message().find("ideal diodes form a loop with no impedance that can conduct: d1 and d2"),
              std::string::npos)
        << e.message();
  }
}

// Issue 9, defect 4: before, event failed with "no consistent mode" and euler and radau5 picked
// a split silently. Every command builds the model, so every method refuses alike.
TEST(Topology, ParallelIdealDiodesWithTheSameThresholdAreRejected) {
  NetlistBuilder b;
  b.v("v1", "in", "0", NetlistBuilder::dc(5)).r("r1", "in", "a", 100);
  b.d("d1", "a", "out", 0.7).d("d2", "a", "out", 0.7).r("r2", "out", "0", 100);
  try {
    build(b);
    FAIL() << "expected a topology error";
  } catch (const TopologyError& e) {
    EXPECT_EQ(e.message(),
              "ideal diodes d1 and d2 are in parallel with the same VON and RON = 0: when they "
              "conduct, the current divides between them in no defined ratio (assumption 5.40); "
              "give them RON > 0, or use one diode");
    EXPECT_EQ(e.elements().size(), 2u);
  }
}

TEST(Topology, ParallelIdealDiodesWithDifferentThresholdsOrResistanceAreAccepted) {
  NetlistBuilder b;
  b.v("v1", "in", "0", NetlistBuilder::dc(5)).r("r1", "in", "a", 100);
  b.d("d1", "a", "out", 0.7).d("d2", "a", "out", 0.6).r("r2", "out", "0", 100);
  EXPECT_NO_THROW(build(b));
  NetlistBuilder c;
  c.v("v1", "in", "0", NetlistBuilder::dc(5)).r("r1", "in", "a", 100);
  c.d("d1", "a", "out", 0.7, 0.1).d("d2", "a", "out", 0.7, 0.1).r("r2", "out", "0", 100);
  EXPECT_NO_THROW(build(c));
}

TEST(Topology, AntiParallelDiodesWithThresholdsAreAccepted) {
  NetlistBuilder b;
  b.v("v1", "a", "0", NetlistBuilder::dc(1)).r("r1", "a", "b", 1);
  b.d("d1", "b", "0", 0.7).d("d2", "0", "b", 0.7);
  EXPECT_NO_THROW(build(b));
}

TEST(Topology, DiodeForwardBiasedBySourceHasNoSolution) {
  NetlistBuilder b;
  b.v("v1", "a", "0", NetlistBuilder::sin(0, 5, 50)).d("d1", "a", "0", 0.7).r("r1", "a", "0", 1);
  try {
    build(b, 0.02);
    FAIL() << "expected a topology error";
  } catch (const TopologyError& e) {
    EXPECT_EQ(e.message(),
              "diode d1 is forward-biased directly by voltage source v1 with no impedance in the "
              "loop (d1 and v1): an ideal diode has no solution there (Figure 5.5); give it RON > 0 "
              "or add a series resistance");
  }
}

TEST(Topology, DiodeKeptReverseBiasedBySourceIsAccepted) {
  NetlistBuilder b;
  b.v("v1", "0", "a", NetlistBuilder::dc(5)).d("d1", "a", "0").r("r1", "a", "0", 1);
  EXPECT_NO_THROW(build(b, 1.0));
}

TEST(OperatingPoint, ResistiveDividerWithDiode) {
  // 10 V -> 1k -> diode (VON 0.7, RON 10) -> 1k -> ground: i = 9.3 / 2010.
  NetlistBuilder b;
  b.v("v1", "a", "0", NetlistBuilder::dc(10)).r("r1", "a", "b", 1e3).d("d1", "b", "c", 0.7, 10);
  b.r("r2", "c", "0", 1e3);
  CircuitModel m = build(b);
  OperatingPoint op = solve_operating_point(m);
  const double i = 9.3 / 2010;
  EXPECT_NEAR(m.evaluate(m.branch_current(2), op.x, op.z, 0), i, 1e-14);
  EXPECT_NEAR(m.evaluate(m.node_voltage(m.graph().node_index("c")), op.x, op.z, 0), 1e3 * i, 1e-11);
  EXPECT_EQ(enumerate_operating_points(m).size(), 1u);
}

TEST(OperatingPoint, CapacitorsOpenInductorsShorted) {
  // V -> R1 -> node b; L from b to c; R2 from c to ground; C across c: DC current V/(R1+R2).
  NetlistBuilder b;
  b.v("v1", "a", "0", NetlistBuilder::dc(6)).r("r1", "a", "b", 1e3).l("l1", "b", "c", 1e-3);
  b.r("r2", "c", "0", 2e3).c("c1", "c", "0", 1e-6);
  CircuitModel m = build(b);
  OperatingPoint op = solve_operating_point(m);
  EXPECT_TRUE(op.undetermined.empty());
  Eigen::VectorXd phys = m.physical_state(op.x, 0);
  EXPECT_NEAR(phys(0), 4.0, 1e-12);    // v(c1)
  EXPECT_NEAR(phys(1), 2e-3, 1e-15);   // i(l1)
}

}  // namespace
}  // namespace lcs

namespace lcs {
namespace {

using testing::NetlistBuilder;

// A capacitor whose only DC path is a conducting diode: A is singular only because the diode
// current is the complementarity variable. The operating point is exact, whatever C is.
TEST(OperatingPoint, CapacitorHeldByAConductingDiodeIsExact) {
  for (double C : {1e-12, 1e-9, 1e-6}) {
    NetlistBuilder b;
    b.i("i1", "0", "a", NetlistBuilder::dc(1e-3)).c("c1", "a", "0", C).d("d1", "a", "0", 0.7);
    CircuitModel m = CircuitModel::build(b.build(), {});
    OperatingPoint op = solve_operating_point(m);
    EXPECT_NEAR(m.evaluate_dc(m.node_voltage(m.graph().node_index("a")), op.x, op.z, 0), 0.7, 1e-12) << C;
    EXPECT_TRUE(op.undetermined.empty()) << "the diode is the DC path";
  }
  NetlistBuilder b;  // through a resistor: 0.7 + 1k * 1m
  b.i("i1", "0", "a", NetlistBuilder::dc(1e-3)).c("c1", "a", "0", 1e-6).r("r1", "a", "b", 1e3);
  b.d("d1", "b", "0", 0.7);
  CircuitModel m = CircuitModel::build(b.build(), {});
  OperatingPoint op = solve_operating_point(m);
  EXPECT_NEAR(m.evaluate_dc(m.node_voltage(m.graph().node_index("a")), op.x, op.z, 0), 1.7, 1e-12);
}

TEST(OperatingPoint, NoDcPathIsReportedAndTakesTheLeastEnergySplit) {
  NetlistBuilder b;
  b.v("v1", "a", "0", NetlistBuilder::dc(5)).c("c1", "a", "m", 1e-6).c("c2", "m", "n", 3e-6);
  b.r("r1", "n", "0", 1e3);
  CircuitModel m = CircuitModel::build(b.build(), {});
  OperatingPoint op = solve_operating_point(m);
  // c1 and c2 in series (both tree capacitors: n is reached through c2 before r1) across v1,
  // r1 to ground carries no DC current: v(c1) + v(c2) = 5, but how it splits is not fixed at
  // DC, so both states lie in the undetermined direction. Least energy 1/2 (C1 v1^2 + C2 v2^2)
  // on v1 + v2 = 5 is the capacitive divider C1 v1 = C2 v2: 3.75 V / 1.25 V.
  EXPECT_EQ(op.undetermined, (std::vector<std::string>{"v(c1)", "v(c2)"}));
  Eigen::VectorXd x = m.physical_state(op.x, 0);
  EXPECT_NEAR(x(0), 3.75, 1e-12);
  EXPECT_NEAR(x(1), 1.25, 1e-12);
}

// Operating point with sources that are ramping at t = 0: capacitors open, so no C du/dt.
TEST(OperatingPoint, CapacitorsAreOpenEvenWhenSourcesRamp) {
  NetlistBuilder b;
  Waveform ramp;
  ramp.kind = Waveform::Kind::Pwl;
  ramp.params = {0, 0, 1e-3, 1};
  b.v("v1", "a", "0", ramp).c("c1", "a", "0", 1e-6).r("r1", "a", "0", 1e3);
  CircuitModel m = CircuitModel::build(b.build(), {});
  OperatingPoint op = solve_operating_point(m);
  EXPECT_EQ(m.evaluate_dc(m.branch_current(1), op.x, op.z, 0), 0.0);
  EXPECT_NEAR(m.evaluate(m.branch_current(1), op.x, op.z, 0), 1e-3, 1e-15);  // C du/dt in transient
}

// Circuits with no resistor, source or diode at all have no static equations (empty matrices).
TEST(CircuitModel, CircuitsWithoutStaticBranches) {
  NetlistBuilder b;
  b.c("c1", "a", "0", 1e-6, 1.0).c("c2", "a", "0", 2e-6);
  CircuitModel m = CircuitModel::build(b.build(), {});
  EXPECT_EQ(m.lcs().states(), 1);
  EXPECT_EQ(m.lcs().A(0, 0), 0.0);
  NetlistBuilder l;
  l.l("l1", "a", "b", 1e-3, 1e-3).l("l2", "b", "0", 1e-3);
  CircuitModel ml = CircuitModel::build(l.build(), {});
  EXPECT_EQ(ml.lcs().states(), 0);  // an open chain: both inductors forced, current 0
  NetlistBuilder e;
  EXPECT_NO_THROW(CircuitModel::build(e.build(), {}));
}

TEST(CircuitModel, BadlyScaledResistorsAreNotSingular) {
  NetlistBuilder b;
  b.v("v1", "a", "0", NetlistBuilder::dc(1)).r("r1", "a", "0", 1e16).r("r2", "a", "b", 1e-6);
  b.r("r3", "b", "0", 1e-6);
  CircuitModel m = CircuitModel::build(b.build(), {});
  OperatingPoint op = solve_operating_point(m);
  EXPECT_NEAR(m.evaluate_dc(m.node_voltage(m.graph().node_index("b")), op.x, op.z, 0), 0.5, 1e-12);
}

int branch_named(const CircuitModel& m, const std::string& name) {
  for (int b = 0; b < static_cast<int>(m.graph().branches.size()); ++b)
    if (m.graph().branches[b].name == name) return b;
  return -1;
}

// Perfect coupling (K ... 1): v1 across l1 (1 mH), l2 (4 mH) into rl. Lf = s s^T is singular and
// only the flux is a state, kept as the magnetising current referred to l1,
// imag(l1) = i(l1) + n i(l2), n = sqrt(L2/L1) = 2: L1 d imag/dt = u. The windings are algebraic:
// v(s) = n u, i(l2) = -n u / RL, i(l1) = imag - n i(l2) = imag + n^2 u / RL.
TEST(PerfectCoupling, OnlyTheMagnetisingCurrentIsAState) {
  const double L1 = 1e-3, L2 = 4e-3, RL = 50, n = 2;
  NetlistBuilder b;
  b.v("v1", "p", "0", NetlistBuilder::sin(0, 10, 1000)).l("l1", "p", "0", L1).l("l2", "s", "0", L2);
  b.k("k1", "l1", "l2", 1.0).r("rl", "s", "0", RL);
  CircuitModel m = build(b);
  ASSERT_EQ(m.lcs().states(), 1);
  const StateInfo& st = m.states()[0];
  EXPECT_EQ(st.label, "imag(l1)");
  EXPECT_FALSE(st.capacitor);
  ASSERT_EQ(st.windings.size(), 2u);
  EXPECT_EQ(st.windings[0].first, branch_named(m, "l1"));
  EXPECT_EQ(st.windings[0].second, 1.0);
  EXPECT_EQ(st.windings[1].first, branch_named(m, "l2"));
  EXPECT_NEAR(st.windings[1].second, n, 1e-12);
  const Lcs& s = m.lcs();
  EXPECT_NEAR(s.A(0, 0), 0, 1e-12 / L1);
  EXPECT_NEAR(s.E(0, 1), 1 / L1, 1e-9 / L1);
  EXPECT_NEAR(s.Gamma(0, 1), 0, 1e-15);
  const OutputRow i2 = m.branch_current(branch_named(m, "l2"));
  EXPECT_NEAR(i2.g(0), 0, 1e-12);
  EXPECT_NEAR(i2.j(1), -n / RL, 1e-12);
  const OutputRow i1 = m.branch_current(branch_named(m, "l1"));
  EXPECT_NEAR(i1.g(0), 1, 1e-12);
  EXPECT_NEAR(i1.j(1), n * n / RL, 1e-12);
  const OutputRow vs = m.node_voltage(m.graph().node_index("s"));
  EXPECT_NEAR(vs.j(1), n, 1e-12);
}

// Three windings coupled pairwise with k = 1 share one flux: one state, imag(l1) =
// i(l1) + sqrt(L2/L1) i(l2) + sqrt(L3/L1) i(l3).
TEST(PerfectCoupling, ThreeWindingsShareOneFlux) {
  NetlistBuilder b;
  b.v("v1", "p", "0", NetlistBuilder::sin(0, 10, 1000)).r("r1", "p", "a", 1).l("l1", "a", "0", 1e-3);
  b.l("l2", "s", "0", 4e-3).r("r2", "s", "0", 10).l("l3", "t", "0", 9e-3).r("r3", "t", "0", 20);
  b.k("k12", "l1", "l2", 1.0).k("k13", "l1", "l3", 1.0).k("k23", "l2", "l3", 1.0);
  CircuitModel m = build(b);
  ASSERT_EQ(m.lcs().states(), 1);
  const StateInfo& st = m.states()[0];
  EXPECT_EQ(st.label, "imag(l1)");
  ASSERT_EQ(st.windings.size(), 3u);
  EXPECT_NEAR(st.windings[1].second, 2, 1e-12);
  EXPECT_NEAR(st.windings[2].second, 3, 1e-12);
}

// Two equal windings in series opposition with k = 1: L1 + L2 - 2M = 0, the loop has no
// inductance left and no state; its current is the resistive one at once, v(b) = 0.
TEST(PerfectCoupling, EqualWindingsInSeriesOppositionLeaveNoState) {
  NetlistBuilder b;
  b.v("v1", "a", "0", NetlistBuilder::sin(0, 10, 1000)).r("r1", "a", "b", 10);
  b.l("l1", "b", "c", 1e-3).l("l2", "0", "c", 1e-3).k("k1", "l1", "l2", 1.0);
  CircuitModel m = build(b);
  EXPECT_EQ(m.lcs().states(), 0);
  const OutputRow i = m.branch_current(branch_named(m, "r1"));
  EXPECT_NEAR(i.j(1), 0.1, 1e-12);
  EXPECT_NEAR(m.node_voltage(m.graph().node_index("b")).j(1), 0, 1e-12);
  EXPECT_NEAR(m.node_voltage(m.graph().node_index("c")).j(1), 0, 1e-12);
}

// 1 - k = 1e-6 is far above the tolerance that counts a coupled group as flux-free (1e-12): both
// currents stay states, and the leakage inductance is simulated.
TEST(PerfectCoupling, NearlyPerfectCouplingKeepsBothStates) {
  NetlistBuilder b;
  b.v("v1", "p", "0", NetlistBuilder::sin(0, 10, 1000)).l("l1", "p", "0", 1e-3).l("l2", "s", "0", 4e-3);
  b.k("k1", "l1", "l2", 1 - 1e-6).r("rl", "s", "0", 50);
  CircuitModel m = build(b);
  ASSERT_EQ(m.lcs().states(), 2);
  EXPECT_EQ(m.states()[0].label, "i(l1)");
  EXPECT_EQ(m.states()[1].label, "i(l2)");
}

// (4) An ideal transformer straight from a voltage source into a capacitor: the current that
// carries no flux sees no resistance, v(c1) = 2 u would be forced (an impulsive current, higher
// index). Refused, naming both windings.
TEST(PerfectCoupling, HigherIndexCircuitIsRefusedNamingTheWindings) {
  NetlistBuilder b;
  b.v("v1", "p", "0", NetlistBuilder::sin(0, 10, 1000)).l("l1", "p", "0", 1e-3).l("l2", "s", "0", 4e-3);
  b.k("k1", "l1", "l2", 1.0).c("c1", "s", "0", 1e-6);
  try {
    build(b);
    FAIL() << "expected a topology error";
  } catch (const TopologyError& e) {
    EXPECT_EQ(e.message(),
              "perfectly coupled inductors l1 and l2 (k = 1): the current that carries no flux "
              "between the windings meets no resistance or diode, so the winding currents are not "
              "determined (a higher-index circuit); put resistance in series with a winding or use "
              "k < 1");
    EXPECT_EQ(e.elements(), (std::vector<int>{1, 2}));
  }
  // With a resistor in series with the secondary the same circuit is fine.
  NetlistBuilder r;
  r.v("v1", "p", "0", NetlistBuilder::sin(0, 10, 1000)).l("l1", "p", "0", 1e-3).l("l2", "s", "0", 4e-3);
  r.k("k1", "l1", "l2", 1.0).r("r2", "s", "c", 1).c("c1", "c", "0", 1e-6);
  EXPECT_EQ(build(r).lcs().states(), 2);  // imag(l1) and v(c1)
}

}  // namespace
}  // namespace lcs
