// The θ-method's start on the descriptor form (descriptor_start.h): on a charged multiplier the
// same z as the dense start (start_complementarity.h), without its dense LCP; refused where a
// pair at z = w = 0 leaves undetermined something a step reads.
#include <algorithm>
#include <string>

#include <gtest/gtest.h>

#include "netlist/netlist.h"
#include "solver/integrators/descriptor_start.h"
#include "solver/integrators/start_complementarity.h"
#include "solver/integrators/theta_method.h"
#include "solver/model/circuit_model.h"

namespace lcs {
namespace {

// `bench --scale cw`'s multiplier (cli/scale_family.cpp), N stages, from rest; `extra` cards
// (before .end) and the diodes' VON may be changed.
CircuitModel multiplier(int n, const std::string& von = "0.7", const std::string& extra = "") {
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
  s += "RL b" + std::to_string(n) + " 0 1g\n.model dcw D(VON=" + von + " RON=1)\n.tran 100u 40m UIC\n" + extra + ".end\n";
  const Netlist netlist = parse_netlist_string(s, "cw.cir");
  ModelOptions mo;
  mo.t1 = netlist.tran->tstop;
  return CircuitModel::build(netlist, mo);
}

// From the states of a 100-stage multiplier charging (every 10th step of 1.5 periods at 100 us,
// some diodes conducting), the descriptor start and the dense start give the same z. The dense
// start's step h is 1e-8 of the run's or less, so the two may differ by O(h) rates: measured
// 2.5e-12 to 3.6e-12 of the largest z (1e-9 asked), the answer accepted at all 30 instants, a
// diode conducting at each.
TEST(DescriptorStart, GivesTheDenseStartsZOnAChargingMultiplier) {
  const CircuitModel model = multiplier(100);
  ASSERT_NE(model.sparse_descriptor(), nullptr);
  const SparseDescriptor& d = *model.sparse_descriptor();
  const double h = 1e-4;
  ThetaMethod run(model, 1.0);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(model.state_count()), z = Eigen::VectorXd::Zero(model.pair_count());
  run.Start(0.0, h, x, z);
  int accepted = 0, conducting = 0;
  double worst = 0;
  for (int k = 1; k <= 300; ++k) {
    run.Step((k - 1) * h, h, x, z);
    if (k % 10 != 0) continue;
    const double t = k * h;
    StepperStats own, dense_stats;
    Eigen::VectorXd zd = z;
    if (!descriptor_start_z(model, d, t, x, own, zd)) continue;
    ++accepted;
    EXPECT_EQ(own.lcp.solves, 0);
    const Eigen::VectorXd zdense = consistent_start_z(model, t, h, x, dense_stats, z);
    const double size = std::max(zdense.cwiseAbs().maxCoeff(), 1e-300);
    if (zdense.maxCoeff() > 0) ++conducting;
    worst = std::max(worst, (zd - zdense).cwiseAbs().maxCoeff() / size);
  }
  EXPECT_GE(accepted, 20);
  EXPECT_GE(conducting, 5);  // not only instants with every diode off
  EXPECT_LT(worst, 1e-9);
}

// A run's start takes the descriptor path: no dense LCP (the stepper's lcp counts stay zero).
TEST(DescriptorStart, TheThetaMethodStartsOnIt) {
  const CircuitModel model = multiplier(100);
  ThetaMethod run(model, 1.0);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(model.state_count()), z = Eigen::VectorXd::Zero(model.pair_count());
  run.Start(0.0, 1e-4, x, z);
  EXPECT_EQ(run.stats().lcp.solves, 0);
  EXPECT_EQ(run.stats().sparse.solves, 1);
  EXPECT_EQ(z.cwiseAbs().maxCoeff(), 0.0);  // at rest every diode is off (w = VON)
}

// Pairs at z = w = 0 (diodes of VON 0 between uncharged capacitors at a zero source) are
// taken here when the mode with them held on is regular: the limit LCP's solution is then
// isolated, and the dense start's tiny step reaches it to O(h) whichever way those pairs go (z
// is continuous where it is zero). From rest every diode of the VON = 0 multiplier is at zero;
// the dense start cost 1.46 of the 500-stage run's 1.79 s (0.31 s on this path).
TEST(DescriptorStart, TakesPairsAtZeroZAndWWhereTheirModeIsRegular) {
  const CircuitModel model = multiplier(100, "0");
  ThetaMethod run(model, 1.0);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(model.state_count()), z = Eigen::VectorXd::Zero(model.pair_count());
  run.Start(0.0, 1e-4, x, z);
  EXPECT_EQ(run.stats().lcp.solves, 0);  // the dense start was not asked
  EXPECT_EQ(z.cwiseAbs().maxCoeff(), 0.0);
}

// Charged by a run, then the first stage's two capacitors emptied at a zero source: its diodes
// sit at v = 0 = VON with no current, while others conduct. The same z as the dense start.
TEST(DescriptorStart, GivesTheDenseStartsZWithPairsAtZeroBesideConductingOnes) {
  const CircuitModel model = multiplier(100, "0");
  const SparseDescriptor& d = *model.sparse_descriptor();
  const double h = 1e-4;
  ThetaMethod run(model, 1.0);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(model.state_count()), z = Eigen::VectorXd::Zero(model.pair_count());
  run.Start(0.0, h, x, z);
  for (int k = 1; k <= 130; ++k) run.Step((k - 1) * h, h, x, z);
  const std::vector<StateInfo>& states = model.states();
  int emptied = 0;
  for (size_t j = 0; j < states.size(); ++j)
    if (states[j].label == "v(c1)" || states[j].label == "v(c2)") {
      x(static_cast<int>(j)) = 0;
      ++emptied;
    }
  ASSERT_EQ(emptied, 2);
  StepperStats own, dense_stats;
  Eigen::VectorXd zd = z;
  ASSERT_TRUE(descriptor_start_z(model, d, 0.0, x, own, zd));
  const Eigen::VectorXd zdense = consistent_start_z(model, 0.0, h, x, dense_stats, z);
  ASSERT_GT(zdense.maxCoeff(), 0);  // some diodes conduct
  EXPECT_LT((zd - zdense).cwiseAbs().maxCoeff(), 1e-9 * zdense.cwiseAbs().maxCoeff());
}

// A diode to a node nothing else reaches: held on, its mode is singular (the node's potential and
// the diode's margin z are free at the instant), but that direction moves nothing a step reads,
// so the answer is taken (the dense start's tiny-step LCP is as undetermined there). The run
// from it follows the dense path's run: states after 150 steps of 100 us (the multiplier
// charging, the floating diode off) within 1e-9 of their size, and the other pairs' z at the
// start the dense start's.
TEST(DescriptorStart, TakesADiodeToAFloatingNodeWhoseFreePotentialNoStepReads) {
  const CircuitModel model = multiplier(70, "0.7", "DF b70 fl dcw\n");
  ASSERT_NE(model.sparse_descriptor(), nullptr);
  const int n = model.state_count(), m = model.pair_count();
  StepperStats stats, dense_stats;
  Eigen::VectorXd z = Eigen::VectorXd::Zero(m);
  ASSERT_TRUE(descriptor_start_z(model, *model.sparse_descriptor(), 0.0, Eigen::VectorXd::Zero(n), stats, z));
  const Eigen::VectorXd zdense = consistent_start_z(model, 0.0, 1e-4, Eigen::VectorXd::Zero(n), dense_stats,
                                                    Eigen::VectorXd::Zero(m));
  int floating = -1;
  for (int k = 0; k < m; ++k)
    if (model.graph().branches[model.pairs()[k].branch].name == "df") floating = k;
  ASSERT_GE(floating, 0);
  for (int k = 0; k < m; ++k) {
    if (k != floating) {
      EXPECT_NEAR(z(k), zdense(k), 1e-12) << "pair " << k;
    }
  }

  const double h = 1e-4;
  ThetaMethod sparse(model, 1.0), dense(model, 1.0, true, m + 1);  // the second never steps on the descriptor
  Eigen::VectorXd xs = Eigen::VectorXd::Zero(n), zs = Eigen::VectorXd::Zero(m), xd = xs, zd = zs;
  sparse.Start(0.0, h, xs, zs);
  dense.Start(0.0, h, xd, zd);
  for (int k = 0; k < 150; ++k) {
    sparse.Step(k * h, h, xs, zs);
    dense.Step(k * h, h, xd, zd);
  }
  ASSERT_GT(xd.cwiseAbs().maxCoeff(), 1.0);  // charged
  EXPECT_LT((xs - xd).cwiseAbs().maxCoeff(), 1e-9 * xd.cwiseAbs().maxCoeff());
}

// An ideal diode (RON = 0) across a capacitor charged to exactly its threshold: held on, the
// diode's voltage is the capacitor's whatever its current, so at the instant that current is
// free, and a step reads it (the capacitor's row): the answer is refused and the dense start
// decides (its tiny step would discharge the capacitor below the threshold: the current is 0).
TEST(DescriptorStart, RefusesAFreeCurrentThatAStepReads) {
  const CircuitModel model = multiplier(70, "0.7", "CQ p 0 1u\nDQ p 0 dq\n.model dq D(VON=0.7 RON=0)\n");
  ASSERT_NE(model.sparse_descriptor(), nullptr);
  const int n = model.state_count(), m = model.pair_count();
  Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
  for (int j = 0; j < n; ++j)
    if (model.states()[j].label == "v(cq)") x(j) = 0.7;
  ASSERT_EQ(x.sum(), 0.7);
  // The search is started with DQ off, where its mode is regular and the solution (z = w = 0)
  // is found; held on, its current is free.
  Eigen::VectorXd preferred = Eigen::VectorXd::Constant(m, 7.0);
  for (int k = 0; k < m; ++k)
    if (model.graph().branches[model.pairs()[k].branch].name == "dq") preferred(k) = 0.0;
  ASSERT_EQ(preferred.sum(), 7.0 * (m - 1));
  StepperStats stats;
  Eigen::VectorXd z = preferred;
  EXPECT_FALSE(descriptor_start_z(model, *model.sparse_descriptor(), 0.0, x, stats, z));
  EXPECT_EQ(z, preferred);  // untouched
}

}  // namespace
}  // namespace lcs
