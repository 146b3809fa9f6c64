// `--diode auto` asks the circuit whether its ideal answer depends on the junctions' curves below
// the currents they carry (solver/integrators/fit_sensitivity.h): every fitted line refitted two
// decades lower, the ideal circuit run again, each probe's move against its range (within one
// output interval in time). Above 2 % the whole circuit runs the Shockley junctions (smooth);
// below, the ideal run. Each decision is checked against the Shockley answer itself: the ideal
// run is off by more than 2 % where auto leaves it, and within 2 % where auto keeps it.
#include <algorithm>
#include <cmath>

#include "solver/integrators/fit_sensitivity.h"
#include "tests/cli_support.h"

namespace lcs {
namespace {

using namespace cli_testing;

// The largest distance of b from a's values within dt of b's time, over a's range: how far two
// answers differ where an edge that moves by less than dt is not a difference.
double tube_distance(const Csv& a, const Csv& b, const std::string& probe, double dt) {
  const std::vector<double> ta = column(a, "time"), va = column(a, probe);
  const std::vector<double> tb = column(b, "time"), vb = column(b, probe);
  const double range = *std::max_element(va.begin(), va.end()) - *std::min_element(va.begin(), va.end());
  double worst = 0;
  for (size_t k = 0; k < tb.size(); ++k) {
    double lo = INFINITY, hi = -INFINITY;
    for (size_t j = 0; j < ta.size(); ++j)
      if (std::abs(ta[j] - tb[k]) <= dt * (1 + 1e-9)) lo = std::min(lo, va[j]), hi = std::max(hi, va[j]);
    if (lo <= hi) worst = std::max({worst, vb[k] - hi, lo - vb[k]});
  }
  return worst / range;
}

// The first time v crosses the midpoint of its range going up.
double first_rise(const Csv& csv, const std::string& probe) {
  const std::vector<double> t = column(csv, "time"), v = column(csv, probe);
  const double mid = (*std::max_element(v.begin(), v.end()) + *std::min_element(v.begin(), v.end())) / 2;
  for (size_t k = 1; k < v.size(); ++k)
    if (v[k - 1] < mid && v[k] >= mid) return t[k];
  return NAN;
}

// An emitter-coupled Schmitt trigger (ngspice's tests/general/schmitt.cir without its output
// followers) on a slow ramp. It trips where the pair's loop gain reaches one: the exponential
// junctions' transconductance I / Vt grows with the current, the line's is 1 / RON as soon as it
// conducts, so the ideal trigger trips late (measured: v(c2) rises at 354 ns, the Shockley
// junctions' at 288 ns, ngspice's the same: `validate --method smooth` passes, the ideal FAILs).
const char* const kEclSchmitt =
    "emitter-coupled Schmitt trigger on a slow ramp, transistors with only IS and BF\n"
    "vin in 0 pwl(0 -1.6 400n -1.2 800n -1.6)\n"
    "vee vee 0 -5\n"
    "rc1 0 c1 50\n"
    "r1 c1 b2 185\n"
    "r2 b2 vee 760\n"
    "rc2 0 c2 100\n"
    "re e vee 260\n"
    "q1 c1 in e qstd off\n"
    "q2 c2 b2 e qstd\n"
    ".model qstd npn(is=1e-16 bf=50 br=0.1 cje=0.4p)\n"
    "cl c2 0 5p\n"
    ".tran 2n 800n\n"
    ".print tran v(c2)\n"
    ".end\n";

TEST(DiodeAuto, ASchmittTriggerRunsItsShockleyJunctions) {
  const fs::path deck = write_deck("diode_auto_", "ecl", kEclSchmitt);
  const fs::path dir = deck.parent_path();
  const Result r = run_lcspice("run '" + deck.string() + "' --diode auto -o '" + (dir / "auto.csv").string() + "'", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("lcspice: --diode auto: the ideal answer depends on the junctions' curves: v(c2) moves 100 % "
                       "of its range (at t = 2.7e-07 s; bound 2 %) when the junctions' lines are fitted 2 decades "
                       "below the currents they carry; running --method smooth with Shockley diodes\n"),
            std::string::npos)
      << r.err;
  const Csv autocsv = parse_csv(read_file(dir / "auto.csv"));
  const Csv smooth = run_csv(deck, "smooth");
  EXPECT_EQ(autocsv.raw, smooth.raw);
  // The decision is right: the ideal trigger trips 66 ns late.
  const Csv ideal = run_csv(deck, "");
  EXPECT_NEAR(first_rise(smooth, "v(c2)"), 288e-9, 2e-9);
  EXPECT_NEAR(first_rise(ideal, "v(c2)") - first_rise(smooth, "v(c2)"), 66e-9, 4e-9);
}

// A 10 V half-wave rectifier with a card copied from a library (only IS, N, RS).
const char* const kRectifier =
    "half-wave rectifier, 10 V, 1k load, 100u filter, a card with only IS, N, RS\n"
    "V1 in 0 SIN(0 10 50)\n"
    "D1 in out d1n\n"
    "R1 out 0 1k\n"
    "C1 out 0 100u\n"
    ".model d1n D(IS=2.5e-9 N=1.75 RS=0.04)\n"
    ".tran 0.1m 60m\n"
    ".print tran v(out)\n"
    ".end\n";

// Its output does not care where in the cycle the diode starts to conduct: v(out) moves 1.2 % of
// its range with the line fitted two decades lower, so auto keeps the ideal run, and the ideal
// v(out) is within 0.5 % of the Shockley diode's (one output interval's tube).
TEST(DiodeAuto, ARectifiersOutputKeepsTheIdealRun) {
  const fs::path deck = write_deck("diode_auto_", "rectifier", kRectifier);
  const fs::path dir = deck.parent_path();
  const Result r = run_lcspice(
      "run '" + deck.string() + "' --diode auto --stats -o '" + (dir / "auto.csv").string() + "'", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.err.find("--diode auto:"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("fit sensitivity: v(out) moves 1.2 % of its range (at t = 0.0251 s; bound 2 %) when the "
                       "junctions' lines are fitted 2 decades below the currents they carry, "),
            std::string::npos)
      << r.err;
  const Csv ideal = run_csv(deck, "");
  EXPECT_EQ(parse_csv(read_file(dir / "auto.csv")).raw, ideal.raw);
  const Csv smooth = run_csv(deck, "smooth");
  EXPECT_LT(tube_distance(smooth, ideal, "v(out)", 1e-4), 0.006);
}

// The same rectifier with its diode current printed: the charging pulses' edges depend on the
// curve (i(d1) moves 3.83 % of its range), and the ideal i(d1) is 3.5 % of its range outside the
// Shockley diode's tube, more than the 2 % auto promises: auto runs the Shockley diode.
TEST(DiodeAuto, ARectifiersDiodeCurrentRunsTheShockleyDiode) {
  std::string text = kRectifier;
  text.replace(text.find(".print tran v(out)"), 18, ".print tran v(out) i(d1)");
  const fs::path deck = write_deck("diode_auto_", "rectifier_current", text);
  const fs::path dir = deck.parent_path();
  const Result r = run_lcspice("run '" + deck.string() + "' --diode auto -o '" + (dir / "auto.csv").string() + "'", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("lcspice: --diode auto: the ideal answer depends on the junctions' curves: i(d1) moves 3.83 % "
                       "of its range (at t = 0.0005 s; bound 2 %)"),
            std::string::npos)
      << r.err;
  const Csv smooth = run_csv(deck, "smooth");
  EXPECT_EQ(parse_csv(read_file(dir / "auto.csv")).raw, smooth.raw);
  const double off = tube_distance(smooth, run_csv(deck, ""), "i(d1)", 1e-4);
  EXPECT_NEAR(off, 0.0351, 0.0005);
}

// A relay driver: the BJT switches the coil (100 mH, 200 ohm) off, the flyback diode takes its
// current. Its answer depends on the junctions' curves (v(c) moves 4.8 % at the lowered lines), so
// auto runs the Shockley junctions; but the smooth method stops at the turn-off (with no junction
// capacitance the collector's voltage jumps 12.7 V while IDA's step falls to 1e-19 s). The run
// does not end there: the ideal answer auto passed over is written, with the reason, as the
// default run writes it.
TEST(DiodeAuto, ASmoothRunThatStopsGivesWayToTheIdealAnswer) {
  const fs::path deck = write_deck("diode_auto_", "relay", R"(relay driver
VCC vcc 0 DC 12
VIN in 0 PULSE(0 5 1m 1u 1u 2m 5m)
RB in b 4.7k
Q1 c b 0 QN
LR vcc m 100m
RR m c 200
D1 c vcc DS
.model QN NPN(IS=1e-14 BF=150 BR=2)
.model DS D(IS=1e-14 N=1 RS=0.1)
.tran 1u 10m
.print tran v(c) i(lr)
.end
)");
  const fs::path dir = deck.parent_path();
  const Result r = run_lcspice("run '" + deck.string() + "' --diode auto -o '" + (dir / "auto.csv").string() + "'", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("lcspice: warning: --diode auto: method smooth failed at t = 0.0030014"), std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("; writing the ideal answer (method event, the junctions' fitted lines) instead, passed over "
                       "because the ideal answer depends on the junctions' curves: v(c) moves 4.79 % of its range"),
            std::string::npos)
      << r.err;
  const Csv written = parse_csv(read_file(dir / "auto.csv"));
  EXPECT_EQ(written.raw, run_csv(deck, "").raw);
  // The coil's current half a millisecond after the turn-off: ngspice 39.3 gives 19.19 mA.
  const std::vector<double> t = column(written, "time"), i = column(written, "i(lr)");
  EXPECT_NEAR(i[row_at(t, 3.5e-3)], 19.19e-3, 0.01 * 19.19e-3);
}

// A plain run (the ideal law) makes the same check against its own rows and warns where the
// answer is the lines' guess, naming the probe and the remedy; where it is not, it says nothing.
TEST(DiodeAuto, ThePlainRunWarnsWhereTheLinesDoNotServe) {
  const fs::path ecl = write_deck("diode_auto_plain_", "ecl", kEclSchmitt);
  const Result r = run_lcspice("run '" + ecl.string() + "' -o '" + (ecl.parent_path() / "out.csv").string() + "'",
                               ecl.parent_path());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("lcspice: warning: the ideal answer depends on the junctions' curves below the currents they "
                       "carry (v(c2) moves 100 % of its range (at t = 2.7e-07 s; bound 2 %) when the junctions' "
                       "lines are fitted 2 decades below the currents they carry): use --diode auto (the Shockley "
                       "junctions where it does), --diode shockley, or give VON/RON on the cards\n"),
            std::string::npos)
      << r.err;
  // The rows are the ideal run's, whatever the check (it runs beside them).
  EXPECT_EQ(parse_csv(read_file(ecl.parent_path() / "out.csv")).raw, run_csv(ecl, "", "--diode ideal").raw);
  const fs::path rect = write_deck("diode_auto_plain_", "rectifier", kRectifier);
  const Result q = run_lcspice("run '" + rect.string() + "' -o '" + (rect.parent_path() / "out.csv").string() + "'",
                               rect.parent_path());
  ASSERT_EQ(q.code, 0) << q.err;
  EXPECT_EQ(q.err.find("warning"), std::string::npos) << q.err;
}

// `analyze` says which it is, with the measurement, and warns where the lines do not serve. Its
// transient is run's (the default method, event, with run's fallback): the same numbers as
// `run --stats` (before, it stepped euler at TSTEP: 2.84e-07 s and 1.17 % here, run's 2.7e-07 s
// and 1.2 %, and on a bridge whose refit run completed it reported fits run never used).
TEST(DiodeAuto, AnalyzeReportsWhetherTheLinesServeTheCircuit) {
  const fs::path ecl = write_deck("diode_auto_analyze_", "ecl", kEclSchmitt);
  const Result a = run_lcspice("analyze '" + ecl.string() + "'", ecl.parent_path());
  ASSERT_EQ(a.code, 0) << a.err;
  EXPECT_NE(a.out.find("  the lines do not serve this circuit: v(c2) moves 100 % of its range (at t = 2.7e-07 s; "
                       "bound 2 %) when the junctions' lines are fitted 2 decades below the currents they carry\n"),
            std::string::npos)
      << a.out;
  EXPECT_NE(a.out.find("the ideal answer depends on the junctions' curves below the currents they carry (v(c2) moves "
                       "100 % of its range"),
            std::string::npos)
      << a.out;
  const Result j = run_lcspice("analyze --json '" + ecl.string() + "'", ecl.parent_path());
  EXPECT_NE(j.out.find("\"fit_sensitivity\": {\"probe\": \"v(c2)\", \"moved\": 0.9999"), std::string::npos) << j.out;
  EXPECT_NE(j.out.find("\"lines_serve\": false}"), std::string::npos) << j.out;
  const fs::path rect = write_deck("diode_auto_analyze_", "rectifier", kRectifier);
  const Result b = run_lcspice("analyze '" + rect.string() + "'", rect.parent_path());
  EXPECT_NE(b.out.find("  the lines serve this circuit: v(out) moves 1.2 % of its range"), std::string::npos) << b.out;
  EXPECT_EQ(b.out.find("depends on the junctions' curves"), std::string::npos) << b.out;
}

TEST(DiodeAuto, LoweredRangesMoveOnlyTheLowEndOfRangesCarried) {
  std::map<std::string, DiodeCurrentRanges> fitted;
  fitted["d1"].forward = {2e-3, 5e-2};
  fitted["q1:be"].reverse = {1e-6, 1e-3};
  fitted["d2"] = {};  // carried nothing: stays empty
  const auto low = lowered_ranges(fitted, 2);
  EXPECT_DOUBLE_EQ(low.at("d1").forward.lo, 2e-5);
  EXPECT_DOUBLE_EQ(low.at("d1").forward.hi, 5e-2);
  EXPECT_TRUE(low.at("d1").reverse.empty());
  EXPECT_DOUBLE_EQ(low.at("q1:be").reverse.lo, 1e-8);
  EXPECT_TRUE(low.at("d2").forward.empty());
  // Conducting throughout (always_on): only down to the least current carried.
  fitted["z1"].reverse = {20e-3, 45e-3, true, 16e-3};
  EXPECT_DOUBLE_EQ(lowered_ranges(fitted, 2).at("z1").reverse.lo, 16e-3);
}

// A Zener shunt regulator (breakdown 16-45 mA throughout, a 10 -> 40 mA load step): its line
// never passes through a turn-on, and its output (6.51 / 6.33 V, a 0.18 V range) is within 3 mV
// of the Shockley diode's. With the breakdown line lowered two decades (0.16-45 mA) v(out) moved
// 27 % of its range and the plain run warned that the answer depended on the curve below the
// currents carried; it is lowered only to the least current carried now, and no warning comes.
TEST(DiodeAuto, AZenerConductingThroughoutIsNotJudgedByATurnOnItNeverMakes) {
  const fs::path deck = write_deck("diode_auto_", "zener",
                                   "Zener shunt regulator with a load step\nVin in 0 DC 12\nRs in out 100\n"
                                   "DZ1 0 out ZEN62\n.model ZEN62 D(IS=1n N=1.5 RS=5 BV=6.2 IBV=5m)\n"
                                   "Cout out 0 1u\n"
                                   "Iload out 0 PWL(0 10m 1m 10m 1.001m 40m 2m 40m 2.001m 10m 3m 10m)\n"
                                   ".tran 5u 3m\n.print tran v(out)\n.end\n");
  const fs::path dir = deck.parent_path();
  const Result r = run_lcspice("run '" + deck.string() + "' --stats -o '" + (dir / "out.csv").string() + "'", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.err.find("depends on the junctions' curves"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("fit sensitivity: no probe moves (bound 2 %)"), std::string::npos) << r.err;
  const Csv ideal = parse_csv(read_file(dir / "out.csv"));
  const Csv smooth = run_csv(deck, "smooth", "--diode shockley");
  const auto ti = column(ideal, "time"), vi = column(ideal, "v(out)");
  const auto ts = column(smooth, "time"), vs = column(smooth, "v(out)");
  for (double t : {0.9e-3, 1.9e-3, 2.9e-3}) EXPECT_NEAR(vi[row_at(ti, t)], vs[row_at(ts, t)], 3e-3) << t;
  EXPECT_NEAR(vs[row_at(ts, 1.9e-3)], 6.330, 0.002);
}

}  // namespace
}  // namespace lcs
