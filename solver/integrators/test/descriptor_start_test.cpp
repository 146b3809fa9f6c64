// The θ-method's start on the descriptor form (descriptor_start.h): on a charged multiplier the
// same z as the dense start (start_complementarity.h), without its dense LCP; refused where a
// pair sits at z = w = 0.
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

// `bench --scale cw`'s multiplier (cli/scale_family.cpp), N stages, from rest.
CircuitModel multiplier(int n) {
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
  s += "RL b" + std::to_string(n) + " 0 1g\n.model dcw D(VON=0.7 RON=1)\n.tran 100u 40m UIC\n.end\n";
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

// A pair at z = w = 0 (a diode of VON 0 across an uncharged capacitor at a zero source) is what
// the dense start hands to the event method's mode selection: refused here.
TEST(DescriptorStart, RefusesAPairAtZeroZAndW) {
  std::string s = "degenerate\nV1 in 0 SIN(0 1 1k)\n";
  for (int k = 1; k <= 70; ++k) {
    const std::string a = "n" + std::to_string(k), prev = k == 1 ? "in" : "n" + std::to_string(k - 1);
    s += "C" + std::to_string(k) + " " + prev + " " + a + " 1u\nD" + std::to_string(k) + " " + a + " 0 dz\n";
    s += "DB" + std::to_string(k) + " 0 " + a + " dz\n";
  }
  s += ".model dz D(VON=0 RON=1)\n.tran 1u 1m UIC\n.end\n";
  const Netlist netlist = parse_netlist_string(s, "zero.cir");
  ModelOptions mo;
  mo.t1 = netlist.tran->tstop;
  const CircuitModel model = CircuitModel::build(netlist, mo);
  ASSERT_NE(model.sparse_descriptor(), nullptr);
  StepperStats stats;
  Eigen::VectorXd z = Eigen::VectorXd::Constant(model.pair_count(), 7.0);
  EXPECT_FALSE(descriptor_start_z(model, *model.sparse_descriptor(), 0.0,
                                  Eigen::VectorXd::Zero(model.state_count()), stats, z));
  EXPECT_EQ(z, Eigen::VectorXd::Constant(model.pair_count(), 7.0));  // untouched
}

}  // namespace
}  // namespace lcs
