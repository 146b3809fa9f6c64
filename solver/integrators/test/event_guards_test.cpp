// The event method's switch guards (SwitchGuards, RunSegment): a segment ends where a guard,
// a linear output of the circuit against a threshold, falls below zero, located like a mode
// change; a guard below zero at the start ends the segment there, before any row.
#include <cmath>
#include <optional>

#include <gtest/gtest.h>

#include "netlist/netlist.h"
#include "solver/integrators/event_driven.h"
#include "solver/model/circuit_model.h"

namespace lcs {
namespace {

// C1 = 1 uF charged from 1 V through R1 = 1 k (tau = 1 ms), and a diode D1 that conducts only
// above 2 V (never here): v(c) = 1 - exp(-t / tau).
const char* const kRc = R"(rc with an idle diode
V1 in 0 DC 1
R1 in c 1k
C1 c 0 1u
D1 c 0 dclamp
.model dclamp D(VON=2 RON=1)
.tran 10u 3m
.end
)";

struct Fixture {
  Netlist netlist = parse_netlist_string(kRc, "rc.cir");
  CircuitModel model = CircuitModel::build(netlist, {});
  OutputGrid grid;

  Fixture() {
    grid.tstep = 10e-6;
    grid.tstop = 3e-3;
  }
  // Guard: sign * (v(c) - threshold).
  SwitchGuards guard(double threshold, double sign) const {
    const OutputMap o = model.output_map({parse_probe("v(c)", {})});
    const Eigen::Index inputs = model.lcs().inputs();
    SwitchGuards g;
    g.G = Eigen::MatrixXd(o.G);
    g.H = Eigen::MatrixXd(o.H);
    g.J = o.J.rows() == 1 && o.J.cols() == inputs ? o.J : Eigen::MatrixXd::Zero(1, inputs);
    g.K = o.K.rows() == 1 && o.K.cols() == inputs ? o.K : Eigen::MatrixXd::Zero(1, inputs);
    g.threshold = Eigen::VectorXd::Constant(1, threshold);
    g.sign = Eigen::VectorXd::Constant(1, sign);
    return g;
  }
};

TEST(EventGuards, SegmentEndsWhereTheGuardCrossesItsThreshold) {
  Fixture f;
  EventDriven method(f.model, EventOptions{});
  method.set_guards(f.guard(0.5, -1.0));  // 0.5 - v(c) >= 0 while "off"
  SegmentStart start;
  start.x = Eigen::VectorXd::Zero(f.model.lcs().states());
  double last_row = -1;
  const std::optional<GuardCrossing> c =
      method.RunSegment(start, f.grid, [&](double t, const Eigen::VectorXd&, const Eigen::VectorXd&, bool) {
        last_row = t;
      });
  ASSERT_TRUE(c.has_value());
  const double t_half = 1e-3 * std::log(2.0);
  // Located to the bisection bracket (2^-43 of the 10 us step) past a 1e-12 V overshoot of the
  // control (2e-15 s at its slope of 0.5 V/ms).
  EXPECT_NEAR(c->at.t, t_half, 1e-14);
  EXPECT_EQ(c->crossed, std::vector<int>{0});
  // The state there: past the threshold by 1e-12 of the guard's terms (|v(c)| + |threshold|,
  // about 1 V) and by at most the bracket's change (5.7e-18 V), never before it.
  const double v = f.model.output_map({parse_probe("v(c)", {})}).G.toDense().row(0).dot(c->at.x);
  EXPECT_GT(v - 0.5, 1e-12);
  EXPECT_LT(v - 0.5, 1.001e-12);
  EXPECT_LT(last_row, t_half);  // no row at or past the crossing: the next configuration writes it
  EXPECT_NEAR(c->at.at.seconds(f.grid.tstep), c->at.t, 0.0);
}

TEST(EventGuards, GuardBelowZeroAtTheStartEndsTheSegmentThere) {
  Fixture f;
  EventDriven method(f.model, EventOptions{});
  method.set_guards(f.guard(0.6, 1.0));  // v(c) - 0.6 >= 0 while "on"; v(c) starts at 0.5
  SegmentStart start;
  start.x = Eigen::VectorXd::Constant(f.model.lcs().states(), 0.5);
  start.t = 0.25e-3;
  start.at = DyadicTime::from(start.t, f.grid.tstep);
  int rows = 0;
  const std::optional<GuardCrossing> c = method.RunSegment(
      start, f.grid, [&](double, const Eigen::VectorXd&, const Eigen::VectorXd&, bool) { ++rows; });
  ASSERT_TRUE(c.has_value());
  EXPECT_EQ(c->at.t, start.t);
  EXPECT_EQ(rows, 0);
}

// Without a crossing the segment runs to TSTOP from its start, rows on the grid after it.
TEST(EventGuards, SegmentFromAMidStepStartRunsToTheEnd) {
  Fixture f;
  EventDriven method(f.model, EventOptions{});
  method.set_guards(f.guard(2.0, -1.0));  // never reached
  SegmentStart start;
  start.t = 0.255e-3;  // between grid times
  start.at = DyadicTime::from(start.t, f.grid.tstep);
  start.x = Eigen::VectorXd::Constant(f.model.lcs().states(), 1 - std::exp(-0.255));
  std::vector<double> times, values;
  const OutputMap o = f.model.output_map({parse_probe("v(c)", {})});
  const std::optional<GuardCrossing> c = method.RunSegment(
      start, f.grid, [&](double t, const Eigen::VectorXd& x, const Eigen::VectorXd&, bool) {
        times.push_back(t);
        values.push_back(o.G.toDense().row(0).dot(x));
      });
  EXPECT_FALSE(c.has_value());
  ASSERT_GE(times.size(), 2u);
  EXPECT_EQ(times.front(), start.t);
  EXPECT_NEAR(times[1], 0.26e-3, 1e-18);
  EXPECT_NEAR(times.back(), 3e-3, 1e-18);
  EXPECT_EQ(times.size(), 1u + 275u);  // the start, then 0.26 ms ... 3 ms
  for (size_t k = 0; k < times.size(); ++k) EXPECT_NEAR(values[k], 1 - std::exp(-times[k] / 1e-3), 1e-13) << times[k];
}

}  // namespace
}  // namespace lcs
