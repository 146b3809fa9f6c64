// A vendor Gummel–Poon card (issue 10): it loads, its junctions get the diode's chord fit of
// their Shockley curves (I_ES = IS/alphaF with NF, I_CS = IS/alphaR with NR, between ifit/10
// and 10 ifit), `analyze` prints the fitted values and lists the parameters the ideal model
// ignores, and a switch built on it runs in every method.
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

// The chord of v(i) = N Vt ln(1 + i/IS) between 1 mA and 100 mA.
void chord(double is, double n, double& von, double& ron) {
  const double vt = 0.025864186, i1 = 1e-3, i2 = 0.1;
  const double v1 = n * vt * std::log1p(i1 / is), v2 = n * vt * std::log1p(i2 / is);
  ron = (v2 - v1) / (i2 - i1);
  von = v1 - ron * i1;
}

std::string fitted_line(const char* junction, double von, double ron) {
  char buf[200];
  std::snprintf(buf, sizeof buf,
                "transistor q1: %s junction fitted to its Shockley curve between 0.001 A and 0.1 A: VON = %.6g V, "
                "RON = %.6g ohm",
                junction, von, ron);
  return buf;
}

TEST(BjtVendorCard, LoadsFitsItsJunctionsAndListsWhatTheIdealModelIgnores) {
  const fs::path dir = scratch_dir("bjt_vendor");
  const fs::path f = dir / "q2n2222.cir";
  std::ofstream(f) << kSwitch;
  const Result r = run_lcspice("analyze '" + f.string() + "'", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  const double af = 255.9 / 256.9, ar = 6.092 / 7.092;
  double von_e, ron_e, von_c, ron_c;
  chord(14.34e-15 / af, 1.0, von_e, ron_e);
  chord(14.34e-15 / ar, 1.0, von_c, ron_c);
  EXPECT_NE(r.out.find(fitted_line("B-E", von_e, ron_e)), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(fitted_line("B-C", von_c, ron_c)), std::string::npos) << r.out;
  for (const char* p : {"vaf", "ikf", "ise", "ne", "rb", "rc", "cjc", "tf", "tr", "mfg", "vceo", "icrate"})
    EXPECT_NE(r.out.find(std::string("transistor q1: model parameter ") + p + " is ignored by the ideal model"),
              std::string::npos)
        << p;
  EXPECT_NE(r.out.find("transistor q1: base-emitter capacitance 2.201e-11 F (CJE)"), std::string::npos);
  // The card's warning lists them once, at the first ignored parameter.
  EXPECT_NE(r.err.find("warning: transistor model 'q2n2222': parameters xti, eg, vaf, ne, ise, ikf, xtb, nc, isc"),
            std::string::npos)
      << r.err;
  // In the active region the fitted B-E junction and BF give the base loop below. Without the
  // card's CJE (`.options bjtcap=0`), so that ib is the junction's alone.
  const fs::path bare = dir / "q2n2222_bare.cir";
  std::string text = kSwitch;
  text.insert(text.find(".tran"), ".options bjtcap=0\n");
  std::ofstream(bare) << text;
  for (const char* method : {"event", "euler", "radau5"}) {
    const fs::path csv = dir / (std::string(method) + ".csv");
    const Result run = run_lcspice("run '" + bare.string() + "' --method " + method + " --probe 'v(in),v(c),ib(q1),ic(q1)' -o '" +
                                       csv.string() + "'",
                                   dir);
    ASSERT_EQ(run.code, 0) << method << ": " << run.err;
    const Csv out = parse_csv(read_file(csv));
    int active_rows = 0;
    for (const std::vector<double>& row : out.rows) {
      const double ib = row[3], ic = row[4];
      if (ic <= 1e-9 || row[2] < 1.0) continue;  // cutoff, or saturated
      ++active_rows;
      EXPECT_NEAR(ic / ib, 255.9, 1e-9 * 255.9) << method << " t = " << row[0];
      // Base loop: v_in = Rb ib + VON + RON (ib + ic).
      EXPECT_NEAR(row[1], 100e3 * ib + von_e + ron_e * (ib + ic), 1e-9) << method << " t = " << row[0];
    }
    EXPECT_GT(active_rows, 5) << method;
  }
}

}  // namespace
}  // namespace lcs::cli_testing
