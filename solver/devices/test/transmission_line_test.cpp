// The line device's recursive convolutions against closed forms of the same fitted kernels
// (line_kernel.h), and the lossless line's bookkeeping (history, DC relations).
//
// A lossy line from rest (UIC), driven at port 1 by an ideal 1 V step and open at port 2:
//   I1 = Yc V1 - H (Yc V2 + I2); before the far end's answer returns (t < 2 tau) the second term
//   is zero, so i1(t) = 1/Z0 + (step response of the fitted Yc - 1/Z0)(t), which
//   RationalFit::step gives in closed form (the direct convolution of the fitted kernel with the
//   step, done exactly);
//   I2 = 0 = Yc V2 - H (2 Yc V1): V2 = 2 H V1, so v2(t) = 2 (step response of the fitted H e^{s tau})(t - tau)
//   for tau < t < 3 tau, 0 before.
// The run carries these convolutions as exponential states (the recursive convolution); the
// event method integrates them exactly, so both agree to rounding.
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "netlist/netlist.h"
#include "solver/devices/transmission_line.h"
#include "solver/integrators/output_sink.h"
#include "solver/integrators/transient.h"
#include "solver/model/circuit_model.h"
#include "solver/model/operating_point.h"

namespace lcs {
namespace {

const char* kLossyStep =
    "lossy line step\n"
    "v1 in 0 dc 1\n"
    "o1 in 0 far 0 cable\n"
    ".model cable ltra(r=0.5 l=250n g=0 c=100p len=10)\n"
    ".tran 1n 140n uic\n"
    ".end\n";

struct Run {
  CircuitModel model;
  MemorySink sink;
  const TransmissionLine* line = nullptr;
};

std::unique_ptr<Run> run(const char* deck, const std::string& method, double step) {
  const Netlist netlist = parse_netlist_string(deck, "line.cir");
  ModelOptions mo;
  mo.t1 = netlist.tran->tstop;
  auto r = std::make_unique<Run>(Run{CircuitModel::build(netlist, mo), {}, nullptr});
  for (const auto& d : r->model.devices())
    if (auto* l = dynamic_cast<const TransmissionLine*>(d.get())) r->line = l;
  TransientOptions o;
  o.method = method;
  o.step = step;
  o.tstop = netlist.tran->tstop;
  o.uic = true;
  std::vector<Probe> probes = {parse_probe("i(o1)", {}), parse_probe("v(far)", {})};
  run_transient(r->model, r->model.output_map(probes), o, r->sink);
  return r;
}

TEST(TransmissionLine, LossyRecursiveConvolutionIsTheFittedKernelsClosedForm) {
  for (const std::string method : {"event", "radau5"}) {
    SCOPED_TRACE(method);
    const auto r = run(kLossyStep, method, method == "event" ? 1e-9 : 0.25e-9);
    ASSERT_NE(r->line, nullptr);
    ASSERT_TRUE(r->line->lossy());
    const LineKernel& k = *r->line->kernel();
    const double tau = k.delay, z0 = k.z0;
    ASSERT_NEAR(tau, 50e-9, 1e-15);
    ASSERT_FALSE(k.admittance.poles.empty());
    ASSERT_FALSE(k.propagation.poles.empty());
    // Event: to rounding of the states' exponentials (1e-9 of the levels); radau5 at 0.25 ns:
    // its error on the fastest fitted poles (|p| h up to ~2), measured 2e-4 of the levels.
    const double tol = method == "event" ? 1e-9 : 1e-3;
    int checked_i = 0, checked_v = 0;
    for (size_t row = 0; row < r->sink.times.size(); ++row) {
      const double t = r->sink.times[row];
      if (t > 0 && t < 2 * tau - 1e-12) {
        const double expected = 1 / z0 + k.admittance.step(t);
        EXPECT_NEAR(r->sink.rows[row](0), expected, tol / z0) << "i(o1) at t = " << t;
        ++checked_i;
      }
      if (t > 0 && t < 3 * tau - 1e-12) {
        const double expected = t < tau ? 0.0 : 2 * k.propagation.step(t - tau);
        if (std::abs(t - tau) > 1.5e-9) {  // the wavefront itself: a jump at tau
          EXPECT_NEAR(r->sink.rows[row](1), expected, 2 * tol) << "v(far) at t = " << t;
          ++checked_v;
        }
      }
    }
    EXPECT_GT(checked_i, 90);
    EXPECT_GT(checked_v, 130);
  }
}

// The operating point of a deck whose line `o1` (LTRA parameters `ltra`) joins `in` (1 V) to `far`,
// loaded by `load` ohm: v(far) and the port-1 current.
struct DcLine {
  double v_far, i_port1;
  std::vector<std::string> undetermined;
};
DcLine dc_line(const std::string& ltra, const std::string& load) {
  const Netlist netlist = parse_netlist_string(
      "dc\nv1 in 0 dc 1\no1 in 0 far 0 cable\nrl far 0 " + load + "\n.model cable ltra(" + ltra +
          ")\n.tran 1n 100n\n.end\n",
      "dc.cir");
  ModelOptions mo;
  mo.t1 = 100e-9;
  const CircuitModel m = CircuitModel::build(netlist, mo);
  const OperatingPoint op = solve_operating_point(m, 0.0);
  int port1 = -1;
  for (size_t b = 0; b < m.graph().branches.size(); ++b)
    if (m.graph().branches[b].name == "o1") port1 = static_cast<int>(b);
  const int far = m.graph().node_index("far");
  return {m.evaluate_dc(m.node_voltage(far), op.x, op.z, 0.0),
          m.evaluate_dc(m.branch_current(port1), op.x, op.z, 0.0), op.undetermined};
}

// At DC a lossy line is its series resistance R len (G = 0), whatever the fitted kernel says
// about s -> 0: 1 V through the line into 45 ohm gives 1 / (45 + 5) A.
TEST(TransmissionLine, LossyLineAtDcIsItsSeriesResistance) {
  const DcLine dc = dc_line("r=0.5 l=250n g=0 c=100p len=10", "45");
  EXPECT_NEAR(dc.v_far, 45.0 / 50.0, 1e-9);
  EXPECT_NEAR(dc.i_port1, 1.0 / 50.0, 1e-12);
  EXPECT_TRUE(dc.undetermined.empty());
}

// With G > 0 the DC two-port is cosh/sinh of th = len sqrt(RG): the far end of an open line
// sits at 1 / cosh(th) of the near end.
TEST(TransmissionLine, LeakyLineAtDcIsItsHyperbolicTwoPort) {
  const DcLine dc = dc_line("r=2 l=250n g=0.02 c=100p len=10", "1e12");
  EXPECT_NEAR(dc.v_far, 1 / std::cosh(10 * std::sqrt(2 * 0.02)), 1e-9);
}

// A lossless line between a 50 MHz sine behind 30 ohm and an RC load (the wave bends where the
// run starts and wherever that bend arrives, k TD later, on the steps here): each method's error
// against `event` (exact: self-consistent to 2e-15 between output steps 0.1 and 0.05 ns) falls at
// its order as the step halves, the history between steps being read at that order.
// Measured per halving: euler 1.9, theta 4.0, radau3 7.8, radau5 52.
TEST(TransmissionLine, TimeSteppingMethodsKeepTheirOrderOnALine) {
  const char* deck =
      "line convergence\nv1 src 0 sin(0 1 50meg)\nrs src in 30\nt1 in 0 out 0 z0=50 td=3.2n\n"
      "rl out 0 120\ncl out 0 20p\n.tran 0.1n 60n uic\n.end\n";
  auto series = [&](const std::string& method, double step) {
    const Netlist netlist = parse_netlist_string(deck, "conv.cir");
    ModelOptions mo;
    mo.t1 = 60e-9;
    const CircuitModel model = CircuitModel::build(netlist, mo);
    TransientOptions o;
    o.method = method;
    o.step = step;
    o.tstop = 60e-9;
    o.uic = true;
    MemorySink sink;
    run_transient(model, model.output_map({parse_probe("v(out)", {})}), o, sink);
    std::map<long, double> out;  // by time in units of 0.05 ns (every method's rows share them)
    for (size_t k = 0; k < sink.times.size(); ++k) {
      const double units = sink.times[k] / 0.05e-9;
      if (std::abs(units - std::round(units)) < 1e-6) out[std::lround(units)] = sink.rows[k](0);
    }
    return out;
  };
  const std::map<long, double> ref = series("event", 0.05e-9);
  auto error = [&](const std::string& method, double step) {
    double e = 0;
    for (const auto& [k, v] : series(method, step)) e = std::max(e, std::abs(v - ref.at(k)));
    return e;
  };
  const struct { const char* method; double least_ratio; } cases[] = {
      {"euler", 1.7}, {"theta", 3.5}, {"radau3", 6.5}, {"radau5", 25}};
  for (const auto& c : cases) {
    SCOPED_TRACE(c.method);
    const double e1 = error(c.method, 0.2e-9), e2 = error(c.method, 0.1e-9), e3 = error(c.method, 0.05e-9);
    EXPECT_GT(e1 / e2, c.least_ratio) << e1 << " " << e2;
    EXPECT_GT(e2 / e3, c.least_ratio) << e2 << " " << e3;
  }
}

// A line at rest in DC between a capacitor behind 50 ohm and an open end: both ends reflect
// almost fully at high frequency, so anything the history polynomials leave behind (a jump at
// each step) travels back and forth for the whole run. It must stay at its DC values to rounding
// and the event method take its usual steps (the first version doubled its rounding noise every
// few round trips and then halved its steps to exhaustion: 106 000 steps for these 80 ns).
TEST(TransmissionLine, EventHistoryLeavesNoNoiseOnAResonantLine) {
  const Netlist netlist = parse_netlist_string(
      "resonant\nv1 s 0 dc 1\nrs s a 50\nt1 a 0 b 0 z0=300 td=0.3n\nc0 a 0 10n\n.tran 1n 80n\n.end\n",
      "resonant.cir");
  ModelOptions mo;
  mo.t1 = 80e-9;
  const CircuitModel model = CircuitModel::build(netlist, mo);
  TransientOptions o;
  o.method = "event";
  o.step = 1e-9;
  o.tstop = 80e-9;
  MemorySink sink;
  const TransientSummary summary =
      run_transient(model, model.output_map({parse_probe("v(a)", {}), parse_probe("v(b)", {})}), o, sink);
  ASSERT_EQ(sink.times.size(), 81u);
  for (size_t k = 0; k < sink.times.size(); ++k) {
    EXPECT_NEAR(sink.rows[k](0), 1.0, 1e-12) << "v(a) at t = " << sink.times[k];
    EXPECT_NEAR(sink.rows[k](1), 1.0, 1e-12) << "v(b) at t = " << sink.times[k];
  }
  EXPECT_LT(summary.stepper.steps, 2000);  // 320 steps of the delay's dyadic cap, and some
}

}  // namespace
}  // namespace lcs
