// The TTL adder's operating point with its junctions refitted to the currents they carry
// (ngspice's examples/digital/compare/adder_bip.cir, 466 complementarity pairs). The ranges in
// tests/data/adder_bip_refit_pass2_ranges.txt are those `lcspice run` builds the refit's second
// pass with (written by that pass: junction, forward lo/hi, reverse lo/hi in A). On them the
// static LCP is as ill-conditioned as the regularised DC equations make it (A singular), and
// Lemke's path ended on a ray after 300 pivots: the run said "the operating point has no
// solution" and the refit kept its first pass's ranges (280 s for the default run, two passes).
// The ray is now repaired as a numerical failure is (operating_point.cpp).
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "netlist/netlist.h"
#include "solver/model/circuit_model.h"
#include "solver/model/operating_point.h"
#include "tests/cli_support.h"

namespace lcs {
namespace {

using namespace cli_testing;

TEST(RealWorldAdders, RefittedJunctionsHaveAnOperatingPoint) {
  const fs::path deck = fs::path(LCSPICE_REALWORLD_DIR) / "ngspice/examples/digital/compare/adder_bip.cir";
  if (!fs::exists(deck)) GTEST_SKIP() << deck << " is missing";
  ModelOptions options;
  std::ifstream ranges(source_path("tests/data/adder_bip_refit_pass2_ranges.txt"));
  std::string line;
  while (std::getline(ranges, line)) {
    std::istringstream is(line);
    std::string key;
    DiodeCurrentRanges r;
    ASSERT_TRUE(is >> key >> r.forward.lo >> r.forward.hi >> r.reverse.lo >> r.reverse.hi) << line;
    options.diode_ranges[key] = r;
  }
  ASSERT_EQ(options.diode_ranges.size(), 343u);
  const Netlist netlist = parse_netlist_file(deck.string());
  options.t1 = netlist.tran->tstop;
  const CircuitModel model = CircuitModel::build(netlist, options);
  ASSERT_EQ(model.pair_count(), 466);
  const OperatingPoint op = solve_operating_point(model, 0.0);

  // It is an equilibrium of the LCS, complementary: A x + B z + E u = 0, 0 <= z _|_ w >= 0.
  const Lcs& s = model.lcs();
  const Eigen::VectorXd u = model.input_values(0.0);
  const Eigen::VectorXd dx = s.A * op.x + s.B * op.z + s.E * u;
  const Eigen::VectorXd w = s.C * op.x + s.D * op.z + s.F * u;
  const double scale_dx = (s.B * op.z).cwiseAbs().maxCoeff() + (s.E * u).cwiseAbs().maxCoeff();
  const double scale_w = (s.F * u).cwiseAbs().maxCoeff();
  EXPECT_LE(dx.cwiseAbs().maxCoeff(), 1e-9 * scale_dx);
  EXPECT_GE(op.z.minCoeff(), 0.0);
  EXPECT_GE(w.minCoeff(), -1e-9 * scale_w);
  EXPECT_LE(op.z.cwiseMin(w).cwiseAbs().maxCoeff(), 1e-9 * std::max(scale_w, op.z.cwiseAbs().maxCoeff()));
  // Its sum and carry bits are at ngspice's level at t = 0: inputs 0 + 0, every output low
  // (ngspice: 0.0178 V each).
  for (const char* node : {"9", "10", "11", "12", "13"}) {
    const double v = model.evaluate_dc(model.node_voltage(model.graph().node_index(node)), op.x, op.z, 0.0);
    EXPECT_LE(v, 0.4) << "v(" << node << ")";
    EXPECT_GE(v, 0.0) << "v(" << node << ")";
  }
}

}  // namespace
}  // namespace lcs
