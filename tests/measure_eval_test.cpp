// `.meas tran` evaluation (cli/measure.h) on hand-made waveforms whose answers are worked out by
// hand: the statistics, the window's interpolated ends, ngspice's RISE/FALL/CROSS counting, the
// failures and their reasons, and the tap that hides the measures' columns from the CSV.
#include <cmath>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "cli/measure.h"
#include "netlist/netlist.h"

namespace lcs {
namespace {

// One measure card read in a deck with nodes a, b and c.
Measure meas(const std::string& card) {
  const Netlist n = parse_netlist_string(
      "t\nV1 a 0 1\nR1 a b 1\nR2 b c 1\nR3 c 0 1\n.tran 1 8\n" + card + "\n", "m.cir");
  if (n.measures.size() != 1) throw std::runtime_error("no measure in " + card);
  return n.measures.front();
}

// t = 0..8: v(a) a triangle 0 1 2 3 4 3 2 1 0, v(b) = 2, v(c) = 10 t.
MeasureWaveforms triangle() {
  MeasureWaveforms w;
  for (int k = 0; k <= 8; ++k) {
    w.times.push_back(k);
    w.columns["v(a)"].push_back(k <= 4 ? k : 8 - k);
    w.columns["v(b)"].push_back(2);
    w.columns["v(c)"].push_back(10.0 * k);
  }
  return w;
}

double value(const std::string& card) {
  const MeasureResult r = evaluate_measure(meas(card), triangle());
  EXPECT_TRUE(r.value.has_value()) << card << ": " << r.failure;
  return r.value.value_or(NAN);
}

std::string failure(const std::string& card) {
  const MeasureResult r = evaluate_measure(meas(card), triangle());
  EXPECT_FALSE(r.value.has_value()) << card << " = " << r.value.value_or(0);
  return r.failure;
}

TEST(MeasureEval, StatisticsOverTheWholeRun) {
  EXPECT_DOUBLE_EQ(value(".meas tran x avg v(a)"), 2.0);           // area 16 over 8 s
  EXPECT_DOUBLE_EQ(value(".meas tran x integ v(a)"), 16.0);
  EXPECT_DOUBLE_EQ(value(".meas tran x integral v(c)"), 320.0);    // 10 t^2 / 2 at t = 8
  // RMS: the exact integral of the triangle's square, 2 * 4^3 / 3, over 8 s (the trapezoid of the
  // squares would give 44 / 8).
  EXPECT_DOUBLE_EQ(value(".meas tran x rms v(a)"), 4 / std::sqrt(3.0));
  EXPECT_DOUBLE_EQ(value(".meas tran x rms v(a) from=1 to=3"), std::sqrt(13.0 / 3));  // (27 - 1) / 3 / 2
  EXPECT_DOUBLE_EQ(value(".meas tran x max v(a)"), 4.0);
  EXPECT_DOUBLE_EQ(value(".meas tran x min v(a)"), 0.0);
  EXPECT_DOUBLE_EQ(value(".meas tran x pp v(a)"), 4.0);
  EXPECT_DOUBLE_EQ(value(".meas tran x max_at v(a)"), 4.0);
  // Equal minima at t = 0 and t = 8: the last one, as ngspice (`value <= min`).
  EXPECT_DOUBLE_EQ(value(".meas tran x min_at v(a)"), 8.0);
}

TEST(MeasureEval, WindowEndsAreInterpolated) {
  // [0.5, 1.5]: 0.5 .. 1 .. 1.5, area 1 over 1 s (ngspice averages the one row inside: 0/0).
  EXPECT_DOUBLE_EQ(value(".meas tran x avg v(a) from=0.5 to=1.5"), 1.0);
  EXPECT_DOUBLE_EQ(value(".meas tran x integ v(a) from=0.5 to=1.5"), 1.0);
  // No row inside [4.2, 4.6]: the interpolated ends 3.8 and 3.4.
  EXPECT_DOUBLE_EQ(value(".meas tran x max v(a) from=4.2 to=4.6"), 3.8);
  EXPECT_DOUBLE_EQ(value(".meas tran x min_at v(a) from=4.2 to=4.6"), 4.6);
  EXPECT_NEAR(value(".meas tran x pp v(a) from=4.2 to=4.6"), 0.4, 1e-15);
  // A window reaching past the run is clipped to it: the average over [6, 8].
  EXPECT_DOUBLE_EQ(value(".meas tran x avg v(a) from=6 to=20"), 1.0);
}

TEST(MeasureEval, FindAt) {
  EXPECT_DOUBLE_EQ(value(".meas tran x find v(a) at=2.25"), 2.25);
  EXPECT_DOUBLE_EQ(value(".meas tran x find v(a) at=0"), 0.0);
  EXPECT_DOUBLE_EQ(value(".meas tran x find v(a) at=8"), 0.0);
  EXPECT_EQ(failure(".meas tran x find v(a) at=9"), "AT=9 s is outside the run (t = 0 to 8 s)");
}

TEST(MeasureEval, CrossingsCountedAsNgspice) {
  EXPECT_DOUBLE_EQ(value(".meas tran x when v(a)=2.5"), 2.5);  // the first crossing, a rise
  EXPECT_DOUBLE_EQ(value(".meas tran x when v(a)=2.5 fall=1"), 5.5);
  EXPECT_DOUBLE_EQ(value(".meas tran x when v(a)=2.5 cross=2"), 5.5);
  EXPECT_DOUBLE_EQ(value(".meas tran x when v(a)=2.5 cross=last"), 5.5);
  EXPECT_DOUBLE_EQ(value(".meas tran x when v(a)=2.5 rise=last"), 2.5);
  // TD= and FROM=: crossings before them do not count.
  EXPECT_DOUBLE_EQ(value(".meas tran x when v(a)=2.5 td=3"), 5.5);
  EXPECT_DOUBLE_EQ(value(".meas tran x when v(a)=2.5 from=3"), 5.5);
  EXPECT_EQ(failure(".meas tran x when v(a)=2.5 cross=2 to=5"),
            "v(a) crosses 2.5 only 1 time between t = 0 and 5 s (CROSS=2)");
  // The window's first interval (ngspice 39): a rise there is counted (here v(a) = 0.5 at t = 0.5)
  // and reported by interpolating [1, 2], but the default (the first) and LAST skip it.
  EXPECT_DOUBLE_EQ(value(".meas tran x when v(a)=0.5 rise=1"), 0.5);
  EXPECT_DOUBLE_EQ(value(".meas tran x when v(a)=0.5 cross=1"), 0.5);
  EXPECT_DOUBLE_EQ(value(".meas tran x when v(a)=0.5"), 7.5);
  EXPECT_DOUBLE_EQ(value(".meas tran x when v(a)=0.5 cross=2"), 7.5);
  // Reaching the level is crossing it: v(a) = 2 at t = 2 (a rise) and t = 6 (a fall).
  EXPECT_DOUBLE_EQ(value(".meas tran x when v(a)=v(b)"), 2.0);
  EXPECT_DOUBLE_EQ(value(".meas tran x when v(a)=v(b) cross=2"), 6.0);
  EXPECT_DOUBLE_EQ(value(".meas tran x when v(b)=v(a) fall=1"), 2.0);  // v(b) - v(a) falls at t = 2
  // Starting on the level and going up is a rise on the first interval (ngspice 39: RISE=1 is
  // t = 0); the default takes the return to 0 at t = 8, a fall.
  EXPECT_DOUBLE_EQ(value(".meas tran x when v(a)=0 rise=1"), 0.0);
  EXPECT_DOUBLE_EQ(value(".meas tran x when v(a)=0 cross=1"), 0.0);
  EXPECT_DOUBLE_EQ(value(".meas tran x when v(a)=0"), 8.0);
  EXPECT_DOUBLE_EQ(value(".meas tran x when v(a)=0 cross=2"), 8.0);
  EXPECT_DOUBLE_EQ(value(".meas tran x when v(a)=0 cross=last"), 8.0);
  // Only the first interval's rise: RISE=1 finds it, the default and LAST do not (ngspice 39.3).
  EXPECT_DOUBLE_EQ(value(".meas tran x when v(a)=2.5 rise=1 from=2.2 to=4.2"), 2.5);
  EXPECT_EQ(failure(".meas tran x when v(a)=2.5 rise=last from=2.2 to=4.2"),
            "v(a) rises through 2.5 between t = 2.2 and 4.2 s only on the window's first interval, which LAST does not "
            "take (ngspice 39)");
  EXPECT_EQ(failure(".meas tran x when v(a)=2.5 from=2.2 to=4.2"),
            "v(a) crosses 2.5 between t = 2.2 and 4.2 s only on the window's first interval, which the first crossing "
            "does not take (ngspice 39)");
  // Starting on the level and going down is no fall (and below, there is none to come); nor is a
  // fall through the level on the first interval.
  EXPECT_EQ(failure(".meas tran x when v(a)=4 fall=1 from=4"), "v(a) never falls through 4 between t = 4 and 8 s");
  EXPECT_EQ(failure(".meas tran x when v(a)=4 cross=1 from=4"), "v(a) never crosses 4 between t = 4 and 8 s");
  EXPECT_EQ(failure(".meas tran x when v(a)=3.5 fall=1 from=4"), "v(a) never falls through 3.5 between t = 4 and 8 s");
}

// t = 0..10: v(a) 0 0.5 1 1 1 0 0 0 1 2 1, sitting on 1 (t = 2..4) and on 0 (t = 5..7).
MeasureWaveforms flat() {
  MeasureWaveforms w;
  const double a[] = {0, 0.5, 1, 1, 1, 0, 0, 0, 1, 2, 1};
  for (int k = 0; k <= 10; ++k) {
    w.times.push_back(k);
    w.columns["v(a)"].push_back(a[k]);
    w.columns["v(b)"].push_back(1);
    w.columns["v(c)"].push_back(10.0 * k);
  }
  return w;
}

TEST(MeasureEval, WaveformSittingOnTheLevel) {
  auto on_flat = [](const std::string& card) { return evaluate_measure(meas(card), flat()); };
  auto at = [&](const std::string& card) {
    const MeasureResult r = on_flat(card);
    EXPECT_TRUE(r.value.has_value()) << card << ": " << r.failure;
    return r.value.value_or(NAN);
  };
  // ngspice 39 changes side on every row equal to the level: on v(a) = 1 the rise at t = 2, a fall
  // at t = 3 and a rise at t = 4 (both 1 to 1: no time, the measure fails), the fall at t = 5, ...
  EXPECT_DOUBLE_EQ(at(".meas tran x when v(a)=1 rise=1"), 2.0);
  const MeasureResult f1 = on_flat(".meas tran x when v(a)=1 fall=1");
  EXPECT_FALSE(f1.value);
  EXPECT_EQ(f1.failure, "v(a) is level with 1 from t = 2 to 3 s where the crossing asked for is counted "
                        "(ngspice fails such a measure)");
  EXPECT_FALSE(on_flat(".meas tran x when v(a)=1 rise=2").value);
  EXPECT_DOUBLE_EQ(at(".meas tran x when v(a)=1 fall=2"), 4.0);
  EXPECT_DOUBLE_EQ(at(".meas tran x when v(a)=1 rise=3"), 8.0);
  EXPECT_DOUBLE_EQ(at(".meas tran x when v(a)=1 rise=last"), 8.0);
  EXPECT_DOUBLE_EQ(at(".meas tran x when v(a)=1 fall=last"), 10.0);
  // On v(a) = 0: a rise counted on [0, 1], the fall at t = 5, then a rise and a fall 0 to 0 on
  // [5, 6] and [6, 7] (failed), the rise at t = 7.
  EXPECT_DOUBLE_EQ(at(".meas tran x when v(a)=0 cross=2"), 5.0);
  EXPECT_FALSE(on_flat(".meas tran x when v(a)=0 cross=3").value);
  EXPECT_FALSE(on_flat(".meas tran x when v(a)=0 fall=last").value);
  EXPECT_DOUBLE_EQ(at(".meas tran x when v(a)=0 cross=last"), 7.0);
  EXPECT_FALSE(on_flat(".meas tran x when v(a)=v(b) fall=1").value);  // the same against a probe
  EXPECT_DOUBLE_EQ(at(".meas tran x when v(a)=v(b) fall=2"), 4.0);
  EXPECT_FALSE(on_flat(".meas tran x trig v(a) val=1 fall=1 targ v(c) val=50 rise=1").value);
}

TEST(MeasureEval, FindWhenAndTrigTarg) {
  EXPECT_DOUBLE_EQ(value(".meas tran x find v(c) when v(a)=1 fall=1"), 70.0);
  EXPECT_DOUBLE_EQ(value(".meas tran x find v(c) when v(a)=v(b) fall=last"), 60.0);
  EXPECT_DOUBLE_EQ(value(".meas tran x trig v(a) val=1 rise=1 targ v(a) val=1 fall=1"), 6.0);
  EXPECT_DOUBLE_EQ(value(".meas tran x trig at=2 targ v(a) val=3 fall=1"), 3.0);
  // Negative when the target comes first, as ngspice's targ - trig.
  EXPECT_DOUBLE_EQ(value(".meas tran x trig v(a) val=3 fall=1 targ v(c) val=25 cross=1"), -2.5);
  EXPECT_DOUBLE_EQ(value(".meas tran x trig v(a) val=3 rise=1 targ v(a) val=3 fall=1 td=4.5"), 2.0);
}

TEST(MeasureEval, Failures) {
  EXPECT_EQ(failure(".meas tran x when v(a)=5"), "v(a) never crosses 5 between t = 0 and 8 s");
  EXPECT_EQ(failure(".meas tran x when v(a)=2.5 rise=2"), "v(a) rises through 2.5 only 1 time between t = 0 and 8 s (RISE=2)");
  EXPECT_EQ(failure(".meas tran x when v(a)=2.5 fall=last td=6"), "v(a) never falls through 2.5 between t = 6 and 8 s");
  EXPECT_EQ(failure(".meas tran x find v(c) when v(a)=v(b) cross=3"),
            "v(a) crosses v(b) only 2 times between t = 0 and 8 s (CROSS=3)");
  EXPECT_EQ(failure(".meas tran x trig v(a) val=1 rise=1 targ v(a) val=9 fall=1"),
            "TARG: v(a) never falls through 9 between t = 0 and 8 s");
  EXPECT_EQ(failure(".meas tran x trig v(a) val=1 rise=3 targ v(a) val=1 fall=1"),
            "TRIG: v(a) rises through 1 only 1 time between t = 0 and 8 s (RISE=3)");
  EXPECT_EQ(failure(".meas tran x avg v(a) from=9"), "no part of the run (t = 0 to 8 s) lies in the window t >= 9 s");
  EXPECT_EQ(failure(".meas tran x max v(a) from=9 to=12"), "no part of the run (t = 0 to 8 s) lies in the window t = 9 to 12 s");
  EXPECT_EQ(failure(".meas tran x avg v(a) from=8"), "the window t = 8 to 8 s has no length");
  // INTEG over no length is 0 (ngspice's sum of nothing).
  EXPECT_DOUBLE_EQ(value(".meas tran x integ v(a) from=8"), 0.0);
}

TEST(MeasureEval, ReportLines) {
  std::vector<MeasureResult> results(2);
  results[0].name = "trise";
  results[0].value = 2.1972245773362196e-3;
  results[1].name = "never";
  results[1].failure = "v(out) never crosses 2 between t = 0 and 0.005 s";
  std::ostringstream out;
  report_measures(results, out);
  EXPECT_EQ(out.str(), "trise = 2.197224577e-03\n"
                       "lcspice: warning: .meas never failed: v(out) never crosses 2 between t = 0 and 0.005 s\n");
}

TEST(MeasureEval, ProbesEachOnceInOrderOfUse) {
  const Netlist n = parse_netlist_string(
      "t\nV1 a 0 1\nR1 a b 1\nR2 b c 1\nR3 c 0 1\n.tran 1 8\n"
      ".meas tran x find v(c) when v(a)=v(b)\n.meas tran y avg v(b)\n"
      ".meas tran z trig at=1 targ i(v1) val=0 rise=1\n", "m.cir");
  std::vector<std::string> names;
  for (const Probe& p : measure_probes(n.measures)) names.push_back(p.name());
  EXPECT_EQ(names, (std::vector<std::string>{"v(c)", "v(a)", "v(b)", "i(v1)"}));
}

TEST(MeasureEval, TapPassesTheVisibleColumnsAndRecordsTheNeededOnes) {
  MemorySink csv;
  MeasureTap tap(csv, 2, {"hidden", "v(a)"});
  tap.begin({"v(a)", "v(b)", "hidden"});
  Eigen::VectorXd row(3);
  row << 1, 2, 3;
  tap.row(0.5, row);
  row << 4, 5, 6;
  tap.row(1.5, row);
  tap.finish();
  EXPECT_EQ(csv.names, (std::vector<std::string>{"v(a)", "v(b)"}));
  ASSERT_EQ(csv.rows.size(), 2u);
  EXPECT_EQ(csv.rows[1].size(), 2);
  EXPECT_EQ(csv.rows[1][1], 5);
  EXPECT_TRUE(csv.finished);
  EXPECT_EQ(tap.waveforms().times, (std::vector<double>{0.5, 1.5}));
  EXPECT_EQ(tap.waveforms().columns.at("hidden"), (std::vector<double>{3, 6}));
  EXPECT_EQ(tap.waveforms().columns.at("v(a)"), (std::vector<double>{1, 4}));
  EXPECT_EQ(tap.waveforms().columns.count("v(b)"), 0u);
}

}  // namespace
}  // namespace lcs
