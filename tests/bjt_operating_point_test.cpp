// Operating points of transistor circuits whose DC network ties nodes only through junctions
// (the emitters of a differential pair fed by a transistor's collector, the node between two
// diode-connected transistors), as the RCA 3040 amplifier and the bipolar adders do. The static
// LCP's A is singular there; its regularised Schur complement used to give Lemke's numerical
// failure (rca3040, the adders) and spurious "operating points" with a junction held off by the
// regularisation's leak (the pair below). The ideal Ebers–Moll closed form (Stewart 5.4.7) is the
// reference; the answers are exact solutions of the unreduced DC equations, so 1e-9 relative.
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include <gtest/gtest.h>

#include "tests/cli_support.h"

namespace lcs::cli_testing {
namespace {

const std::string kRealWorld = std::string(LCSPICE_REALWORLD_DIR) + "/ngspice";

// Every value `lcspice op` prints ("  v(x) = value", "  i(d1) = value   (on)").
std::map<std::string, double> op_values(const std::string& out) {
  std::map<std::string, double> v;
  std::istringstream in(out);
  std::string line;
  while (std::getline(in, line)) {
    const size_t eq = line.find('=');
    if (eq == std::string::npos) continue;
    std::string name = line.substr(0, eq);
    name.erase(0, name.find_first_not_of(' '));
    name.erase(name.find_last_not_of(' ') + 1);
    v[name] = std::strtod(line.c_str() + eq + 1, nullptr);
  }
  return v;
}

// The node voltages among them.
std::map<std::string, double> op_voltages(const std::string& out) {
  std::map<std::string, double> v;
  for (const auto& [name, value] : op_values(out))
    if (name.rfind("v(", 0) == 0) v[name] = value;
  return v;
}

// A differential pair (q1, q2, bases to ground through RB) whose emitter node e is fed only by
// the tail transistor q3's collector; q3's base is biased by a stack of two diode-connected
// transistors (q4, q5, node d between them) from VEE, fed through RBIAS from ground. Junctions
// VON = 0.7, RON = 10; BF = 80, BR = 1; every B-C junction off.
struct TailPair {
  double vcc = 15, vee = -15, rb = 1e3, rc = 4e3, re = 1e3, rbias = 10e3, von = 0.7, ron = 10, bf = 80;
  double af() const { return bf / (1 + bf); }
  // v(b3) = VEE + 2 VON + 2 RON i_s (the stack), i_s = -v(b3)/RBIAS - i_E3/(BF+1),
  // i_E3 = (v(b3) - VON - VEE)/(RE + RON) (q3's B-E junction and RE): linear in v(b3).
  double vb3() const {
    const double k = 1.0 / ((re + ron) * (bf + 1));
    return (vee + 2 * von - 2 * ron * k * (-von - vee)) / (1 + 2 * ron / rbias + 2 * ron * k);
  }
  double ie3() const { return (vb3() - von - vee) / (re + ron); }
  double stack() const { return -vb3() / rbias - ie3() / (bf + 1); }
  double ie() const { return af() * ie3() / 2; }  // each side of the pair: half of q3's collector
  std::map<std::string, double> voltages() const {
    const double vb = -rb * ie() / (bf + 1);
    return {{"v(b1)", vb},
            {"v(b2)", vb},
            {"v(e)", vb - von - ron * ie()},
            {"v(c1)", vcc - rc * af() * ie()},
            {"v(c2)", vcc - rc * af() * ie()},
            {"v(b3)", vb3()},
            {"v(e3)", vb3() - von - ron * ie3()},
            {"v(d)", vee + von + ron * stack()}};
  }
};

TEST(BjtOperatingPoint, DifferentialPairOnATransistorTailIsTheUniqueClosedForm) {
  const TailPair c;
  const fs::path dir = scratch_dir("bjt_op_tail_pair");
  std::ofstream(dir / "pair.cir") << "differential pair on a transistor tail, diode-connected bias stack\n"
                                     "vcc 2 0 15\nvee 3 0 -15\nrb1 b1 0 1k\nrb2 b2 0 1k\n"
                                     "q1 c1 b1 e qn\nq2 c2 b2 e qn\nrc1 2 c1 4k\nrc2 2 c2 4k\n"
                                     "q3 e b3 e3 qn\nre e3 3 1k\nrbias 0 b3 10k\n"
                                     "q4 b3 b3 d qn\nq5 d d 3 qn\n"
                                     ".model qn npn bf=80 von=0.7 ron=10 cje=3p\n.tran 1n 10n\n.end\n";
  const Result r = run_lcspice("op '" + (dir / "pair.cir").string() + "'", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  // Every state is fixed by the conducting junctions: nothing left to least energy.
  EXPECT_EQ(r.err.find("does not determine"), std::string::npos) << r.err;
  const auto v = op_voltages(r.out);
  for (const auto& [node, value] : c.voltages()) {
    ASSERT_TRUE(v.count(node)) << node << "\n" << r.out;
    EXPECT_NEAR(v.at(node), value, 1e-9 * c.vcc) << node << "\n" << r.out;
  }
}

// The real deck: 20 pairs, past the enumeration, so Lemke's path and its repair. Its card has no
// VON/RON (fitted from IS), so no closed form here; the amplifier is symmetric, so both halves
// must agree to the solution's precision, and the transistors that conduct must have
// forward-biased B-E junctions. op fits the lines as run does, over the deck's transient, where
// the sine drives one side only and the halves' lines differ: the deck is read with its input
// at 0 V (vin = 0 at t = 0 either way).
TEST(BjtOperatingPoint, Rca3040HasASymmetricOperatingPoint) {
  const std::string deck = kRealWorld + "/tests/general/rca3040.cir";
  if (!fs::exists(deck)) GTEST_SKIP() << deck << " not found";
  const fs::path dir = scratch_dir("bjt_op_rca3040");
  std::string text = read_file(deck);
  const std::string input = "vin 1 0 sin(0 0.1 50meg 0.5ns) ac 1";
  ASSERT_NE(text.find(input), std::string::npos);
  text.replace(text.find(input), input.size(), "vin 1 0 0");
  std::ofstream(dir / "rca3040.cir") << text;
  const Result r = run_lcspice("op '" + (dir / "rca3040.cir").string() + "'", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  const auto v = op_voltages(r.out);
  for (const auto& [a, b] : std::vector<std::pair<std::string, std::string>>{
           {"v(30)", "v(31)"}, {"v(5)", "v(6)"}, {"v(10)", "v(11)"}, {"v(14)", "v(15)"}, {"v(16)", "v(17)"}}) {
    ASSERT_TRUE(v.count(a) && v.count(b)) << r.out;
    EXPECT_NEAR(v.at(a), v.at(b), 1e-9 * 15) << a << " vs " << b << "\n" << r.out;
  }
  // The current mirror's diode-connected stack q7, q8 conducts: v(12) > v(13) > 0.
  EXPECT_GT(v.at("v(12)"), v.at("v(13)"));
  EXPECT_GT(v.at("v(13)"), 0.0);
}

TEST(BjtOperatingPoint, BipolarAddersHaveAnOperatingPoint) {
  for (const std::string rel : {"/tests/general/fourbitadder.cir", "/examples/digital/compare/adder_bip.cir"}) {
    const std::string deck = kRealWorld + rel;
    if (!fs::exists(deck)) GTEST_SKIP() << deck << " not found";
    const fs::path dir = scratch_dir("bjt_op_adder");
    const Result r = run_lcspice("op '" + deck + "'", dir);
    EXPECT_EQ(r.code, 0) << rel << "\n" << r.err;
    EXPECT_EQ(r.err.find("error"), std::string::npos) << rel << "\n" << r.err;
  }
}

// The driver of ngspice's ltra4_1_line.sp cut down to what shows the fault: emitter followers
// q8, q9 whose collectors float, into a lossy line (4.8 ohm) open at its far end. At DC no
// current has a path: every current is zero and the line's far end sits at its near end's
// potential. Two defects put 0.43 mA from VCC into the line at its near end and none out at its
// far end (v(a) - v(b) = 0.105 V):
//  - the regularisation of the singular DC problem (-eps I) scaled the line's DC relations
//    (i1 + i2 = 0, v1 - v2 = R len i1: coefficients ~1) by the largest state coefficient (~1e10
//    here), so they read i1 + i2 = 10 S x (wave); each row is now regularised on its own scale;
//  - where Lemke's conducting set has no exact point, the enumeration's one exact solution is
//    taken (the IS-only card needed this).
TEST(BjtOperatingPoint, EmitterFollowersIntoAnOpenLossyLineCarryNoDcCurrent) {
  const fs::path dir = scratch_dir("bjt_op_open_line");
  const fs::path f = dir / "followers.cir";
  for (const char* diode : {"D(IS=1e-14)", "D(VON=0.6 RON=1)"}) {
    std::ofstream(f) << "emitter followers whose collectors float, into a lossy line open at its far end\n"
                        "vcc vcc 0 5\nq8 n7 n11 n10 qn\nq9 n7 n10 a qn\ndd1 n17 n10 dmod\nd501 n17 a dmod\n"
                        "r6 n24 vcc 750\nr12 n24 n11 1.5k\no2 a 0 b 0 lline\n"
                        ".model qn NPN(IS=1e-12 BF=100 CJE=0.09p)\n.model dmod " << diode << "\n"
                        ".model lline ltra r=0.2 g=0 l=9.13e-9 c=3.65e-12 len=24\n.tran 0.1n 20n\n.end\n";
    const Result r = run_lcspice("op '" + f.string() + "'", dir);
    ASSERT_EQ(r.code, 0) << r.err;
    std::map<std::string, double> values = op_values(r.out);
    for (const char* current : {"i(vcc)", "i(o2)", "i2(o2)", "i(r6)", "i(q8:be)", "i(q9:be)"}) {
      ASSERT_TRUE(values.count(current)) << current << "\n" << r.out;
      EXPECT_LT(std::abs(values[current]), 1e-12) << diode << ": " << current;
    }
    EXPECT_NEAR(values["v(n11)"], 5.0, 1e-9) << diode;           // no current through r6, r12
    EXPECT_NEAR(values["v(a)"], values["v(b)"], 1e-9) << diode;  // none through the line's 4.8 ohm
  }
}

// A DTL NAND gate with both inputs low: the input diodes clamp x at VON + RON i/2; the level
// shifter's diodes d3, d4 and q1's base are off, and the node y between d3 and d4 is reached only
// through them (its potential is a choice). The enumeration found this one point twice, d3 "on"
// at a current of the regularisation's leak in one copy, and `op` and `run` refused the deck as
// having 2 operating points ("transistor d3", a diode); polished, the copies are one point.
TEST(BjtOperatingPoint, DtlGateWithAFloatingLevelShifterNodeHasOneOperatingPoint) {
  const fs::path dir = scratch_dir("bjt_op_dtl");
  const fs::path f = dir / "dtl.cir";
  std::ofstream(f) << "DTL NAND gate, inputs low\nVCC vcc 0 5\nVA a 0 0\nVB b 0 0\nDA x a dx\nDB x b dx\n"
                      "R1 vcc x 5k\nD3 x y dx\nD4 y z dx\nR2 z 0 5k\nRC vcc out 2.2k\nQ1 out z 0 qx\n"
                      ".model dx D(VON=0.7 RON=10)\n.model qx NPN(BF=100 VON=0.7 RON=10)\n.tran 10n 1u\n.end\n";
  const Result r = run_lcspice("op '" + f.string() + "'", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  std::map<std::string, double> values = op_values(r.out);
  const double i = 4.3 / 5005;  // (5 - x)/5k with x = 0.7 + 10 (i/2)
  EXPECT_NEAR(values["v(x)"], 0.7 + 5 * i, 1e-12);
  EXPECT_NEAR(values["i(da)"], i / 2, 1e-15);
  EXPECT_NEAR(values["v(out)"], 5.0, 1e-12);
  EXPECT_NEAR(values["v(z)"], 0.0, 1e-12);
  EXPECT_EQ(values["i(d3)"], 0.0);
  const Result all = run_lcspice("op --all '" + f.string() + "'", dir);
  EXPECT_NE(all.out.find("* 1 solution"), std::string::npos) << all.out;
  const Result run = run_lcspice("run '" + f.string() + "' -o '" + (dir / "out.csv").string() + "'", dir);
  EXPECT_EQ(run.code, 0) << run.err;
}

}  // namespace
}  // namespace lcs::cli_testing
