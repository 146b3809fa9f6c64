// Transistor junctions fitted to the currents they carry in the circuit (issue 13, as diodes are:
// diode_refit.h). A card with IS and BF only used to get the chord of its junction curves between
// 1 mA and 100 mA, wherever the transistor was biased.
#include <cmath>
#include <fstream>

#include "tests/cli_support.h"

namespace lcs {
namespace {

using namespace cli_testing;

constexpr double kVt = 0.025864917007157;  // ngspice 39's thermal voltage at 27 C

// A common-emitter stage biased at microamperes: 2 V through 1 Mohm into the base, 10 kohm to 5 V
// at the collector. In the active region the Ebers-Moll transistor's emitter junction carries
// i_DE = (1 + BF) i_B with v_BE = Vt ln(1 + i_DE / I_ES), I_ES = IS / alpha_F.
const char* const kBiased =
    "common emitter biased at microamperes, a card with IS and BF only\n"
    "vcc vcc 0 5\n"
    "vb in 0 2\n"
    "rb in b 1meg\n"
    "rc vcc c 10k\n"
    "q1 c b 0 qs\n"
    ".model qs npn(is=1e-16 bf=100)\n"
    ".tran 1u 10u\n"
    ".print tran v(c) v(b)\n"
    ".end\n";

// The Shockley operating point of kBiased: i_B = (2 - v_BE) / 1 Mohm, solved by Newton's method.
void shockley_bias(double& vb, double& vc) {
  const double bf = 100, alpha = bf / (1 + bf), ies = 1e-16 / alpha;
  double v = 0.6;
  for (int k = 0; k < 100; ++k) {
    const double f = ies * std::expm1(v / kVt) - (1 + bf) * (2 - v) / 1e6;
    const double df = ies * std::exp(v / kVt) / kVt + (1 + bf) / 1e6;
    v -= f / df;
  }
  vb = v;
  vc = 5 - 10e3 * bf * (2 - v) / 1e6;
}

TEST(TransistorFit, AJunctionBiasedAtMicroamperesGetsTheCurveAtItsCurrent) {
  const fs::path dir = scratch_dir("transistor_fit_bias");
  const fs::path deck = dir / "biased.cir";
  std::ofstream(deck) << kBiased;
  const fs::path csv = dir / "out.csv";
  for (const char* method : {"event", "euler"}) {
    const Result r = run_lcspice("run '" + deck.string() + "' --method " + method + " -o '" + csv.string() + "'", dir);
    ASSERT_EQ(r.code, 0) << r.err;
    const Csv out = parse_csv(read_file(csv));
    double vb, vc;
    shockley_bias(vb, vc);
    // A constant current: the fit is the curve's tangent there, exact at the operating point up
    // to the refit's stopping rule (VON moved less than 1 mV). 1 mV in v_BE moves the base
    // current 1 nA and the collector 1 mV; the 1-100 mA chord put both 52 mV off.
    for (double v : column(out, "v(b)")) EXPECT_NEAR(v, vb, 1e-3) << method;
    for (double v : column(out, "v(c)")) EXPECT_NEAR(v, vc, 2e-3) << method;
  }
  // analyze reports the fit over the current the junction carries: 1.28 uA times 101.
  const Result a = run_lcspice("analyze '" + deck.string() + "'", dir);
  ASSERT_EQ(a.code, 0) << a.err;
  EXPECT_NE(a.out.find("transistor q1: B-E junction fitted to its Shockley curve between 0.0001"), std::string::npos)
      << a.out;
  EXPECT_NE(a.out.find("(the currents it carries here)"), std::string::npos) << a.out;
}

}  // namespace
}  // namespace lcs
