// `lcspice bench` on a reduced setting (--quick: two settings per method, one ngspice run): the
// table it writes must hold the accuracy facts the methods are known for, so a wrong reference,
// a mismatched comparison grid or a broken method shows up here.
#include <algorithm>
#include <cmath>
#include <map>

#include <gtest/gtest.h>

#include "tests/cli_support.h"

namespace lcs::cli_testing {
namespace {

struct BenchRow {
  std::string method, setting, reference, failure;
  double error = NAN, error_vs_ideal = NAN, cpu = NAN;
  long steps = 0, events = 0;
};

std::vector<BenchRow> read_bench(const fs::path& csv) {
  const Csv table = parse_csv(read_file(csv));
  std::vector<BenchRow> rows;
  auto col = [&](const char* name) {
    const int c = table.column(name);
    EXPECT_GE(c, 0) << name;
    return c;
  };
  const int method = col("method"), setting = col("setting"), ref = col("reference"), err = col("max_rel_error"),
            vs = col("max_rel_error_vs_ideal"), cpu = col("cpu_seconds"), steps = col("steps"),
            events = col("events"), failure = col("failure");
  for (const auto& raw : table.raw) {
    BenchRow r;
    r.method = raw[method];
    r.setting = raw[setting];
    r.reference = raw[ref];
    r.failure = raw[failure];
    auto number = [](const std::string& s) { return s.empty() ? NAN : std::stod(s); };
    r.error = number(raw[err]);
    r.error_vs_ideal = number(raw[vs]);
    r.cpu = number(raw[cpu]);
    r.steps = raw[steps].empty() ? 0 : std::stol(raw[steps]);
    r.events = raw[events].empty() ? 0 : std::stol(raw[events]);
    rows.push_back(r);
  }
  return rows;
}

const BenchRow* find(const std::vector<BenchRow>& rows, const std::string& method, const std::string& setting) {
  for (const BenchRow& r : rows)
    if (r.method == method && r.setting == setting) return &r;
  return nullptr;
}

TEST(Bench, QuickRunOnTheLcTankHoldsTheKnownAccuracies) {
  const fs::path dir = scratch_dir("bench_tank");
  const Result r = run_lcspice("bench --quick '" + source_path("circuits/lc_tank_bridge.cir").string() + "' -o '" + (dir / "out").string() + "'", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  const std::vector<BenchRow> rows = read_bench(dir / "out" / "bench.csv");

  // The reference (event, rtol 1e-13) agrees with its own tightening to rounding.
  const BenchRow* check = find(rows, "reference-check", "event rtol=1e-13 vs 1e-14 at TSTEP/2");
  ASSERT_NE(check, nullptr);
  EXPECT_LT(check->error, 1e-12);

  // Every method ran at both quick settings, none failed.
  for (const char* m : {"euler", "theta", "radau3", "radau5", "event"}) {
    int n = 0;
    for (const BenchRow& row : rows)
      if (row.method == m) {
        ++n;
        EXPECT_TRUE(row.failure.empty()) << m << " " << row.setting << ": " << row.failure;
        EXPECT_GT(row.cpu, 0) << m;
      }
    EXPECT_EQ(n, 2) << m;
  }
  // event: exact between switchings, 16 zero crossings in 5 ms.
  for (const char* s : {"rtol=0.0001", "rtol=1e-12"}) {
    const BenchRow* e = find(rows, "event", s);
    ASSERT_NE(e, nullptr) << s;
    EXPECT_LT(e->error, 1e-9) << s;
    EXPECT_EQ(e->events, 16) << s;
  }
  // Implicit Euler is first order: a step 4x smaller gives an error ~4x smaller (3.7 measured;
  // the ratio of its damping errors 1 - exp(-w^2 h t/2) at t = 5 ms).
  const BenchRow* e2 = find(rows, "euler", "h=2e-06");
  const BenchRow* e05 = find(rows, "euler", "h=5e-07");
  ASSERT_TRUE(e2 && e05);
  EXPECT_NEAR(e2->error / e05->error, 3.7, 0.3);
  EXPECT_GT(e2->error, 1e-2);
  // theta 0.5 is second order (ratio ~16), radau5 fifth order down to the reference's floor.
  const BenchRow* t2 = find(rows, "theta", "h=2e-06");
  const BenchRow* t05 = find(rows, "theta", "h=5e-07");
  ASSERT_TRUE(t2 && t05);
  EXPECT_NEAR(t2->error / t05->error, 16, 1.5);
  const BenchRow* r5 = find(rows, "radau5", "h=2e-06");
  ASSERT_NE(r5, nullptr);
  EXPECT_LT(r5->error, 1e-9);
  EXPECT_GT(e2->error / r5->error, 1e6);

  // ngspice ran once, in-process, and is compared at its own points.
  const BenchRow* ng = find(rows, "ngspice", "reltol=0.001");
  ASSERT_NE(ng, nullptr);
  EXPECT_TRUE(ng->failure.empty()) << ng->failure;
  EXPECT_GT(ng->steps, 100);
  // Against the ideal reference it cannot beat the model gap: 2 junctions x 36 mV on 20 V range.
  EXPECT_GT(ng->error_vs_ideal, 1e-3);
  EXPECT_LT(ng->error_vs_ideal, 2e-2);

  // The chart is a PNG.
  const std::string png = read_file(dir / "out" / "lc_tank_bridge.png");
  ASSERT_GT(png.size(), 8u);
  EXPECT_EQ(png.substr(1, 3), "PNG");
  EXPECT_NE(r.out.find("headline: event reaches 1e-6"), std::string::npos) << r.out;
  // Progress goes to a terminal only: with standard error in a file there is none.
  EXPECT_EQ(r.err, "") << r.err;
}

// A switch deck (issue 13): the event method is the reference there (it locates the switch
// change); a smooth method that did not apply would be left out instead of failing the study. The RC
// charged through a switch on a ramp: the reference agrees with its tightening to 2.4e-13 of the
// range (measured), event at rtol 1e-12 with it to rounding, and implicit Euler is first order
// (4x the step, 4x the error: 4.0236e-4 / 1.0068e-4 measured).
TEST(Bench, SwitchDeckWithTheEventReference) {
  const fs::path dir = scratch_dir("bench_switch");
  std::ofstream(dir / "ramped_rc.cir") << "RC charged through a switch\nVDD dd 0 DC 5\nVC c 0 PWL(0 0 1m 0.9)\n"
                                          "S1 dd out c 0 sw1\nC1 out 0 1u\n"
                                          ".model sw1 SW(VT=0.4 VH=0.1 RON=1k ROFF=1e12)\n.tran 1u 3m UIC\n.end\n";
  const Result r = run_lcspice("bench --quick --no-ngspice '" + (dir / "ramped_rc.cir").string() + "' -o '" +
                                   (dir / "out").string() + "'",
                               dir);
  ASSERT_EQ(r.code, 0) << r.err;
  const std::vector<BenchRow> rows = read_bench(dir / "out" / "bench.csv");
  const BenchRow* check = find(rows, "reference-check", "event rtol=1e-13 vs 1e-14 at TSTEP/2");
  ASSERT_NE(check, nullptr);
  EXPECT_LT(check->error, 1e-12);
  for (const BenchRow& row : rows)
    EXPECT_TRUE(row.failure.empty()) << row.method << " " << row.setting << ": " << row.failure;
  // smooth (switches as IDA's roots; no diodes, so the smooth circuit is the ideal one) against
  // the event reference: within its rtol (1.75e-5 and 7.3e-8 of the range measured at 1e-4 and
  // 1e-7).
  const BenchRow* sm = find(rows, "smooth", "rtol=1e-07");
  ASSERT_NE(sm, nullptr);
  EXPECT_LT(sm->error_vs_ideal, 1e-6);
  const BenchRow* ev = find(rows, "event", "rtol=1e-12");
  ASSERT_NE(ev, nullptr);
  EXPECT_LT(ev->error, 1e-14);
  EXPECT_EQ(ev->events, 1);
  const BenchRow* e2 = find(rows, "euler", "h=2e-06");
  const BenchRow* e05 = find(rows, "euler", "h=5e-07");
  ASSERT_TRUE(e2 && e05);
  EXPECT_NEAR(e2->error / e05->error, 4.0, 0.1);
}

// --no-smooth-reference (for circuits where the smooth reference's rtol 1e-10 run outlasts the
// study: 310 s on a 50-stage multiplier): no smooth reference and no smooth method; ngspice is
// judged against the event reference, so its error is its error against the ideal circuit.
TEST(Bench, WithoutTheSmoothReferenceNgspiceIsJudgedAgainstTheEventOne) {
  const fs::path dir = scratch_dir("bench_no_smooth_ref");
  const Result r = run_lcspice("bench --quick --no-smooth-reference --methods euler,smooth '" +
                                   source_path("circuits/lc_tank_bridge.cir").string() + "' -o '" +
                                   (dir / "out").string() + "'",
                               dir);
  ASSERT_EQ(r.code, 0) << r.err;
  const std::vector<BenchRow> rows = read_bench(dir / "out" / "bench.csv");
  for (const BenchRow& row : rows) {
    EXPECT_NE(row.method, "smooth") << row.setting;
    EXPECT_EQ(row.setting.find("smooth"), std::string::npos) << row.method << " " << row.setting;
  }
  EXPECT_NE(find(rows, "euler", "h=2e-06"), nullptr);
  const BenchRow* ng = find(rows, "ngspice", "reltol=0.001");
  ASSERT_NE(ng, nullptr);
  EXPECT_EQ(ng->reference, "ideal");
  EXPECT_EQ(ng->error, ng->error_vs_ideal);
  EXPECT_GT(ng->error, 1e-3);  // the model gap, as in the quick run above
  const Result scale = run_lcspice("bench --scale cw --no-smooth-reference -o '" + (dir / "s").string() + "'", dir);
  EXPECT_EQ(scale.code, 1);
  EXPECT_EQ(scale.err_line(0), "error: --no-smooth-reference belongs to the work-precision study");
}

// --reference euler (for circuits whose event reference takes too long: a 1000-diode multiplier
// or ladder): implicit Euler at TSTEP/64, checked at TSTEP/128. Being first order, its own error
// is about twice its check (3.33e-4 of the tank's range measured): theta at h = 5e-7 (1.8e-5
// from the event reference) reads 6.68e-4 against it; euler's and ngspice's errors (ngspice at
// its own times, the reference read linearly between its rows) move by less than that from
// their errors against the event reference.
TEST(Bench, ImplicitEulerReferenceIsWithinItsOwnErrorOfTheEventOne) {
  const fs::path dir = scratch_dir("bench_euler_ref");
  const std::string deck = "'" + source_path("circuits/lc_tank_bridge.cir").string() + "'";
  const Result a = run_lcspice("bench --quick --methods euler,theta " + deck + " -o '" + (dir / "event").string() + "'", dir);
  ASSERT_EQ(a.code, 0) << a.err;
  const Result b = run_lcspice("bench --quick --methods euler,theta --reference euler " + deck + " -o '" +
                                   (dir / "euler").string() + "'",
                               dir);
  ASSERT_EQ(b.code, 0) << b.err;
  const std::vector<BenchRow> by_event = read_bench(dir / "event" / "bench.csv");
  const std::vector<BenchRow> by_euler = read_bench(dir / "euler" / "bench.csv");
  EXPECT_EQ(find(by_euler, "reference-check", "event rtol=1e-13 vs 1e-14 at TSTEP/2"), nullptr);
  const BenchRow* check = find(by_euler, "reference-check", "euler h=TSTEP/64 vs TSTEP/128");
  ASSERT_NE(check, nullptr);
  EXPECT_GT(check->error, 1e-4);
  EXPECT_LT(check->error, 1e-3);
  const double own_error = 2 * check->error;
  const BenchRow* theta = find(by_euler, "theta", "h=5e-07");
  const BenchRow* theta_exact = find(by_event, "theta", "h=5e-07");
  ASSERT_TRUE(theta && theta_exact);
  EXPECT_LT(theta_exact->error, 0.05 * own_error);
  EXPECT_NEAR(theta->error, own_error, 0.1 * own_error);
  for (const char* setting : {"h=2e-06", "h=5e-07"}) {
    const BenchRow* e = find(by_euler, "euler", setting);
    const BenchRow* e_exact = find(by_event, "euler", setting);
    ASSERT_TRUE(e && e_exact) << setting;
    EXPECT_NEAR(e->error, e_exact->error, 1.1 * own_error) << setting;
  }
  const BenchRow* ng = find(by_euler, "ngspice", "reltol=0.001");
  const BenchRow* ng_exact = find(by_event, "ngspice", "reltol=0.001");
  ASSERT_TRUE(ng && ng_exact);
  EXPECT_GT(ng->steps, 100);
  EXPECT_NEAR(ng->error_vs_ideal, ng_exact->error_vs_ideal, 1.1 * own_error);
  EXPECT_EQ(ng->error, ng_exact->error);  // against the smooth reference, as before

  const Result bad = run_lcspice("bench --quick --reference lemke " + deck + " -o '" + (dir / "x").string() + "'", dir);
  EXPECT_EQ(bad.code, 1);
  EXPECT_EQ(bad.err_line(0), "error: --reference: 'lemke' (known: event, euler)");
  // Its rows cannot land on a source's corner: refused where there is one (a 10 ns PULSE edge
  // read ngspice's error as 0.39 where the event reference reads 0.04).
  std::ofstream(dir / "pulse.cir") << "pulse rc\nV1 a 0 PULSE(0 1 1.3u 10n 10n 2u 5u)\nR1 a b 1k\nC1 b 0 1n\n"
                                      "D1 b 0 dm\n.model dm D(VON=0.7 RON=1)\n.tran 1u 20u\n.end\n";
  const Result corner = run_lcspice("bench --quick --no-ngspice --reference euler '" + (dir / "pulse.cir").string() +
                                        "' -o '" + (dir / "p").string() + "'",
                                    dir);
  EXPECT_EQ(corner.code, 1);
  EXPECT_EQ(corner.err_line(0), "lcspice: error: " + (dir / "pulse.cir").string() +
                                    ": --reference euler reads its rows linearly between steps of TSTEP/64 and "
                                    "cannot place them on the sources' corners (the first at 1.3e-06 s): use the "
                                    "event reference");
  const Result scale = run_lcspice("bench --scale cw --reference euler -o '" + (dir / "s").string() + "'", dir);
  EXPECT_EQ(scale.code, 1);
  EXPECT_EQ(scale.err_line(0), "error: --reference belongs to the work-precision study");
}

TEST(Bench, LongRunsAreQuietWhenStandardErrorIsNotATerminal) {
  const fs::path dir = scratch_dir("quiet_run");
  const Result r = run_lcspice("run '" + source_path("circuits/lc_tank_bridge.cir").string() +
                                   "' --method event --tstop 0.2 -o '" + (dir / "tank.csv").string() + "'",
                               dir);
  ASSERT_EQ(r.code, 0) << r.err;
  // One line, the summary; no progress line (it would hold '\r' and a percentage).
  EXPECT_EQ(r.err.rfind("lcspice: wrote ", 0), 0u) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_EQ(r.err.find('\r'), std::string::npos);
  EXPECT_EQ(r.err.find('%'), std::string::npos);
}

TEST(Bench, BadArgumentsAreUsageErrors) {
  const fs::path dir = scratch_dir("bench_errors");
  const std::string tank = "'" + source_path("circuits/lc_tank_bridge.cir").string() + "'";
  const std::string out = " -o '" + (dir / "out").string() + "'";
  Result r = run_lcspice("bench --quick --no-ngspice --method rk4 " + tank + out, dir);
  EXPECT_EQ(r.code, 1);
  EXPECT_EQ(r.err_line(0), "error: unknown method 'rk4' (known: euler, event, radau3, radau5, smooth, theta)");
  r = run_lcspice("bench --quick --no-ngspice '" + (dir / "missing.cir").string() + "'" + out, dir);
  EXPECT_EQ(r.code, 1);
  EXPECT_FALSE(fs::exists(dir / "out" / "bench.csv"));
}

// --scaling on a short base (2 us of the 50 us run, 200 steps of 10 ns, up to 8x): the CSV holds
// one euler row per TSTOP, TSTOP and the steps doubling exactly, and a fitted slope is printed.
// No timings are asserted (shared machines are noisy).
TEST(Bench, ScalingStudyDoublesTheRunAndFitsASlope) {
  const fs::path dir = scratch_dir("bench_scaling");
  const Result r = run_lcspice("bench --scaling --no-ngspice --tstop 2u --scaling-max 8 '" +
                                   source_path("circuits/tline_lossy_rectifier.cir").string() + "' -o '" +
                                   (dir / "out").string() + "'",
                               dir);
  ASSERT_EQ(r.code, 0) << r.err;
  const Csv csv = parse_csv(read_file(dir / "out" / "tline_lossy_rectifier_scaling.csv"));
  ASSERT_EQ(csv.header, (std::vector<std::string>{"who", "tstop", "steps", "cpu_seconds"}));
  ASSERT_EQ(csv.raw.size(), 4u);
  for (size_t k = 0; k < csv.raw.size(); ++k) {
    EXPECT_EQ(csv.raw[k][0], "euler") << k;
    EXPECT_NEAR(std::stod(csv.raw[k][1]), 2e-6 * (1 << k), 1e-15) << k;
    EXPECT_EQ(std::stol(csv.raw[k][2]), 200L << k) << k;
    EXPECT_GT(std::stod(csv.raw[k][3]), 0) << k;
  }
  EXPECT_NE(r.out.find("slope euler: "), std::string::npos) << r.out;
  const std::string png = read_file(dir / "out" / "tline_lossy_rectifier_scaling.png");
  ASSERT_GT(png.size(), 8u);
  EXPECT_EQ(png.substr(1, 3), "PNG");
  EXPECT_EQ(r.err, "") << r.err;
}

TEST(Bench, ScalingNeedsAFixedStepMethodAndANetlist) {
  const fs::path dir = scratch_dir("bench_scaling_errors");
  const std::string line = "'" + source_path("circuits/tline_lossy_rectifier.cir").string() + "'";
  const std::string out = " -o '" + (dir / "out").string() + "'";
  Result r = run_lcspice("bench --scaling --no-ngspice --method event " + line + out, dir);
  EXPECT_EQ(r.code, 1);
  EXPECT_EQ(r.err_line(0), "error: --scaling needs a fixed-step method; 'event' is not one");
  r = run_lcspice("bench --scaling --no-ngspice" + out, dir);
  EXPECT_EQ(r.code, 1);
  EXPECT_EQ(r.err_line(0), "error: --scaling needs one or more netlists");
  r = run_lcspice("bench --quick --no-ngspice --tstop 1u " + line + out, dir);
  EXPECT_EQ(r.code, 1);
  EXPECT_EQ(r.err_line(0), "error: --tstop and --scaling-max belong to --scaling");
}

// --scale on two tiny sizes: one row per series and size, every run in its own process with a
// positive CPU time and peak memory, the exponents printed (fitted from 1 diode on, so that two
// runs are enough). No timings are compared (shared machines are noisy).
TEST(Bench, ScaleStudyRunsEverySizeInItsOwnProcess) {
  const fs::path dir = scratch_dir("bench_scale");
  const Result r =
      run_lcspice("bench --scale rectifiers --sizes 2,4 --methods euler --fit-from 1 -o '" + (dir / "out").string() + "'",
                  dir);
  ASSERT_EQ(r.code, 0) << r.err;
  const Csv csv = parse_csv(read_file(dir / "out" / "scale_rectifiers.csv"));
  ASSERT_EQ(csv.header, (std::vector<std::string>{"family", "who", "size", "diodes", "status", "tstop", "steps",
                                                  "cpu_seconds", "cpu_per_sim_second", "formation_cpu_seconds",
                                                  "peak_rss_mb", "baseline_rss_mb", "wall_seconds", "failure"}));
  ASSERT_EQ(csv.raw.size(), 4u);
  const char* who[] = {"euler", "euler", "ngspice", "ngspice"};
  for (size_t k = 0; k < 4; ++k) {
    SCOPED_TRACE(k);
    const std::vector<std::string>& row = csv.raw[k];
    const std::vector<double>& v = csv.rows[k];
    EXPECT_EQ(row[0], "rectifiers");
    EXPECT_EQ(row[1], who[k]);
    EXPECT_EQ(row[2], k % 2 ? "4" : "2");
    EXPECT_EQ(row[3], row[2]);
    EXPECT_EQ(row[4], "ok") << row[13];
    EXPECT_NEAR(v[5], 0.1, 1e-12);  // five periods of 50 Hz
    EXPECT_GT(v[6], 0);
    EXPECT_GT(v[7], 0);
    EXPECT_NEAR(v[8], v[7] / v[5], 1e-6 * v[8]);
    if (k < 2) EXPECT_GT(v[9], 0);   // forming lcspice's model
    else EXPECT_EQ(row[9], "");      // ngspice: none
    EXPECT_GT(v[10], 0);
    EXPECT_GE(v[10], v[11] * 0.99);  // a peak holds the idle child's
    EXPECT_GT(v[12], 0);
    EXPECT_EQ(row[13], "");
  }
  EXPECT_EQ(csv.raw[0][6], "1000");  // euler: 200 steps a period
  EXPECT_NE(r.out.find("growth exponent euler: CPU/sim-s ~ diodes^"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("growth exponent ngspice: CPU/sim-s ~ diodes^"), std::string::npos) << r.out;
  const std::string png = read_file(dir / "out" / "scale_rectifiers.png");
  ASSERT_GT(png.size(), 8u);
  EXPECT_EQ(png.substr(1, 3), "PNG");
  EXPECT_EQ(r.err, "") << r.err;
  // The decks it ran, to repeat a run or study its accuracy: the 4-rectifier bank, run again,
  // takes the same 1000 steps.
  EXPECT_TRUE(fs::exists(dir / "out" / "rectifiers_2.cir"));
  const fs::path deck = dir / "out" / "rectifiers_4.cir";
  EXPECT_EQ(read_file(deck).rfind("4 half-wave rectifiers on one 10 V 50 Hz source", 0), 0u);
  const Result rerun = run_lcspice("run '" + deck.string() + "' --method euler --stats -o '" +
                                       (dir / "rerun.csv").string() + "'",
                                   dir);
  ASSERT_EQ(rerun.code, 0) << rerun.err;
  EXPECT_EQ(rerun.err_line(0).rfind("method euler: 1000 steps, ", 0), 0u) << rerun.err;
}

// A run over the wall-clock limit is killed and recorded, and its series stops there; the study
// still succeeds. (5000 s of simulated time, 5e7 steps, cannot finish in half a second.)
TEST(Bench, ScaleStudyKillsARunOverTheLimitAndStopsItsSeries) {
  const fs::path dir = scratch_dir("bench_scale_timeout");
  const Result r = run_lcspice("bench --scale cw --sizes 1,2 --methods euler --no-ngspice --tstop 5000 --run-timeout 0.5 -o '" +
                                   (dir / "out").string() + "'",
                               dir);
  ASSERT_EQ(r.code, 0) << r.err;
  const Csv csv = parse_csv(read_file(dir / "out" / "scale_cw.csv"));
  ASSERT_EQ(csv.raw.size(), 1u);
  EXPECT_EQ(csv.raw[0][4], "timeout");
  EXPECT_EQ(csv.raw[0][13], "timed out after 0.5 s (wall clock)");
  EXPECT_EQ(csv.raw[0][7], "");
  EXPECT_LT(csv.rows[0][12], 10.0);
  EXPECT_NE(r.out.find("growth exponent euler: n/a"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(dir / "out" / "scale_cw.png"));  // nothing to draw
}

TEST(Bench, ScaleArgumentsAreChecked) {
  const fs::path dir = scratch_dir("bench_scale_errors");
  const std::string out = " -o '" + (dir / "out").string() + "'";
  Result r = run_lcspice("bench --scale bridge" + out, dir);
  EXPECT_EQ(r.code, 1);
  EXPECT_EQ(r.err_line(0), "error: unknown circuit family 'bridge' (known: cw, ladder, rectifiers)");
  r = run_lcspice("bench --scale cw --sizes 4,2" + out, dir);
  EXPECT_EQ(r.code, 1);
  EXPECT_EQ(r.err_line(0), "error: --sizes must be increasing");
  r = run_lcspice("bench --scale cw --sizes 2,x" + out, dir);
  EXPECT_EQ(r.code, 1);
  EXPECT_EQ(r.err_line(0), "error: --sizes: 'x' is not a whole number");
  r = run_lcspice("bench --scale cw --methods rk4" + out, dir);
  EXPECT_EQ(r.code, 1);
  EXPECT_EQ(r.err_line(0), "error: unknown method 'rk4' (known: euler, event, radau3, radau5, smooth, theta)");
  r = run_lcspice("bench --quick --sizes 2 '" + source_path("circuits/lc_tank_bridge.cir").string() + "'" + out, dir);
  EXPECT_EQ(r.code, 1);
  EXPECT_EQ(r.err_line(0), "error: --sizes, --run-timeout and --fit-from belong to --scale");
  EXPECT_FALSE(fs::exists(dir / "out" / "scale_cw.csv"));
}

}  // namespace
}  // namespace lcs::cli_testing
