// Step LCPs of TTL gates (the NAND of ngspice's fourbitadder.cir and adder_bip.cir, two one-bit
// full adders of it: 18 gates, 234 pairs). Ebers-Moll transistors with parallel junctions (the
// two input transistors share base and collector) make the step LCPs degenerate, and their bases
// are ill-conditioned enough that rounding, not the lexicographic rule, decided Lemke's ratio
// tests: the path came back to a basis it had left and cycled to the iteration limit (the
// adders' exit 3 at 6 ns / 7 ns; this circuit at the first step, 1 ns). lemke.cpp detects the
// revisited basis and restarts on a generically shifted q.
#include <algorithm>
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "netlist/netlist.h"
#include "solver/integrators/theta_method.h"
#include "solver/model/circuit_model.h"
#include "solver/model/initial_state.h"

namespace lcs {
namespace {

// The NAND and one-bit adder subcircuits of fourbitadder.cir, with the transistor parameters
// lcspice used before it modelled CJC (RB is ignored; CJC left out). Inputs: the deck's first three pulses.
const char* kTwoBitAdder = R"(two one-bit TTL adders
.model dmod D
.model qmod NPN(BF=75 CJE=1PF)
.subckt NAND 1 2 3 4
q1 9 5 1 qmod
d1clamp 0 1 dmod
q2 9 5 2 qmod
d2clamp 0 2 dmod
rb 4 5 4k
r1 4 6 1.6k
q3 6 9 8 qmod
r2 8 0 1k
rc 4 7 130
q4 7 6 10 qmod
dvbedrop 10 3 dmod
q5 3 8 0 qmod
.ends
.subckt ONEBIT 1 2 3 4 5 6
x1 1 2 7 6 NAND
x2 1 7 8 6 NAND
x3 2 7 9 6 NAND
x4 8 9 10 6 NAND
x5 3 10 11 6 NAND
x6 3 11 12 6 NAND
x7 10 11 13 6 NAND
x8 12 13 4 6 NAND
x9 11 7 5 6 NAND
.ends
vcc 99 0 DC 5
vina a 0 pulse(0 3 0 10ns 10ns 10ns 50ns)
vinb b 0 pulse(0 3 0 10ns 10ns 20ns 100ns)
vcin cin 0 pulse(0 3 0 10ns 10ns 40ns 200ns)
x1 a b cin s0 c0 99 ONEBIT
rs0 s0 0 1k
x2 a b c0 s1 c1 99 ONEBIT
rs1 s1 0 1k
rc1 c1 0 1k
.tran 1ns 200ns uic
.end
)";

// From rest (UIC: every capacitor at 0 V, the supply and inputs switched on at t = 0) with
// implicit Euler at the deck's 1 ns on the dense step LCP (Lemke's path; the sparse active-set
// path leaves transistor circuits' mode changes to Lemke anyway):
//  - every step's z and w = C x + D z + F u solve the complementarity problem to rounding;
//  - where the inputs have been steady for 10 ns, the outputs are the full adders' truth table
//    at TTL levels, and a low output is the saturated output transistor's V_CE of the ideal
//    law, VON_BE - VON_BC (the junction fits lcspice prints for this card: 0.772662660638 V and
//    0.755077550043 V) plus RON = 1.20312 ohm times its junction currents, a few mA: 17.6 mV
//    to 17.6 + 6 mV;
//  - Lemke's path did need the restart (without it this throws at t = 1 ns).
TEST(TtlAdderSteps, EveryStepIsComplementaryAndTheOutputsAreTheTruthTable) {
  const Netlist netlist = parse_netlist_string(kTwoBitAdder, "ttl_adder.cir");
  ModelOptions mo;
  mo.t1 = 200e-9;
  const CircuitModel model = CircuitModel::build(netlist, mo);
  const Lcs& s = model.lcs();
  ASSERT_EQ(s.pairs(), 234);
  ThetaMethod euler(model, 1.0, /*sparse=*/false);
  const double h = 1e-9;
  Eigen::VectorXd x = initial_state(model, true, 0.0).x, z(s.pairs());
  euler.Start(0.0, h, x, z);

  // t (ns) -> a, b, cin and the expected s0, c0, s1, c1 (bit 1's carry-in is c0).
  struct Settled { int t; int a, b, cin; };
  const Settled settled[] = {{20, 1, 1, 1}, {50, 0, 0, 1}, {100, 0, 0, 0}, {120, 1, 1, 0},
                             {150, 0, 0, 0}, {170, 1, 0, 0}, {200, 0, 0, 0}};
  const double vce_sat = 0.772662660638 - 0.755077550043;
  auto v = [&](const char* node, double t) {
    return model.evaluate_dc(model.node_voltage(model.graph().node_index(node)), x, z, t);
  };
  int checked = 0;
  for (int k = 1; k <= 200; ++k) {
    ASSERT_NO_THROW(euler.Step((k - 1) * h, h, x, z)) << "step " << k;
    const Eigen::VectorXd w = s.C * x + s.D * z + s.F * model.input_values(k * h);
    // z are junction currents (mA) or voltage margins (V), w the other: scale 1 + max.
    const double scale = 1 + x.cwiseAbs().maxCoeff() + z.cwiseAbs().maxCoeff();
    ASSERT_GE(z.minCoeff(), 0.0) << "step " << k;
    ASSERT_GE(w.minCoeff(), -1e-9 * scale) << "step " << k;
    for (int i = 0; i < s.pairs(); ++i)
      ASSERT_LE(std::min(z(i), w(i)), 1e-9 * scale) << "step " << k << " pair " << i;
    for (const Settled& st : settled) {
      if (st.t != k) continue;
      ++checked;
      const int s0 = st.a ^ st.b ^ st.cin, c0 = (st.a & st.b) | (st.cin & (st.a ^ st.b));
      const int s1 = st.a ^ st.b ^ c0, c1 = (st.a & st.b) | (c0 & (st.a ^ st.b));
      const std::pair<const char*, int> outputs[] = {{"s0", s0}, {"c0", c0}, {"s1", s1}, {"c1", c1}};
      for (const auto& [node, high] : outputs) {
        const double out = v(node, k * h);
        if (high) {
          EXPECT_GE(out, 2.4) << node << " at " << k << " ns";
        } else {
          EXPECT_GE(out, vce_sat - 1e-9) << node << " at " << k << " ns";
          EXPECT_LE(out, vce_sat + 6e-3) << node << " at " << k << " ns";
        }
      }
    }
  }
  EXPECT_EQ(checked, 7);
  EXPECT_GT(euler.stats().lcp.lemke_restarts, 0);
}

}  // namespace
}  // namespace lcs
