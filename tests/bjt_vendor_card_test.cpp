// A vendor Gummel–Poon card (issue 10): it loads, its junctions get the diode's fit of their
// Shockley curves (I_ES = IS/alphaF with NF, I_CS = IS/alphaR with NR), refitted to the currents
// they carry in the circuit (issue 13: the least-max-error line over them), `analyze` prints the
// fitted values and lists the parameters the ideal model ignores, and a switch built on it runs
// in every method.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "tests/cli_support.h"

namespace lcs::cli_testing {
namespace {

// The 2N2222 card as manufacturers and ngspice libraries give it (LTspice's vendor extras too).
const char* kSwitch =
    "2N2222 switch\nvcc vcc 0 10\nvin in 0 pwl(0 0 1m 5)\nrb in b 100k\nrc vcc c 1k\nq1 c b 0 q2n2222\n"
    ".model Q2N2222 NPN(IS=14.34f XTI=3 EG=1.11 VAF=74.03 BF=255.9 NE=1.307 ISE=14.34f IKF=.2847\n"
    "+ XTB=1.5 BR=6.092 NC=2 ISC=0 IKR=0 RC=1 CJC=7.306p MJC=.3416 VJC=.75 FC=.5 CJE=22.01p MJE=.377\n"
    "+ VJE=.75 TR=46.91n TF=411.1p ITF=.6 VTF=1.7 XTF=3 RB=10 mfg=Philips Vceo=40 Icrate=800m)\n"
    ".tran 10u 1m\n.end\n";

// The least-max-error line over [i1, i2] of the concave v(i) = N Vt ln(1 + i/IS): the chord
// raised by half its largest distance below the curve, reached where the curve's slope
// N Vt / (IS + i) equals the chord's.
void minimax(double is, double n, double i1, double i2, double& von, double& ron) {
  const double vt = 0.025864917007157;
  auto v = [&](double i) { return n * vt * std::log1p(i / is); };
  ron = (v(i2) - v(i1)) / (i2 - i1);
  const double i_star = n * vt / ron - is;
  const double gap = v(i_star) - (v(i1) + ron * (i_star - i1));
  von = v(i1) - ron * i1 + gap / 2;
}

struct FittedJunctionNote {
  double i1 = 0, i2 = 0, von = 0, ron = 0;
  bool found = false;
};

// "transistor q1: B-E junction fitted to its Shockley curve between I1 A and I2 A (the currents it
// carries here): VON = V, RON = R ohm"
FittedJunctionNote fitted_note(const std::string& out, const char* junction) {
  FittedJunctionNote n;
  const std::string head = std::string("transistor q1: ") + junction + " junction fitted to its Shockley curve between ";
  const size_t at = out.find(head);
  if (at == std::string::npos) return n;
  n.found = std::sscanf(out.c_str() + at + head.size(),
                        "%lf A and %lf A (the currents it carries here): VON = %lf V, RON = %lf ohm", &n.i1, &n.i2,
                        &n.von, &n.ron) == 4;
  return n;
}

TEST(BjtVendorCard, LoadsFitsItsJunctionsAndListsWhatTheIdealModelIgnores) {
  const fs::path dir = scratch_dir("bjt_vendor");
  const fs::path f = dir / "q2n2222.cir";
  std::ofstream(f) << kSwitch;
  const Result r = run_lcspice("analyze '" + f.string() + "'", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  const double af = 255.9 / 256.9, ar = 6.092 / 7.092;
  // Each junction's line is the least-max-error one over the currents it carried: the B-E
  // junction from the base drive's turn-on to saturation (mA), the B-C one in saturation (uA).
  for (auto [junction, is] : {std::pair{"B-E", 14.34e-15 / af}, std::pair{"B-C", 14.34e-15 / ar}}) {
    const FittedJunctionNote note = fitted_note(r.out, junction);
    ASSERT_TRUE(note.found) << junction << "\n" << r.out;
    EXPECT_LT(note.i1, note.i2) << junction;
    EXPECT_LT(note.i2, 20e-3) << junction;  // 10 V over 1 kohm at most, far below the 100 mA chord's end
    double von, ron;
    minimax(is, 1.0, note.i1, note.i2, von, ron);
    EXPECT_NEAR(note.von, von, 1e-8 * von) << junction;
    EXPECT_NEAR(note.ron, ron, 1e-8 * ron) << junction;
  }
  for (const char* p : {"vaf", "ikf", "ise", "ne", "rb", "rc", "vjc", "mjc", "tf", "tr", "mfg", "vceo", "icrate"})
    EXPECT_NE(r.out.find(std::string("transistor q1: model parameter ") + p + " is ignored by the ideal model"),
              std::string::npos)
        << p;
  EXPECT_NE(r.out.find("transistor q1: base-emitter capacitance 2.201e-11 F (CJE)"), std::string::npos);
  EXPECT_NE(r.out.find("transistor q1: base-collector capacitance 7.306e-12 F (CJC)"), std::string::npos);
  EXPECT_EQ(r.out.find("parameter cjc is ignored"), std::string::npos);
  // The card's warning lists them once, at the first ignored parameter.
  EXPECT_NE(r.err.find("warning: transistor model 'q2n2222': parameters xti, eg, vaf, ne, ise, ikf, xtb, nc, isc"),
            std::string::npos)
      << r.err;
  // In the active region the fitted B-E junction and BF give the base loop below. Without the
  // card's CJE (`.options bjtcap=0`) and CJC, so that ib is the junction's alone.
  const fs::path bare = dir / "q2n2222_bare.cir";
  std::string text = kSwitch;
  text.insert(text.find(".tran"), ".options bjtcap=0\n");
  text.replace(text.find("CJC=7.306p"), 10, "CJC=0");
  std::ofstream(bare) << text;
  for (const char* method : {"event", "euler", "radau5"}) {
    const fs::path csv = dir / (std::string(method) + ".csv");
    const Result run = run_lcspice("run '" + bare.string() + "' --method " + method + " --probe 'v(in),v(c),ib(q1),ic(q1)' -o '" +
                                       csv.string() + "'",
                                   dir);
    ASSERT_EQ(run.code, 0) << method << ": " << run.err;
    const Csv out = parse_csv(read_file(csv));
    int active_rows = 0;
    std::vector<std::pair<double, double>> loop;  // (junction current, its voltage)
    for (const std::vector<double>& row : out.rows) {
      const double ib = row[3], ic = row[4];
      if (ic <= 1e-9 || row[2] < 1.0) continue;  // cutoff, or saturated
      ++active_rows;
      EXPECT_NEAR(ic / ib, 255.9, 1e-9 * 255.9) << method << " t = " << row[0];
      // Base loop: v_in - Rb ib = VON + RON (ib + ic), one line (each method's own refit).
      loop.push_back({ib + ic, row[1] - 100e3 * ib});
    }
    EXPECT_GT(active_rows, 5) << method;
    if (loop.size() < 2) continue;
    const auto [i0, v0] = loop.front();
    const auto [i1, v1] = loop.back();
    const double ron = (v1 - v0) / (i1 - i0), von = v0 - ron * i0;
    EXPECT_GT(ron, 0) << method;
    EXPECT_GT(von, 0.4) << method;
    for (auto [i, v] : loop) EXPECT_NEAR(v, von + ron * i, 1e-9) << method << " i = " << i;
  }
}

}  // namespace
}  // namespace lcs::cli_testing
