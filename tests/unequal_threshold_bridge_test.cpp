// A bridge of RON = 0 diodes into a pure inductor, its two diode cards 0.05 V apart (D1, D4 at
// 0.75 V; D2, D3 at 0.7 V). At t = 0 the inductor carries no current and the nodes p, n float;
// the start LCP's rows of the inductor's current have only O(h) entries (h = 1e-8 of the step)
// against the O(1) of the diodes' loops, below Lemke's tolerance at .tran 10u, and every ideal
// method stopped at t = 0 (event: "no next mode: the switching LCP has no solution (Lemke: ray
// termination)", euler and radau5: "no consistent initial complementarity state"). With equal
// thresholds, or at .tran 100u, it ran. The operating point's mode is the first guess then
// (event_driven.cpp, select; start_complementarity.cpp).
//
// Closed form. With the current i > 0 flowing p -> n, p is held by the higher of its feeders
// (a - 0.75 through D1, 0 - 0.7 through D3) and n by the lower of its drains (a + 0.7 through D2,
// 0 + 0.75 through D4), so v(p, n) = |a - 0.05| - 1.45 with a = 20 sin(wt). The current starts
// where a = 1.5 V (t1) and, since the mean of |a - 0.05| is far above 1.45 V, never returns to
// zero:  i(t) = (1/L) * integral from t1 to t of (|a(s) - 0.05| - 1.45) ds, integrated piecewise
// between the zeros of a - 0.05.
#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/cli_support.h"

namespace lcs::cli_testing {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kOmega = 2 * kPi * 50, kAmplitude = 20, kL = 0.5, kOffset = 0.05, kDrop = 1.45;

std::string bridge(const std::string& tstep) {
  return "RON=0 bridge into an inductor, D1/D4 threshold 0.75 V, D2/D3 0.7 V\n"
         "V1 a 0 SIN(0 20 50)\nD1 a p d1\nD2 n a d2\nD3 0 p d2\nD4 n 0 d1\nL1 p n 0.5\n"
         ".model d1 D(VON=0.75 RON=0)\n.model d2 D(VON=0.7 RON=0)\n.tran " +
         tstep + " 0.1\n.end\n";
}

// The antiderivative of a - 0.05 (a = 20 sin(wt)).
double primitive(double s) { return -kAmplitude * std::cos(kOmega * s) / kOmega - kOffset * s; }

double closed_form_current(double t) {
  const double t1 = std::asin((kDrop + kOffset) / kAmplitude) / kOmega;
  if (t <= t1) return 0;
  std::vector<double> cuts{t1};
  const double k0 = std::asin(kOffset / kAmplitude);
  for (int k = 0;; ++k) {
    const double up = (k0 + 2 * kPi * k) / kOmega, down = (kPi - k0 + 2 * kPi * k) / kOmega;
    if (up >= t) break;
    if (up > t1) cuts.push_back(up);
    if (down < t && down > t1) cuts.push_back(down);
  }
  cuts.push_back(t);
  double integral = 0;
  for (size_t j = 0; j + 1 < cuts.size(); ++j) {
    const double mid = (cuts[j] + cuts[j + 1]) / 2;
    const double sign = kAmplitude * std::sin(kOmega * mid) - kOffset > 0 ? 1 : -1;
    integral += sign * (primitive(cuts[j + 1]) - primitive(cuts[j])) - kDrop * (cuts[j + 1] - cuts[j]);
  }
  return integral / kL;
}

// The largest distance of i(l1) from the closed form over the rows of one run.
double worst_error(const std::string& method, const std::string& tstep) {
  const fs::path dir = scratch_dir("unequal_threshold_bridge_" + method + "_" + tstep);
  std::ofstream(dir / "bridge.cir") << bridge(tstep);
  const Result r = run_lcspice("run '" + (dir / "bridge.cir").string() + "' --method " + method + " -o '" +
                                   (dir / "out.csv").string() + "'",
                               dir);
  EXPECT_EQ(r.code, 0) << method << ": " << r.err;
  if (r.code != 0) return INFINITY;
  const Csv csv = parse_csv(read_file(dir / "out.csv"));
  const std::vector<double> t = column(csv, "time"), i = column(csv, "i(l1)");
  EXPECT_EQ(t.back(), 0.1) << method;
  double worst = 0;
  for (size_t j = 0; j < t.size(); ++j) worst = std::max(worst, std::abs(i[j] - closed_form_current(t[j])));
  return worst;
}

// Measured: event 2.7e-13 A, radau5 1.9e-8 A, euler 1.9e-4 A at 10 us (of 2.26 A at 0.1 s).
TEST(UnequalThresholdBridge, EveryIdealMethodStartsAndFollowsTheClosedForm) {
  EXPECT_LT(worst_error("event", "10u"), 1e-9);
  EXPECT_LT(worst_error("radau5", "10u"), 1e-7);
  const double euler = worst_error("euler", "10u"), half = worst_error("euler", "5u");
  EXPECT_LT(euler, 4e-4);
  // First order: halving the step halves the error.
  EXPECT_GT(euler / half, 1.6);
  EXPECT_LT(euler / half, 2.4);
}

}  // namespace
}  // namespace lcs::cli_testing
