// `.meas tran` through `lcspice run`: an RC charging from 0 to 1 V (tau = RC = 1 ms) and a 1 kHz
// sine, whose measures have closed forms; a measure that cannot be computed (a warning, exit 0);
// an unknown probe (exit 2, located); the CSV unchanged by the measures' hidden columns; no
// measures after a numerical failure (exit 3); PARAM measures in ngspice's order of evaluation.
#include <cmath>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/cli_support.h"

namespace lcs::cli_testing {
namespace {

// v(out) = 1 - exp(-t / tau) from v(out) = 0 at t = 0.
const char* kRc =
    "rc charging\n"
    "V1 in 0 DC 1\n"
    "R1 in out 1k\n"
    "C1 out 0 1u IC=0\n"
    ".tran 1u 5m UIC\n"
    ".print tran v(out)\n";
const char* kRcMeasures =
    ".meas tran trise trig v(out) val=0.1 rise=1 targ v(out) val=0.9 rise=1\n"
    ".meas tran t50 when v(out)=0.5\n"
    ".measure tran vtau find v(out) at=1m\n"
    ".meas tran vavg avg v(out) from=0 to=5m\n"
    ".meas tran vint integ v(out)\n"
    ".meas tran vrms rms v(out)\n"
    ".meas tran vmax max v(out) to=2m\n"
    ".meas tran iin find i(v1) when v(out)=0.5\n";
constexpr double kTau = 1e-3, kT = 5e-3;

// "name = value" lines of standard error, in order.
std::vector<std::pair<std::string, double>> measure_lines(const std::string& err) {
  static const std::regex line("^([a-z0-9_]+) = (\\S+)$");
  std::vector<std::pair<std::string, double>> out;
  std::istringstream in(err);
  for (std::string s; std::getline(in, s);) {
    std::smatch m;
    if (std::regex_match(s, m, line)) out.emplace_back(m[1], std::stod(m[2]));
  }
  return out;
}

std::map<std::string, double> measures(const std::string& err) {
  std::map<std::string, double> out;
  for (const auto& [name, value] : measure_lines(err)) out[name] = value;
  return out;
}

Result run_deck(const fs::path& deck, const std::string& extra = "") {
  return run_lcspice("run '" + deck.string() + "' -o '" + (deck.parent_path() / "out.csv").string() + "' " + extra,
                     deck.parent_path());
}

TEST(MeasureCli, RcChargingMatchesTheClosedForms) {
  const fs::path deck = write_deck("measure_", "rc", std::string(kRc) + kRcMeasures + ".end\n");
  const Result r = run_deck(deck);
  ASSERT_EQ(r.code, 0) << r.err;
  const auto lines = measure_lines(r.err);
  std::vector<std::string> order;
  for (const auto& line : lines) order.push_back(line.first);
  EXPECT_EQ(order, (std::vector<std::string>{"trise", "t50", "vtau", "vavg", "vint", "vrms", "vmax", "iin"}));
  std::map<std::string, double> m = measures(r.err);
  const double e5 = std::exp(-kT / kTau);
  // Rows every 1 us, exact (event method): what is left is the linear interpolation between them.
  auto near = [&](const char* name, double expected, double relative) {
    EXPECT_NEAR(m[name], expected, relative * std::abs(expected)) << name;
  };
  near("trise", kTau * std::log(9.0), 1e-7);  // 10 % to 90 %
  near("t50", kTau * std::log(2.0), 1e-6);    // -tau ln(1 - 0.5)
  near("vtau", 1 - std::exp(-1.0), 1e-9);
  near("vavg", 1 - kTau / kT * (1 - e5), 1e-7);
  near("vint", kT - kTau * (1 - e5), 1e-7);
  near("vrms", std::sqrt((kT - 2 * kTau * (1 - e5) + kTau / 2 * (1 - e5 * e5)) / kT), 1e-7);
  near("vmax", 1 - std::exp(-2.0), 1e-9);
  near("iin", -0.5e-3, 1e-6);  // V1's current runs from + through it to -: (0.5 V - 1 V) / 1k
}

TEST(MeasureCli, MeasureThatCannotBeComputedWarnsAndExitsZero) {
  const fs::path deck = write_deck("measure_", "never",
                                   std::string(kRc) + ".meas tran never when v(out)=2\n"
                                                      ".meas tran late find v(out) at=6m\n"
                                                      ".meas tran t50 when v(out)=0.5\n.end\n");
  const Result r = run_deck(deck);
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("lcspice: warning: .meas never failed: v(out) never crosses 2 between t = 0 and 0.005 s\n"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("lcspice: warning: .meas late failed: AT=0.006 s is outside the run (t = 0 to 0.005 s)\n"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(measures(r.err).count("t50"), 1u) << r.err;  // the others are still reported
  EXPECT_LT(r.err.find(".meas never failed"), r.err.find("t50 = "));  // in card order
}

TEST(MeasureCli, ParamsAreComputedAfterTheOtherMeasuresInCardOrder) {
  // ngspice 39.3's order (checked with libngspice): every other measure first, then the PARAMs
  // in card order, each seeing the ones above it; one naming a failed measure, a PARAM further
  // down or an unknown name fails, and the rest are reported, in card order.
  const fs::path deck = write_deck("measure_", "param",
                                   std::string(kRc) + ".param k=2\n.func half(x) {x/2}\n"
                                                      ".meas tran ratio param='vmax*k/vtau'\n"
                                                      ".meas tran vmax max v(out) to=2m\n"
                                                      ".meas tran vtau find v(out) at=1m\n"
                                                      ".meas tran twice param={2*ratio + half(vtau)}\n"
                                                      ".meas tran early param='later+1'\n"
                                                      ".meas tran later param='1'\n"
                                                      ".meas tran never when v(out)=2\n"
                                                      ".meas tran broken param='never*2'\n"
                                                      ".meas tran ltspice PARAM vmax**2\n.end\n");
  const Result r = run_deck(deck);
  ASSERT_EQ(r.code, 0) << r.err;
  const auto lines = measure_lines(r.err);
  std::vector<std::string> order;
  for (const auto& line : lines) order.push_back(line.first);
  EXPECT_EQ(order, (std::vector<std::string>{"ratio", "vmax", "vtau", "twice", "later", "ltspice"}));
  std::map<std::string, double> m = measures(r.err);
  const double vmax = 1 - std::exp(-2.0), vtau = 1 - std::exp(-1.0);
  EXPECT_NEAR(m["ratio"], vmax * 2 / vtau, 1e-8);
  EXPECT_NEAR(m["twice"], 2 * m["ratio"] + vtau / 2, 1e-8);
  EXPECT_EQ(m["later"], 1);
  EXPECT_NEAR(m["ltspice"], vmax * vmax, 1e-8);
  EXPECT_NE(r.err.find("lcspice: warning: .meas early failed: PARAM 'later+1': measure 'later' is a PARAM further "
                       "down (PARAMs are computed in card order, as in ngspice)\n"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("lcspice: warning: .meas broken failed: PARAM 'never*2': measure 'never' failed\n"),
            std::string::npos)
      << r.err;
  EXPECT_LT(r.err.find("ratio = "), r.err.find("vmax = "));
  EXPECT_LT(r.err.find(".meas early failed"), r.err.find("later = "));
}

TEST(MeasureCli, CsvIsTheSameWithAndWithoutMeasures) {
  const fs::path plain = write_deck("measure_", "plain", std::string(kRc) + ".end\n");
  // The measures read i(v1) and v(in), which the CSV does not write: hidden columns.
  const fs::path measured = write_deck("measure_", "measured",
                                       std::string(kRc) + kRcMeasures + ".meas tran vin avg v(in)\n.end\n");
  ASSERT_EQ(run_deck(plain).code, 0);
  const Result r = run_deck(measured);
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string a = read_file(plain.parent_path() / "out.csv"), b = read_file(measured.parent_path() / "out.csv");
  EXPECT_EQ(a.substr(0, a.find('\n')), "time,v(out)");
  EXPECT_EQ(a, b);
  EXPECT_NEAR(measures(r.err)["vin"], 1.0, 1e-12);
  // --probe names the CSV's columns; the measures still read theirs.
  const Result p = run_deck(measured, "--probe 'v(in)'");
  ASSERT_EQ(p.code, 0) << p.err;
  const Csv csv = parse_csv(read_file(measured.parent_path() / "out.csv"));
  EXPECT_EQ(csv.header, (std::vector<std::string>{"time", "v(in)"}));
  EXPECT_NEAR(measures(p.err)["t50"], kTau * std::log(2.0), 1e-9);
}

TEST(MeasureCli, UnknownProbeIsALocatedError) {
  const fs::path deck = write_deck("measure_", "unknown", std::string(kRc) + ".meas tran x avg v(nowhere)\n.end\n");
  const Result r = run_deck(deck);
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err, deck.string() + ":7:18: error: unknown node 'nowhere'\n.meas tran x avg v(nowhere)\n" +
                       std::string(17, ' ') + "^~~~~~~~~~\n");
  const fs::path syntax = write_deck("measure_", "syntax", std::string(kRc) + ".meas tran x when v(out)=0.5 rise=0\n");
  const Result s = run_deck(syntax);
  EXPECT_EQ(s.code, 2);
  EXPECT_EQ(s.err_line(0), syntax.string() + ":7:35: error: RISE= must be a whole number from 1, or LAST");
}

TEST(MeasureCli, OtherAnalysesAreWarnedAboutAndSkipped) {
  const fs::path deck = write_deck("measure_", "ac",
                                   std::string(kRc) + ".meas ac gain max vdb(out)\n.meas tran t50 when v(out)=0.5\n.end\n");
  const Result r = run_deck(deck);
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find(deck.string() + ":7:7: warning: '.meas ac' is ignored (lcspice runs transient analyses)"),
            std::string::npos)
      << r.err;
  const auto m = measures(r.err);
  EXPECT_EQ(m.size(), 1u);
  EXPECT_EQ(m.count("t50"), 1u);
}

TEST(MeasureCli, SineMatchesTheClosedForms) {
  // v(in) = sin(2 pi 1k t); v(in) = 0.5 at 1/12 ms (rise), 5/12 ms (fall), 13/12, 17/12, 25/12 ...
  const fs::path deck = write_deck("measure_", "sine",
                                   "sine\nV1 in 0 SIN(0 1 1k)\nR1 in 0 1k\n.tran 1u 3m\n"
                                   ".meas tran vrms rms v(in) from=0 to=2m\n"
                                   ".meas tran vavg avg v(in) from=0 to=2m\n"
                                   ".meas tran vpp pp v(in)\n"
                                   ".meas tran tc3 when v(in)=0.5 cross=3\n"
                                   ".meas tran tlast when v(in)=0.5 rise=last\n"
                                   ".meas tran tf2 when v(in)=0.5 fall=2\n"
                                   ".meas tran tpeak max_at v(in) from=0 to=1m\n"
                                   ".meas tran tlow min_at v(in) from=0 to=1m\n"
                                   ".meas tran ipeak find i(v1) at=0.25m\n"
                                   ".meas tran above trig v(in) val=0.5 rise=1 targ v(in) val=0.5 fall=1\n"
                                   ".end\n");
  const Result r = run_deck(deck);
  ASSERT_EQ(r.code, 0) << r.err;
  std::map<std::string, double> m = measures(r.err);
  // RMS of the rows joined by lines (1 us apart, theta = 2 pi 1k * 1 us between them): a segment
  // from sin x to sin(x + theta) has the mean square (2 + cos theta) / 6 over whole periods, 3.3e-6
  // below the sine's 1/2 (the trapezoid of the squares overestimates it about as much).
  const double theta = 2 * M_PI * 1e-3;
  EXPECT_NEAR(m["vrms"], std::sqrt((2 + std::cos(theta)) / 6), 1e-9);
  EXPECT_NEAR(m["vavg"], 0.0, 1e-9);
  EXPECT_NEAR(m["vpp"], 2.0, 1e-9);
  const double ms = 1e-3;
  EXPECT_NEAR(m["tc3"], 13.0 / 12 * ms, 1e-9);
  EXPECT_NEAR(m["tlast"], 25.0 / 12 * ms, 1e-9);
  EXPECT_NEAR(m["tf2"], 17.0 / 12 * ms, 1e-9);
  EXPECT_NEAR(m["tpeak"], 0.25 * ms, 1e-12);
  EXPECT_NEAR(m["tlow"], 0.75 * ms, 1e-12);
  EXPECT_NEAR(m["ipeak"], -1e-3, 1e-12);
  EXPECT_NEAR(m["above"], 4.0 / 12 * ms, 1e-9);  // 1/12 ms to 5/12 ms
}

// No results, but one warning line that the measures were not computed.
TEST(MeasureCli, NoMeasuresAfterANumericalFailure) {
  // The flip-flop of bjt_multistability_test.cpp: three operating points, none chosen (exit 3).
  const fs::path deck = write_deck("measure_", "flipflop",
                                   "flip-flop without storage\n"
                                   "vs vs 0 5\nr1 vs c1 1k\nr2 vs c2 1k\nr3 c1 b2 10k\nr4 c2 b1 10k\nr5 b1 0 10k\n"
                                   "r6 b2 0 10k\nq1 c1 b1 0 qn\nq2 c2 b2 0 qn\n.model qn npn(bf=100 von=0.7)\n"
                                   ".tran 1u 10u\n.meas tran vc1 avg v(c1)\n.end\n");
  const Result r = run_deck(deck);
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_EQ(r.err.find("vc1"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("lcspice: warning: .meas results not computed: the run stopped early at a numerical failure "
                       "(1 measure)\n"),
            std::string::npos)
      << r.err;
}

}  // namespace
}  // namespace lcs::cli_testing
