// The ngspice dialect end to end: a `.control` block's `tran`, LTspice's model-less diode and
// instance parasitics, a shorted clamp diode, and what the real ngspice decks get (exit codes
// and first messages).
#include <cmath>
#include <fstream>

#include "tests/cli_support.h"

namespace lcs::cli_testing {
namespace {

const std::string kRealWorld = std::string(LCSPICE_REALWORLD_DIR) + "/ngspice";

// v(b) of an ideal half-wave rectifier is max(0, v(a)) exactly; the current through the shorted
// clamp diode is zero. (The offset keeps t = 0 away from the diode's threshold, where the
// operating point is degenerate.)
TEST(DialectCli, ControlTranWithAModelLessDiodeAndAShortedClamp) {
  const fs::path dir = scratch_dir("dialect_control_tran");
  std::ofstream(dir / "c.cir") << "half-wave, ngspice style\nV1 a 0 SIN(0.5 1 100)\nD1 a b\nR1 b 0 1k\n"
                                  "X1 b 0 clamp\n.subckt clamp k g\nDC1 g g dm\n.ends\n.model dm d\n"
                                  ".probe v(a) v(b) i(x1.dc1)\n"
                                  ".control\nset color0=white\ntran 0.5m 20m\nplot v(b)\n.endc\n.end\n";
  Result r = run_lcspice("run '" + (dir / "c.cir").string() + "' -o '" + (dir / "o.csv").string() + "'", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("c.cir:11:1: warning: '.control' block: its 'tran' command is run; ignored: 'set', 'plot'"),
            std::string::npos) << r.err;
  EXPECT_NE(r.err.find("c.cir:3:1: warning: diode 'd1' has no model name (LTspice dialect)"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("c.cir:7:5: warning: 'x1.dc1' has both terminals on node '0'"), std::string::npos) << r.err;
  Csv csv = parse_csv(read_file(dir / "o.csv"));
  ASSERT_EQ(csv.header, (std::vector<std::string>{"time", "v(a)", "v(b)", "i(x1.dc1)"}));
  ASSERT_GE(csv.rows.size(), 41u);  // every 0.5 ms to 20 ms, plus the switching events
  EXPECT_NEAR(csv.rows.back()[0], 20e-3, 1e-15);
  for (std::size_t k = 0; k < csv.rows.size(); ++k) {
    const std::vector<double>& row = csv.rows[k];
    const double va = 0.5 + std::sin(2 * M_PI * 100 * row[0]);
    EXPECT_NEAR(row[1], va, 1e-9) << row[0];
    // At t = 0 the diode's state comes from the operating point's tiny-step LCP (at 1e-8 TSTEP
    // = 5 ps, where v(a) is higher by its slope times 5 ps, 3.1e-9 V): a solver detail.
    EXPECT_NEAR(row[2], std::max(0.0, va), k == 0 ? 2 * M_PI * 100 * 5e-12 * 1.01 : 1e-9) << row[0];
    EXPECT_EQ(row[3], 0.0);
  }
}

// LTspice's Rser on a source and an inductor (instance_parasitics.h): 1 V through 5 + 5 ohm into
// 10 mH from rest, i(l1) = 0.1 (1 - exp(-t / 1 ms)) and v(in) = 1 - 5 i; the internal nodes and
// the parasitic resistors are not default probes.
TEST(DialectCli, SeriesParasiticsOfASourceAndAnInductor) {
  const fs::path dir = scratch_dir("dialect_rser");
  std::ofstream(dir / "rl.cir") << "rl, LTspice style\nV1 in 0 1 Rser=5\nL1 in 0 10m Rser=5\n.tran 10u 3m UIC\n.end\n";
  Result r = run_lcspice("run '" + (dir / "rl.cir").string() + "' -o '" + (dir / "o.csv").string() + "'", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  Csv csv = parse_csv(read_file(dir / "o.csv"));
  ASSERT_EQ(csv.header, (std::vector<std::string>{"time", "v(in)", "i(v1)", "i(l1)"}));
  ASSERT_GE(csv.rows.size(), 301u);
  for (const std::vector<double>& row : csv.rows) {
    const double i = 0.1 * (1 - std::exp(-row[0] / 1e-3));
    EXPECT_NEAR(row[3], i, 1e-9) << row[0];
    EXPECT_NEAR(row[2], -i, 1e-9) << row[0];
    EXPECT_NEAR(row[1], 1 - 5 * i, 1e-8) << row[0];
  }
}

// A buck converter written for LTspice (Rser on the supply, the inductor and the capacitor, a
// Vfwd/Ron diode): the parasitics are R cards in ngspice's deck, and the two agree.
TEST(DialectCli, LtspiceBuckWithParasiticsAgreesWithNgspice) {
  const fs::path dir = scratch_dir("dialect_buck");
  std::ofstream(dir / "buck.cir") << "buck, LTspice style\nV1 in 0 12 Rser=0.1\nS1 in sw ctl 0 SW1\n"
                                     "V2 ctl 0 PULSE(0 5 0 10n 10n 4u 10u)\nD1 0 sw DI\nL1 sw out 100u Rser=0.05\n"
                                     "C1 out 0 47u Rser=10m\nR1 out 0 5\n.model DI D(Ron=0.01 Vfwd=0.4)\n"
                                     ".model SW1 SW(Ron=0.01 Roff=1meg Vt=2.5 Vh=0)\n.tran 50n 200u\n.end\n";
  Result r = run_lcspice("validate '" + (dir / "buck.cir").string() + "'", dir);
  EXPECT_EQ(r.code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("PASS: every probe within"), std::string::npos) << r.out;
}

TEST(DialectCli, DcOnlyDeckIsRefusedForHavingNoTransientAnalysis) {
  const std::string deck = kRealWorld + "/examples/xspice/various/simple-diode.cir";
  if (!std::ifstream(deck)) GTEST_SKIP() << "real-world decks not found in " << kRealWorld;
  const fs::path dir = scratch_dir("dialect_dc_only");
  Result r = run_lcspice("run '" + deck + "' -o '" + (dir / "o.csv").string() + "'", dir);
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_EQ(r.err_line(0), deck + ":19:1: error: the deck has no transient analysis (no '.tran' card and no 'tran' "
                                  "command in '.control'; lcspice runs transient analyses only): the '.control' block "
                                  "runs 'dc'") << r.err;
  EXPECT_FALSE(fs::exists(dir / "o.csv"));
}

// Xyce's `.PRINT TRAN V(*)` with named probes on another .print (or on the same card): every
// voltage and current, then the named probes the defaults lack. Before, the second card narrowed
// the output to its probes (and on one card the named ones beyond the defaults were dropped).
TEST(DialectCli, WildcardPrintKeepsTheNamedProbesOfEveryCard) {
  const fs::path dir = scratch_dir("dialect_wildcard_print");
  for (const char* cards : {".PRINT TRAN FORMAT=CSV V(*)\n.print tran i(r1) v(a,b) v(b)\n",
                            ".print tran i(r1) v(a,b) v(b) V(*)\n"}) {
    SCOPED_TRACE(cards);
    const fs::path deck = write_deck(dir, "x.cir",
                                     std::string("x\nV1 a 0 SIN(0 1 1k)\nR1 a b 1k\nD1 b 0 dm\n"
                                                 ".model dm D(VON=0.7 RON=1)\n.tran 10u 1m\n") + cards + ".end\n");
    Result r = run_lcspice("run '" + deck.string() + "' -o '" + (dir / "o.csv").string() + "'", dir);
    ASSERT_EQ(r.code, 0) << r.err;
    const Csv csv = parse_csv(read_file(dir / "o.csv"));
    EXPECT_EQ(csv.header, (std::vector<std::string>{"time", "v(a)", "v(b)", "i(v1)", "i(d1)", "i(r1)", "v(a,b)"}));
    ASSERT_FALSE(csv.rows.empty());
    // i(r1) = v(a,b) / 1k on every row.
    for (const std::vector<double>& row : csv.rows) EXPECT_NEAR(row[5], row[6] / 1e3, 1e-12);
  }
}

// LTspice's `K1 LP LS1 LS2 k` is the three pairwise couplings: a centre-tapped full-wave
// rectifier written with one K card gives the rows of the deck written with three, to the last bit.
TEST(DialectCli, OneCouplingCardOfThreeWindingsIsThreeCards) {
  const std::string head = "centre-tapped rectifier\nV1 1 0 SIN(0 170 60)\nRP 1 2 0.1\nLP 2 0 100m\nLS1 3 4 25m\n"
                           "LS2 4 5 25m\nD1 3 6 dm\nD2 5 6 dm\nRL 6 4 100\nCL 6 4 470u\nRG 4 0 1meg\n"
                           ".model dm D(VON=0.7 RON=0.05)\n.tran 0.1m 40m\n.probe v(6,4) i(d1) i(d2) i(lp)\n";
  const fs::path one = write_deck("dialect_k3_", "one", head + "K1 LP LS1 LS2 0.999\n.end\n");
  const fs::path three =
      write_deck("dialect_k3_", "three", head + "K1 LP LS1 0.999\nK2 LP LS2 0.999\nK3 LS1 LS2 0.999\n.end\n");
  for (const char* method : {"", "euler"}) {
    const Csv a = run_csv(one, method), b = run_csv(three, method);
    ASSERT_EQ(a.raw, b.raw) << method;
    // Both halves conduct in turn: the full wave's two diodes each carry current.
    double peak1 = 0, peak2 = 0;
    for (const std::vector<double>& row : a.rows) peak1 = std::max(peak1, row[2]), peak2 = std::max(peak2, row[3]);
    EXPECT_GT(peak1, 0.1) << method;
    EXPECT_GT(peak2, 0.1) << method;
  }
}

}  // namespace
}  // namespace lcs::cli_testing
