// Physical laws the circuits in circuits/ must obey, checked against textbook formulas.
#include <cmath>

#include <gtest/gtest.h>

#include "netlist/netlist.h"
#include "solver/integrators/transient.h"
#include "tests/cli_support.h"

namespace lcs {
namespace {

// An n-stage Cockcroft-Walton multiplier (f = 50 Hz, C = 10 uF every stage, Vpk = 100 V, diodes
// VON = 0.7 V) settles at 2 n Vpk - 2 n VON - dV with the load regulation
//   dV = I/(f C) (2n^3/3 + n^2/2 - n/6)  and peak-to-peak ripple  I/(f C) n(n+1)/2,
// I = V/RL (Kuffel, Zaengl & Kuffel, High Voltage Engineering, 2.2.2). For n = 3, RL = 1 MOhm
// the mean output is about 570.7 V with 6.8 V ripple; the formulas neglect RON = 1 ohm and the
// ripple's effect on I, so they are held to 0.5 % and 10 %.
TEST(CockcroftWalton, SteadyStateMatchesLoadRegulationFormula) {
  Netlist netlist = parse_netlist_file(cli_testing::source_path("circuits/cockcroft_walton.cir").string());
  ModelOptions mo;
  mo.t1 = 4.0;
  CircuitModel model = CircuitModel::build(netlist, mo);
  TransientOptions o;
  o.step = netlist.tran->tstep;
  o.tstop = 4.0;
  o.tstart = 3.96;  // the last two cycles
  o.uic = true;
  MemorySink sink;
  run_transient(model, model.output_map({parse_probe("v(f)", {})}), o, sink);
  double lo = INFINITY, hi = -INFINITY;
  for (const Eigen::VectorXd& row : sink.rows) lo = std::min(lo, row(0)), hi = std::max(hi, row(0));
  const int n = 3;
  const double f = 50, C = 10e-6, Vpk = 100, VON = 0.7, RL = 1e6;
  const double ideal = 2 * n * Vpk - 2 * n * VON;
  const double k = (2.0 * n * n * n / 3 + n * n / 2.0 - n / 6.0);
  const double V = ideal / (1 + k / (f * C * RL));  // solves V = ideal - (V/RL)/(f C) k
  const double ripple = V / RL / (f * C) * n * (n + 1) / 2;
  EXPECT_NEAR((lo + hi) / 2, V, 0.005 * V);
  EXPECT_NEAR(hi - lo, ripple, 0.1 * ripple);
}

}  // namespace
}  // namespace lcs
