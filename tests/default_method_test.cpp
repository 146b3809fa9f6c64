// SPEC §1: `run` without a method uses `event` wherever it applies, and a fixed step resolves the
// sources it samples (issue 13: `.tran 1m 1.5` with a 1 kHz source stepped at h = TSTEP sampled
// the source at its zero crossings and reported 0 V for the whole run).
#include <algorithm>
#include <cmath>
#include <fstream>

#include <gtest/gtest.h>

#include "tests/cli_support.h"

namespace lcs {
namespace {

using namespace cli_testing;

// A peak detector at 1 kHz printed once per source period: the aliasing deck.
constexpr const char* kAliasingDeck =
    "peak detector printed once per period\n"
    "V1 a 0 SIN(0 10 1k)\n"
    "D1 a b dx\n"
    "C1 b 0 10u\n"
    "R1 b 0 10k\n"
    ".model dx D(VON=0.7 RON=0)\n"
    ".tran 1m 0.3\n"
    ".end\n";

fs::path write_deck(const fs::path& dir, const std::string& name, const std::string& text) {
  const fs::path p = dir / name;
  std::ofstream(p) << text;
  return p;
}

std::pair<double, double> range_after(const Csv& csv, const std::string& probe, double t0) {
  const int c = csv.column(probe);
  EXPECT_GE(c, 0);
  double lo = INFINITY, hi = -INFINITY;
  for (const std::vector<double>& row : csv.rows)
    if (row[0] >= t0) {
      lo = std::min(lo, row[c]);
      hi = std::max(hi, row[c]);
    }
  return {lo, hi};
}

// The ideal diode (RON = 0) holds v(b) = v(a) - 0.7 while it conducts. It turns off just past
// the crest, where its current C v'(a) + v(b)/R reaches 0: 10 w R C cos(th) + 10 sin(th) - 0.7 = 0,
// and the event method puts a row there, the envelope's top. Between peaks the capacitor
// discharges through R for less than a period: v(b) > 9.3 exp(-1 ms / (R C)) = 9.3 exp(-0.01).
TEST(DefaultMethod, TheAliasingDeckGivesTheEnvelopeByDefault) {
  const fs::path dir = scratch_dir("default_aliasing");
  const fs::path deck = write_deck(dir, "alias.cir", kAliasingDeck);
  Result r = run_lcspice("run '" + deck.string() + "' --stats -o '" + (dir / "out.csv").string() + "'", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.err_line(0).rfind("method event: ", 0), 0u) << r.err;
  const Csv csv = parse_csv(read_file(dir / "out.csv"));
  const auto [lo, hi] = range_after(csv, "v(b)", 1e-3);
  const double wrc = 2 * M_PI * 1e3 * 10e3 * 10e-6;
  double th = M_PI / 2;
  for (int k = 0; k < 20; ++k)
    th -= (10 * wrc * std::cos(th) + 10 * std::sin(th) - 0.7) / (-10 * wrc * std::sin(th) + 10 * std::cos(th));
  EXPECT_NEAR(hi, 10 * std::sin(th) - 0.7, 1e-9);
  EXPECT_LT(hi, 9.3 - 1e-5);  // 11 uV below the crest's 9.3 V
  EXPECT_GT(lo, 9.3 * std::exp(-0.01) - 1e-9);
  // Rows at every TSTEP multiple (and at the events between them).
  EXPECT_GE(csv.rows.size(), 301u);
}

// Implicit Euler asked for by name, with the step left to TSTEP: 50 steps per source period,
// rows still once per TSTEP, and a note that says so.
TEST(DefaultMethod, FixedStepSubdividesATstepThatAliasesTheSource) {
  const fs::path dir = scratch_dir("euler_subdivides");
  const fs::path deck = write_deck(dir, "alias.cir", kAliasingDeck);
  Result r = run_lcspice("run '" + deck.string() + "' --method euler --stats -o '" + (dir / "out.csv").string() + "'",
                         dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.err_line(0),
            "lcspice: note: euler steps at 2e-05 s (50 per TSTEP 0.001 s, to resolve source v1's period 0.001 s); "
            "rows every TSTEP");
  EXPECT_EQ(r.err_line(1).rfind("method euler: 15000 steps, 301 rows", 0), 0u) << r.err;
  const Csv csv = parse_csv(read_file(dir / "out.csv"));
  ASSERT_EQ(csv.rows.size(), 301u);
  EXPECT_NEAR(csv.rows[200][0], 0.2, 1e-15);
  // At 20 us steps the sine's crest is sampled within 1 - cos(pi/50) = 0.2 % of 10 V.
  const auto [lo, hi] = range_after(csv, "v(b)", 1e-3);
  EXPECT_GT(lo, 9.1);
  EXPECT_LT(hi, 9.3 + 1e-9);
}

// A step the user gives is kept, with a warning naming the source it cannot resolve.
TEST(DefaultMethod, AnExplicitCoarseStepIsKeptWithAWarning) {
  const fs::path dir = scratch_dir("euler_explicit_step");
  const fs::path deck = write_deck(dir, "alias.cir", kAliasingDeck);
  Result r = run_lcspice("run '" + deck.string() + "' --method euler --step 1m -o '" + (dir / "out.csv").string() + "'",
                         dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.err_line(0),
            "lcspice: warning: --step 0.001 s is longer than 2e-05 s (source v1's period 0.001 s): euler samples "
            "that source too coarsely to resolve it");
}

// Resolving a 1 ns edge written on the card over a 1 s run would take 1e9 steps: refused, at the
// .tran card, with the remedies and a note at the source.
TEST(DefaultMethod, AFixedStepThatCannotResolveASourceIsRefused) {
  const fs::path dir = scratch_dir("euler_refused");
  const fs::path deck = write_deck(dir, "edge.cir",
                                   "edge\nV1 a 0 PULSE(0 1 0 1n 1n 0.5 1)\nR1 a b 1k\nD1 b 0 dx\n"
                                   ".model dx D(VON=0.7)\n.tran 1u 1\n.end\n");
  Result r = run_lcspice("run '" + deck.string() + "' --method euler -o '" + (dir / "out.csv").string() + "'", dir);
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_EQ(r.err_line(0), deck.string() +
                               ":6:1: error: TSTEP 1e-06 s cannot resolve source v1's rise time 1e-09 s: euler would "
                               "need steps of 1e-09 s, more than 10000000 steps; use --method event (exact between "
                               "events) or give --step");
  // and a note at the source's card, which the remedy may be to change.
  EXPECT_NE(r.err.find(deck.string() + ":2:1: note: source v1's rise time 1e-09 s is written here\n"
                                       "V1 a 0 PULSE(0 1 0 1n 1n 0.5 1)\n^~\n"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(dir / "out.csv"));
}

// A 1 GHz sine over 1000 s: the event method steps at most 0.5/omega (1.7e13 steps), implicit
// Euler 50 a period (5e13). Neither hangs: the event method stops after its first 2^20 steps with
// the projection (exit 3, with the default too: the fallback would need as many), and euler
// refuses at the .tran card without pointing at event.
TEST(DefaultMethod, ARunOfTrillionsOfStepsStopsWithTheProjectionInsteadOfHanging) {
  const fs::path dir = scratch_dir("trillions");
  const fs::path deck = write_deck(dir, "ghz.cir", "ghz\nV1 a 0 SIN(0 1 1g)\nR1 a b 1k\nC1 b 0 1n\n.tran 1 1000\n.end\n");
  for (const char* method : {"", " --method event"}) {
    SCOPED_TRACE(method);
    Result r = run_lcspice("run '" + deck.string() + "'" + method + " -o '" + (dir / "out.csv").string() + "'", dir);
    EXPECT_EQ(r.code, 3) << r.err;
    EXPECT_NE(r.err.find("the event method would take about 1.7e+13 more steps to TSTOP 1000 s at the pace of its "
                         "last 1048576 (now 5.82e-11 s each"),
              std::string::npos)
        << r.err;
  }
  Result r = run_lcspice("run '" + deck.string() + "' --method euler -o '" + (dir / "out.csv").string() + "'", dir);
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_EQ(r.err_line(0), deck.string() +
                               ":5:1: error: TSTEP 1 s cannot resolve source v1's period 1e-09 s: euler would need "
                               "steps of 2e-11 s, more than 10000000 steps; shorten the .tran or give --step");
  // The projection is at the recent pace and the bound generous: a 1 MHz burst of 100000 cycles
  // (LTspice's NCYCLES) in a 100 s run projects 1.6e9 steps at its end, and then the run needs
  // few (1.3e6 in all). And euler's refusal points at event where the finest feature is an edge,
  // which event takes exactly.
  const fs::path burst = write_deck(dir, "burst.cir",
                                    "burst\nV1 in 0 SIN(0 1 1meg 0 0 0 100000)\nR1 in out 1k\nC1 out 0 1n\n"
                                    ".tran 10m 100\n.end\n");
  r = run_lcspice("run '" + burst.string() + "' --stats -o '" + (dir / "burst.csv").string() + "'", dir);
  EXPECT_EQ(r.code, 0) << r.err;
  const fs::path edge = write_deck(dir, "edge.cir",
                                   "edge\nV1 in 0 PULSE(0 1 1 1n 1n 1 1000)\nR1 in out 1k\nC1 out 0 1m\n"
                                   ".tran 10m 100\n.end\n");
  r = run_lcspice("run '" + edge.string() + "' --method euler -o '" + (dir / "edge.csv").string() + "'", dir);
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err_line(0).find("more than 10000000 steps; use --method event (exact between events) or give --step"),
            std::string::npos)
      << r.err;
  r = run_lcspice("run '" + edge.string() + "' -o '" + (dir / "edge.csv").string() + "'", dir);
  EXPECT_EQ(r.code, 0) << r.err;
}

// A 1 pF peak detector behind a 0.1 ohm diode (RON C = 1e-13 s, against a 1 us step): the event
// method's constraint rows could not resolve the diode current (3e-7 A at most, a 3e-8 V drop on
// 5 V) and it kept the diode on past the peak, reporting -2.9e-7 A and the capacitor at -2.6 V at
// 57 us where it holds 4.5 exp(-32 us / 1 ms) = 4.3588 V. A conducting pair's current negative
// beyond 1e-6 of the run's largest stops it now, and the default run falls back to euler, whose
// first-order error here is below 1e-3 V.
TEST(DefaultMethod, ATurnOffTheEventMethodSteppedOverStopsItInsteadOfAWrongAnswer) {
  const fs::path dir = scratch_dir("stiff_peak");
  const fs::path deck = write_deck(dir, "peak.cir",
                                   "peak detector\nV1 a 0 SIN(0 5 10k)\nD1 a p dd\nC1 p 0 1p\nR1 p 0 1G\n"
                                   ".model dd D(VON=0.5 RON=0.1)\n.tran 1u 60u\n.print tran v(p) i(d1)\n.end\n");
  Result r = run_lcspice("run '" + deck.string() + "' --method event -o '" + (dir / "event.csv").string() + "'", dir);
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_NE(r.err.find("conducts -1.08e-10 where its law needs >= 0"), std::string::npos) << r.err;
  r = run_lcspice("run '" + deck.string() + "' -o '" + (dir / "out.csv").string() + "'", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("a turn-off was stepped over"), std::string::npos) << r.err;
  const Csv csv = parse_csv(read_file(dir / "out.csv"));
  const auto t = column(csv, "time"), v = column(csv, "v(p)"), i = column(csv, "i(d1)");
  EXPECT_NEAR(v[row_at(t, 57e-6)], 4.5 * std::exp(-32e-6 / 1e-3), 1e-3);
  for (double current : i) EXPECT_GE(current, -1e-15);
}

// The same detector with RON = 0.01: the diode stays closed through an event at the peak
// (25.28 us) with -1.1e-9 A, 660 times the bound. When the check left alone every row a mode
// begins with (for a multiplier's diodes that close at a grazing contact), this one passed and
// the default run ended 5.5 mV low with exit 0 (v(p) = 4.21177 V at 190 us). A pair that stays
// closed is judged from zero; only one that has just closed is judged from where it closed.
// Reference: radau5 at 1 ns, 4.217284 V.
TEST(DefaultMethod, ADiodeStayingClosedThroughAnEventIsJudgedFromZero) {
  const fs::path dir = scratch_dir("stiff_peak_ron001");
  const fs::path deck = write_deck(dir, "peak.cir",
                                   "peak detector\nV1 a 0 SIN(0 5 10k)\nD1 a p dd\nC1 p 0 1p\nR1 p 0 1G\n"
                                   ".model dd D(VON=0.5 RON=0.01)\n.tran 1u 200u\n.print tran v(p) i(d1)\n.end\n");
  Result r = run_lcspice("run '" + deck.string() + "' --method event -o '" + (dir / "event.csv").string() + "'", dir);
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_NE(r.err.find("conducts -1.1e-09 where its law needs >= 0"), std::string::npos) << r.err;
  r = run_lcspice("run '" + deck.string() + "' -o '" + (dir / "out.csv").string() + "'", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  const Csv csv = parse_csv(read_file(dir / "out.csv"));
  const auto t = column(csv, "time"), v = column(csv, "v(p)");
  EXPECT_NEAR(v[row_at(t, 190e-6)], 4.217284, 1e-3);
}

// validate steps its fixed-step methods under the same guard as run: its output step is TSTEP/10
// (10 a source period here), so implicit Euler takes 5 steps per row, and says so. ngspice, its
// witness, is held to 50 points a period too: at 10 (TMAX = the output step) its sharp diode lost
// the solution near t = 0.296 s (v(b) swung to -9.8 V, the capacitor discharging backwards
// through the blocking diode) and validate FAILed at 205 % of v(b)'s range; both runs agree now.
TEST(DefaultMethod, ValidateResolvesTheAliasingDecksSourceForBothSimulators) {
  const fs::path dir = scratch_dir("validate_aliasing");
  const fs::path deck = write_deck(dir, "alias.cir", kAliasingDeck);
  Result r = run_lcspice("validate '" + deck.string() + "' --method euler --report '" + (dir / "euler.csv").string() +
                             "'",
                         dir);
  EXPECT_EQ(r.code, 0) << r.out << r.err;
  EXPECT_EQ(r.err_line(0),
            "lcspice: note: euler steps at 2e-05 s (5 per output step 0.0001 s, to resolve source v1's period 0.001 "
            "s); rows every output step");
  EXPECT_NE(r.out.find("lcspice: ideal diodes, euler, h = 0.0001 s, 3001 rows"), std::string::npos) << r.out;
  r = run_lcspice("validate '" + deck.string() + "' --report '" + (dir / "event.csv").string() + "'", dir);
  EXPECT_EQ(r.code, 0) << r.out << r.err;
  // ngspice's own points every 2e-5 s at most (15,000 over 0.3 s), not every 1e-4 s (3014).
  const size_t at = r.out.find("ngspice: ");
  ASSERT_NE(at, std::string::npos) << r.out;
  EXPECT_GE(std::stol(r.out.substr(at + 9)), 15000) << r.out;
  const Csv report = parse_csv(read_file(dir / "event.csv"));
  ASSERT_EQ(report.raw.size(), 4u);
  EXPECT_EQ(report.raw[1][0], "v(b)");
  EXPECT_LT(report.rows[1][3], 0.01);  // max|error| / range of v(b), ngspice against the ideal run
}

// Above 128 pairs the event method's dense exponentials cost too much to be the default: implicit
// Euler runs instead, and says why.
TEST(DefaultMethod, ALargeCircuitFallsBackToImplicitEulerWithANote) {
  const fs::path dir = scratch_dir("default_large");
  std::string text = "130 rectifiers\nV1 a 0 SIN(0 5 1k)\n";
  for (int k = 0; k < 130; ++k) {
    const std::string n = std::to_string(k);
    text += "D" + n + " a o" + n + " dx\nR" + n + " o" + n + " 0 1k\n";
  }
  text += ".model dx D(VON=0.6)\n.tran 10u 1m\n.end\n";
  const fs::path deck = write_deck(dir, "bank.cir", text);
  Result r = run_lcspice("run '" + deck.string() + "' --probe 'v(o7)' -o '" + (dir / "out.csv").string() + "'", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.err_line(0),
            "lcspice: note: method euler: the default method does not apply (130 complementarity pairs, more than "
            "the 128 up to which the event method's dense exponentials stay cheap)");
  const Csv csv = parse_csv(read_file(dir / "out.csv"));
  ASSERT_EQ(csv.rows.size(), 101u);
  // Resistive: v(o7) = max(0, 5 sin(2 pi 1k t) - 0.6) at every row.
  for (const std::vector<double>& row : csv.rows)
    EXPECT_NEAR(row[1], std::max(0.0, 5 * std::sin(2 * M_PI * 1e3 * row[0]) - 0.6), 1e-9) << row[0];
}

// Lines: the event method's exact history costs 5-23 times implicit Euler's run (800 times on a
// deck of stiff transistor junctions, whose segments it reads through the exact product), so a circuit
// with a line takes the fixed-step default, which steps within the line's delay.
TEST(DefaultMethod, ACircuitWithALineTakesTheFixedStepDefault) {
  const fs::path dir = scratch_dir("default_line");
  Result r = run_lcspice("run '" + circuit("tline_pulse_forming").string() + "' --stats -o '" +
                             (dir / "out.csv").string() + "'",
                         dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.err_line(0),
            "lcspice: note: method euler: the default method does not apply (transmission lines: the event "
            "method's exact line history took 5 to 23 times implicit Euler's time on circuits/tline_*.cir, 800 "
            "times on ngspice's ltra4_1_line.sp)");
  EXPECT_EQ(r.err_line(1).rfind("method euler: ", 0), 0u) << r.err;
}

}  // namespace
}  // namespace lcs
