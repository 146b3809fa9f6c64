// The event method's next mode after a switching where many pairs reach zero at once and the
// mode has to be read off the LCP's basis (Stewart 4.5; pairs_at_zero_lcp.h). N emitter
// followers hang on one drive, each collector fed from VCC through a diode and nothing else.
// While a transistor is off, its emitter current and its collector diode's current are both
// zero: the diode's pair is degenerate (z = w = 0), and only the mode that holds it on at zero
// current keeps the collector node from floating. The switching LCP's z > 0 leaves every such
// diode off (a mode with N floating nodes, not well posed); the search behind it flipped at
// most 10 pairs, so from 11 stages on the run stopped at t = 0 with exit 3, "no consistent mode
// after a switching event (pairs at zero: d0, ..., d10)". Lemke's final basis holds the
// degenerate diodes whose w = 0 row fixes the others' z: one LCP, whatever N.
//
// No storage: every row is the circuit's DC solution, in closed form (ideal Ebers-Moll,
// bjt_circuits_test.cpp): with v = max(0, v(in) - VON),
//   v(e_k) = v (BF + 1) RE / (RB + (BF + 1) RE),   i(d_k) = BF v / (RB + (BF + 1) RE),
//   v(c_k) = VCC - VON (the diode on, at zero current while the transistor is off).
#include <cmath>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "tests/cli_support.h"

namespace lcs::cli_testing {
namespace {

constexpr double kVcc = 5, kVon = 0.7, kRb = 10e3, kRe = 1e3, kBf = 100;

std::string followers(int stages) {
  std::string deck = std::to_string(stages) + " emitter followers with a diode to VCC on one drive\n"
                     "VCC vcc 0 DC 5\nV1 in 0 SIN(0 2 1k)\n";
  for (int k = 0; k < stages; ++k) {
    const std::string s = std::to_string(k);
    deck += "RB" + s + " in b" + s + " 10k\nQ" + s + " c" + s + " b" + s + " e" + s + " qn\nRE" + s + " e" + s +
            " 0 1k\nD" + s + " vcc c" + s + " dx\n";
  }
  deck += ".model dx D(VON=0.7 RON=0)\n.model qn NPN(BF=100 BR=1 VON=0.7)\n.tran 10u 3m\n.end\n";
  return deck;
}

// Measured on 11 stages: every row within 7.6e-15 V (v(e)), 6.1e-18 A (i(d)) and exactly 4.3 V
// (v(c)) of the closed form; the bounds are 1e-9 V and 1e-12 A.
void expect_closed_form(int stages) {
  const fs::path dir = scratch_dir("event_next_mode_" + std::to_string(stages));
  std::ofstream(dir / "followers.cir") << followers(stages);
  const Result r = run_lcspice("run '" + (dir / "followers.cir").string() + "' --method event -o '" +
                                   (dir / "out.csv").string() + "'",
                               dir);
  ASSERT_EQ(r.code, 0) << r.err;
  const Csv csv = parse_csv(read_file(dir / "out.csv"));
  const std::vector<double> t = column(csv, "time"), vin = column(csv, "v(in)");
  ASSERT_GE(t.size(), 301u);  // every TSTEP, and the events
  EXPECT_EQ(t.back(), 3e-3);
  const double g = kRb + (kBf + 1) * kRe;
  for (int k = 0; k < stages; ++k) {
    const std::string s = std::to_string(k);
    const std::vector<double> ve = column(csv, "v(e" + s + ")"), id = column(csv, "i(d" + s + ")"),
                              vc = column(csv, "v(c" + s + ")");
    for (size_t j = 0; j < t.size(); ++j) {
      const double v = std::max(0.0, vin[j] - kVon);
      ASSERT_NEAR(ve[j], v * (kBf + 1) * kRe / g, 1e-9) << "stage " << k << " at t = " << t[j];
      ASSERT_NEAR(id[j], kBf * v / g, 1e-12) << "stage " << k << " at t = " << t[j];
      ASSERT_NEAR(vc[j], kVcc - kVon, 1e-9) << "stage " << k << " at t = " << t[j];
    }
  }
}

TEST(EventNextMode, ThreeEmitterFollowersWithFloatingCollectorsFollowTheClosedForm) { expect_closed_form(3); }

TEST(EventNextMode, ElevenEmitterFollowersWithFloatingCollectorsFollowTheClosedForm) { expect_closed_form(11); }

TEST(EventNextMode, FortyEmitterFollowersWithFloatingCollectorsFollowTheClosedForm) { expect_closed_form(40); }

}  // namespace
}  // namespace lcs::cli_testing
