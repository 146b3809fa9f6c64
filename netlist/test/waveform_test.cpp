// Waveform semantics against hand-computed values.
#include "netlist/waveform.h"

#include <cmath>

#include <gtest/gtest.h>

namespace lcs {
namespace {

constexpr double kPi = 3.14159265358979323846;

Waveform make(Waveform::Kind kind, std::vector<double> params, double tstep = 0, double tstop = 0) {
  Waveform w;
  w.kind = kind;
  w.params = std::move(params);
  w.resolve(tstep, tstop);
  return w;
}

void expect_times(const std::vector<double>& got, const std::vector<double>& want) {
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t i = 0; i < got.size(); ++i) EXPECT_NEAR(got[i], want[i], 1e-15) << "breakpoint " << i;
}

TEST(WaveformDc, ConstantEverywhere) {
  Waveform w;
  w.dc = 5;
  w.resolve(1e-3, 1);
  EXPECT_EQ(w.value(0), 5);
  EXPECT_EQ(w.value(123.0), 5);
  EXPECT_EQ(w.derivative(0.5), 0);
  EXPECT_EQ(w.range(0, 10), std::make_pair(5.0, 5.0));
  EXPECT_TRUE(w.breakpoints(0, 10).empty());
  EXPECT_EQ(w.describe(), "DC 5");
}

TEST(WaveformSin, DefaultsFromTran) {
  Waveform w = make(Waveform::Kind::Sin, {0, 1}, 1e-3, 0.5);
  ASSERT_EQ(w.params.size(), 6u);
  EXPECT_EQ(w.params[2], 2.0);  // FREQ = 1/TSTOP
  EXPECT_EQ(w.params[3], 0.0);
  EXPECT_EQ(w.params[4], 0.0);
  EXPECT_EQ(w.params[5], 0.0);
  EXPECT_TRUE(w.resolved);
  // resolve() is idempotent.
  w.resolve(1, 100);
  EXPECT_EQ(w.params[2], 2.0);
}

// A written FREQ of 0 is ngspice's default too (vsrcload.c: FREQ = 1/TSTOP when 0), again after
// a reresolve() for another TSTOP.
TEST(WaveformSin, ZeroFrequencyIsTheDefault) {
  Waveform w = make(Waveform::Kind::Sin, {0, 1, 0}, 1e-3, 0.5);
  EXPECT_EQ(w.params[2], 2.0);
  EXPECT_NEAR(w.value(0.125), 1.0, 1e-12);
  w.reresolve(1e-3, 0.25);
  EXPECT_EQ(w.params[2], 4.0);
}

TEST(WaveformSin, PlainSine) {
  Waveform w = make(Waveform::Kind::Sin, {0, 10, 50}, 1e-4, 0.1);
  EXPECT_NEAR(w.value(0), 0.0, 1e-12);
  EXPECT_NEAR(w.value(0.005), 10.0, 1e-12);
  EXPECT_NEAR(w.value(0.0025), 10 * std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(w.value(0.015), -10.0, 1e-12);
  EXPECT_NEAR(w.value(-1.0), 0.0, 1e-12);  // t < 0 is t = 0
  EXPECT_NEAR(w.derivative(0), 10 * 2 * kPi * 50, 1e-9);
  EXPECT_NEAR(w.derivative(0.005), 0.0, 1e-9);
  EXPECT_TRUE(w.breakpoints(0, 1).empty());
  EXPECT_EQ(w.describe(), "SIN(0 10 50)");
}

TEST(WaveformSin, DelayDampingPhase) {
  // SIN(VO=1 VA=2 FREQ=100 TD=1m THETA=100 PHASE=90)
  Waveform w = make(Waveform::Kind::Sin, {1, 2, 100, 1e-3, 100, 90});
  EXPECT_NEAR(w.value(0), 3.0, 1e-12);       // before TD: VO + VA sin(PHASE)
  EXPECT_NEAR(w.value(0.5e-3), 3.0, 1e-12);
  EXPECT_NEAR(w.value(1e-3), 3.0, 1e-12);
  // tau = 5 ms: sin(pi + pi/2) = -1, damping e^{-0.5}
  EXPECT_NEAR(w.value(6e-3), 1 - 2 * std::exp(-0.5), 1e-12);
  EXPECT_NEAR(w.value(6e-3), -0.21306131942526685, 1e-12);
  EXPECT_EQ(w.derivative(0.5e-3), 0.0);
  // Right derivative at TD: VA (w cos(pi/2) - theta sin(pi/2)) = -200
  EXPECT_NEAR(w.derivative(1e-3), -200.0, 1e-9);
  expect_times(w.breakpoints(0, 1), {1e-3});
  EXPECT_TRUE(w.breakpoints(1e-3, 1).empty());  // strictly inside
  EXPECT_EQ(w.describe(), "SIN(1 2 100 0.001 100 90)");
}

TEST(WaveformSin, RangeIsExactOverShortIntervals) {
  Waveform w = make(Waveform::Kind::Sin, {0, 10, 50});
  auto r = w.range(0, 1);
  EXPECT_NEAR(r.first, -10, 1e-9);
  EXPECT_NEAR(r.second, 10, 1e-9);
  r = w.range(0, 0.001);  // quarter of a radian-ish: monotone rising
  EXPECT_NEAR(r.first, 0, 1e-12);
  EXPECT_NEAR(r.second, 10 * std::sin(0.1 * kPi), 1e-12);
  r = w.range(0.004, 0.006);  // peak at 5 ms inside
  EXPECT_NEAR(r.first, 10 * std::sin(0.4 * kPi), 1e-12);
  EXPECT_NEAR(r.second, 10, 1e-12);
}

TEST(WaveformSin, RangeOfDampedSineFindsFirstPeak) {
  Waveform w = make(Waveform::Kind::Sin, {0, 1, 1, 0, 1});
  double tau = std::atan(2 * kPi) / (2 * kPi);
  double peak = std::exp(-tau) * std::sin(std::atan(2 * kPi));
  double trough_tau = tau + 0.5;
  double trough = -std::exp(-trough_tau) * std::sin(std::atan(2 * kPi));
  auto r = w.range(0, 10);
  EXPECT_NEAR(r.second, peak, 1e-12);
  EXPECT_NEAR(r.first, trough, 1e-12);
  EXPECT_LT(r.second, 1.0);
}

TEST(WaveformSin, RangeBeforeDelay) {
  Waveform w = make(Waveform::Kind::Sin, {2, 1, 10, 1.0, 0, 30});
  auto r = w.range(0, 0.5);
  EXPECT_NEAR(r.first, 2.5, 1e-12);
  EXPECT_NEAR(r.second, 2.5, 1e-12);
}

// LTspice's NCYCLES: SIN(1 2 1k TD=1m THETA=0 PHASE=30 NCYCLES=2.5) stops at TE = 3.5 ms and
// holds 1 + 2 sin(2.5 * 360 + 30 deg) = 1 + 2 sin(210 deg) = 0; with THETA = 100 the held value
// carries the envelope at TE, e^{-0.25}.
TEST(WaveformSin, NcyclesStopsAndHoldsTheLastValue) {
  Waveform w = make(Waveform::Kind::Sin, {1, 2, 1e3, 1e-3, 0, 30, 2.5});
  ASSERT_EQ(w.params.size(), 7u);
  EXPECT_EQ(w.sine_end(), 3.5e-3);
  EXPECT_NEAR(w.value(0), 2.0, 1e-12);  // before TD: VO + VA sin(PHASE)
  EXPECT_NEAR(w.value(1.25e-3), 1 + 2 * std::sin(kPi / 2 + kPi / 6), 1e-12);
  EXPECT_NEAR(w.value(3.25e-3), 1 + 2 * std::sin(kPi / 2 + kPi / 6), 1e-12);  // the last half-cycle
  for (double t : {3.5e-3, 3.75e-3, 10.0}) {
    EXPECT_NEAR(w.value(t), 0.0, 1e-12) << t;
    EXPECT_EQ(w.derivative(t), 0.0) << t;
  }
  EXPECT_NEAR(w.derivative(3.4e-3), 2 * 2 * kPi * 1e3 * std::cos(2 * kPi * 2.4 + kPi / 6), 1e-6);
  expect_times(w.breakpoints(0, 1), {1e-3, 3.5e-3});
  auto r = w.range(3.6e-3, 1);
  EXPECT_NEAR(r.first, 0.0, 1e-12);
  EXPECT_NEAR(r.second, 0.0, 1e-12);
  r = w.range(3e-3, 1);  // the phase runs from 30 to 210 deg: through the peak (3), down to the held 0
  EXPECT_NEAR(r.first, 0.0, 1e-12);
  EXPECT_NEAR(r.second, 3.0, 1e-12);
  EXPECT_EQ(w.describe(), "SIN(1 2 1000 0.001 0 30 2.5)");
  Waveform damped = make(Waveform::Kind::Sin, {0, 1, 1e3, 0, 100, 90, 2.5});
  EXPECT_NEAR(damped.value(1.0), std::exp(-0.25) * std::sin(5 * kPi + kPi / 2), 1e-12);
  // 0 (LTspice's default): no end.
  Waveform endless = make(Waveform::Kind::Sin, {0, 1, 1e3, 0, 0, 0, 0});
  EXPECT_TRUE(std::isinf(endless.sine_end()));
  EXPECT_NEAR(endless.value(10.25e-3), 1.0, 1e-9);
}

TEST(WaveformPulse, Defaults) {
  Waveform w = make(Waveform::Kind::Pulse, {0, 5}, 1e-3, 1);
  EXPECT_EQ(w.params, (std::vector<double>{0, 5, 0, 1e-3, 1e-3, 1, 1}));
  EXPECT_EQ(w.describe(), "PULSE(0 5 0 0.001 0.001 1 1)");
  Waveform p = make(Waveform::Kind::Pulse, {0, 5, 2e-3}, 1e-3, 1);
  EXPECT_EQ(p.params, (std::vector<double>{0, 5, 2e-3, 1e-3, 1e-3, 1, 1}));
}

// PULSE(V1=0 V2=5 TD=1m TR=1m TF=2m PW=3m PER=10m)
Waveform trapezoid() { return make(Waveform::Kind::Pulse, {0, 5, 1e-3, 1e-3, 2e-3, 3e-3, 10e-3}); }

TEST(WaveformPulse, ValuesOverTwoPeriods) {
  Waveform w = trapezoid();
  EXPECT_EQ(w.value(0), 0);
  EXPECT_EQ(w.value(1e-3), 0);
  EXPECT_NEAR(w.value(1.5e-3), 2.5, 1e-12);
  EXPECT_NEAR(w.value(2e-3), 5, 1e-12);
  EXPECT_NEAR(w.value(4e-3), 5, 1e-12);
  EXPECT_NEAR(w.value(5e-3), 5, 1e-12);
  EXPECT_NEAR(w.value(6e-3), 2.5, 1e-12);
  EXPECT_NEAR(w.value(7e-3), 0, 1e-12);
  EXPECT_NEAR(w.value(10e-3), 0, 1e-12);
  EXPECT_NEAR(w.value(11e-3), 0, 1e-12);
  EXPECT_NEAR(w.value(11.5e-3), 2.5, 1e-9);
  EXPECT_NEAR(w.value(16e-3), 2.5, 1e-9);
  EXPECT_NEAR(w.value(1001.5e-3), 2.5, 1e-9);  // period 100
}

TEST(WaveformPulse, RightDerivativeAtCorners) {
  Waveform w = trapezoid();
  EXPECT_EQ(w.derivative(0.5e-3), 0);
  EXPECT_NEAR(w.derivative(1e-3), 5000, 1e-6);   // start of rise
  EXPECT_NEAR(w.derivative(1.5e-3), 5000, 1e-6);
  EXPECT_NEAR(w.derivative(2e-3), 0, 1e-6);      // top
  EXPECT_NEAR(w.derivative(5e-3), -2500, 1e-6);  // start of fall
  EXPECT_NEAR(w.derivative(7e-3), 0, 1e-6);      // bottom
  EXPECT_NEAR(w.derivative(11e-3), 5000, 1e-6);  // next period
}

TEST(WaveformPulse, BreakpointsStrictlyInside) {
  Waveform w = trapezoid();
  expect_times(w.breakpoints(0, 12e-3), {1e-3, 2e-3, 5e-3, 7e-3, 11e-3});
  expect_times(w.breakpoints(2e-3, 13e-3), {5e-3, 7e-3, 11e-3, 12e-3});
  expect_times(w.breakpoints(0, 0.5e-3), {});
}

// A fuzz finding: with TD = 1.1e300 s no period starts before TSTOP, and the count of periods
// (negative, -5e306) was cast to an integer (UB; the sanitized suite reports it).
TEST(WaveformPulse, NoBreakpointsWhenTheDelayIsBeyondTheInterval) {
  Waveform w = make(Waveform::Kind::Pulse, {0, 1, 1.1e300, 1e-11, 1e-11, 1e-7, 2e-7});
  expect_times(w.breakpoints(0, 16e-9), {});
  EXPECT_EQ(w.value(16e-9), 0);
}

TEST(WaveformPulse, ExactRange) {
  Waveform w = trapezoid();
  auto r = w.range(1.5e-3, 1.8e-3);
  EXPECT_NEAR(r.first, 2.5, 1e-12);
  EXPECT_NEAR(r.second, 4.0, 1e-12);
  r = w.range(6e-3, 6.5e-3);
  EXPECT_NEAR(r.first, 1.25, 1e-12);
  EXPECT_NEAR(r.second, 2.5, 1e-12);
  r = w.range(0, 100e-3);
  EXPECT_EQ(r.first, 0);
  EXPECT_EQ(r.second, 5);
  r = w.range(0, 0.9e-3);  // before TD
  EXPECT_EQ(r.first, 0);
  EXPECT_EQ(r.second, 0);
  r = w.range(9e-3, 11.5e-3);  // across a period boundary
  EXPECT_NEAR(r.first, 0, 1e-12);
  EXPECT_NEAR(r.second, 2.5, 1e-9);
}

TEST(WaveformPulse, ZeroEdgesAreRightContinuousJumps) {
  // PULSE(0 1 0 0 0 1 2): square wave, high on [0,1), low on [1,2)
  Waveform w = make(Waveform::Kind::Pulse, {0, 1, 0, 0, 0, 1, 2}, 1e-3, 10);
  EXPECT_EQ(w.value(0), 1);
  EXPECT_EQ(w.value(0.5), 1);
  EXPECT_EQ(w.value(1), 0);
  EXPECT_EQ(w.value(1.5), 0);
  EXPECT_EQ(w.value(2), 1);
  EXPECT_EQ(w.value(3), 0);
  EXPECT_EQ(w.derivative(1), 0);
  EXPECT_EQ(w.value_before(0), 0);  // before TD = 0: V1
  EXPECT_EQ(w.value_before(1), 1);
  EXPECT_EQ(w.value_before(2), 0);  // end of the first period
  EXPECT_EQ(w.value_before(3), 1);
  EXPECT_EQ(w.value_before(0.5), 1);
  expect_times(w.breakpoints(0, 4), {1, 2, 3});
  auto r = w.range(0.2, 0.8);
  EXPECT_EQ(r.first, 1);
  EXPECT_EQ(r.second, 1);
  r = w.range(0.2, 1.0);  // includes the fall at 1
  EXPECT_EQ(r.first, 0);
  EXPECT_EQ(r.second, 1);
}

TEST(WaveformPulse, CornersLandExactlyDespiteRounding) {
  // PER = 0.1 is not representable: 3 * 0.1 != 0.3. Values at breakpoints are the right values.
  Waveform w = make(Waveform::Kind::Pulse, {0, 1, 0, 0, 0, 0.05, 0.1});
  EXPECT_EQ(w.value(0.3), 1);
  EXPECT_EQ(w.value(0.35), 0);
  EXPECT_EQ(w.value(0.7), 1);
  for (double t : w.breakpoints(0, 1)) {
    double phase = std::fmod(t + 1e-9, 0.1);
    EXPECT_EQ(w.value(t), phase < 0.05 ? 1 : 0) << "t = " << t;
    EXPECT_EQ(w.value_before(t), phase < 0.05 ? 0 : 1) << "t = " << t;
  }
  EXPECT_EQ(w.breakpoints(0, 1).size(), 19u);
}

TEST(WaveformPulse, PeriodShorterThanShapeCutsIt) {
  // TR=1 PW=5 TF=1 but PER=4: rise, then high until the period restarts
  Waveform w = make(Waveform::Kind::Pulse, {0, 1, 0, 1, 1, 5, 4});
  EXPECT_NEAR(w.value(0.5), 0.5, 1e-12);
  EXPECT_EQ(w.value(3.9), 1);
  EXPECT_EQ(w.value(4), 0);
  EXPECT_NEAR(w.value(4.5), 0.5, 1e-12);
  expect_times(w.breakpoints(0, 9), {1, 4, 5, 8});
  auto r = w.range(2, 3);
  EXPECT_EQ(r.first, 1);
  EXPECT_EQ(r.second, 1);
}

TEST(WaveformPulse, SinglePulseWithoutPeriod) {
  // No .tran: PW = PER = 0 and TR = TF = 0 by default; explicit PW makes one pulse.
  Waveform w = make(Waveform::Kind::Pulse, {1, 2, 1, 1, 1, 1, 0});
  EXPECT_EQ(w.value(0), 1);
  EXPECT_NEAR(w.value(1.5), 1.5, 1e-12);
  EXPECT_EQ(w.value(2.5), 2);
  EXPECT_NEAR(w.value(3.5), 1.5, 1e-12);
  EXPECT_EQ(w.value(100), 1);
  expect_times(w.breakpoints(0, 100), {1, 2, 3, 4});
}

// NP = 2 (ngspice 39, LTspice's Ncycles): the trapezoid twice, then V1 from TD + 2 PER = 21 ms.
TEST(WaveformPulse, CountOfPulsesEndsTheTrain) {
  Waveform w = make(Waveform::Kind::Pulse, {0, 5, 1e-3, 1e-3, 2e-3, 3e-3, 10e-3, 2});
  EXPECT_NEAR(w.value(11.5e-3), 2.5, 1e-9);  // the second pulse
  EXPECT_EQ(w.value(21e-3), 0);
  EXPECT_EQ(w.value(21.5e-3), 0);          // where a third would rise
  EXPECT_EQ(w.value(1.0), 0);
  EXPECT_EQ(w.derivative(21e-3), 0);
  EXPECT_EQ(w.derivative(21.5e-3), 0);
  expect_times(w.breakpoints(0, 40e-3), {1e-3, 2e-3, 5e-3, 7e-3, 11e-3, 12e-3, 15e-3, 17e-3, 21e-3});
  auto r = w.range(20e-3, 40e-3);
  EXPECT_EQ(r.first, 0);
  EXPECT_EQ(r.second, 0);
  r = w.range(11.5e-3, 40e-3);
  EXPECT_EQ(r.first, 0);
  EXPECT_EQ(r.second, 5);
  // A shape longer than the period is cut at 21 ms like any period end: the last one falls there.
  Waveform cut = make(Waveform::Kind::Pulse, {0, 5, 0, 0, 0, 10e-3, 10e-3, 1});
  EXPECT_EQ(cut.value(9.99e-3), 5);
  EXPECT_EQ(cut.value_before(10e-3), 5);
  EXPECT_EQ(cut.value(10e-3), 0);
  EXPECT_EQ(cut.value(10.01e-3), 0);
  // 0 (or no NP): the train does not end.
  Waveform endless = make(Waveform::Kind::Pulse, {0, 5, 1e-3, 1e-3, 2e-3, 3e-3, 10e-3, 0});
  EXPECT_NEAR(endless.value(21.5e-3), 2.5, 1e-9);
}

TEST(WaveformPulse, AbsurdPeriodsStayBoundedAndFinite) {
  Waveform tiny = make(Waveform::Kind::Pulse, {0, 1, 0, 0, 0, 1e-300, 2e-300});
  EXPECT_TRUE(tiny.breakpoints(0.5, 1).size() <= 10'000'000u);
  EXPECT_TRUE(std::isfinite(tiny.value(0.75)));
  Waveform denormal = make(Waveform::Kind::Pulse, {0, 1, 0, 0, 0, 1e-320, 2e-320});
  EXPECT_TRUE(std::isfinite(denormal.value(1.0)));
  EXPECT_TRUE(std::isfinite(denormal.derivative(1.0)));
  auto r = denormal.range(0, 1);
  EXPECT_TRUE(std::isfinite(r.first) && std::isfinite(r.second));
}

TEST(WaveformPwl, ValuesJumpsAndEnds) {
  // PWL(0 0 1 1 1 3 2 3 3 0): ramp, jump to 3 at t=1, flat, ramp down
  Waveform w = make(Waveform::Kind::Pwl, {0, 0, 1, 1, 1, 3, 2, 3, 3, 0});
  EXPECT_EQ(w.value(-1), 0);
  EXPECT_EQ(w.value(0.5), 0.5);
  EXPECT_EQ(w.value(1), 3);
  EXPECT_EQ(w.value_before(1), 1);
  EXPECT_EQ(w.value_before(2.5), 1.5);
  EXPECT_EQ(w.value(1.5), 3);
  EXPECT_EQ(w.value(2.5), 1.5);
  EXPECT_EQ(w.value(3), 0);
  EXPECT_EQ(w.value(10), 0);
  EXPECT_EQ(w.derivative(0.5), 1);
  EXPECT_EQ(w.derivative(1), 0);
  EXPECT_EQ(w.derivative(2), -3);
  EXPECT_EQ(w.derivative(2.5), -3);
  EXPECT_EQ(w.derivative(3), 0);
  expect_times(w.breakpoints(0, 3), {1, 2});
  auto r = w.range(0.5, 2.5);
  EXPECT_EQ(r.first, 0.5);
  EXPECT_EQ(r.second, 3);
  r = w.range(0.2, 0.6);
  EXPECT_DOUBLE_EQ(r.first, 0.2);
  EXPECT_DOUBLE_EQ(r.second, 0.6);
  EXPECT_EQ(w.describe(), "PWL(0 0 1 1 1 3 2 3 3 0)");
}

// PWL(0 0 1 2 3 0 4 1) r=1 (ngspice): as written to t = 4, then the stretch from t = 1 to 4
// (period 3) again and again: 2 at 4+ (a jump from 1), 0 at 6, 1 at 7-, 2 at 7.
TEST(WaveformPwl, RepeatFromATimePoint) {
  Waveform w = make(Waveform::Kind::Pwl, {0, 0, 1, 2, 3, 0, 4, 1});
  w.repeat_from = 1;
  EXPECT_DOUBLE_EQ(w.value(0.5), 1);
  EXPECT_DOUBLE_EQ(w.value(3.5), 0.5);
  EXPECT_DOUBLE_EQ(w.value_before(4), 1);
  EXPECT_DOUBLE_EQ(w.value(4), 2);
  EXPECT_DOUBLE_EQ(w.value(5), 1);
  EXPECT_DOUBLE_EQ(w.value(6), 0);
  EXPECT_DOUBLE_EQ(w.value(6.5), 0.5);
  EXPECT_DOUBLE_EQ(w.value_before(7), 1);
  EXPECT_DOUBLE_EQ(w.value(7), 2);
  EXPECT_NEAR(w.value(3001 + 0.5), 1.5, 1e-9);  // 1000 periods on
  EXPECT_DOUBLE_EQ(w.derivative(4.5), -1);
  EXPECT_DOUBLE_EQ(w.derivative(6), 1);
  expect_times(w.breakpoints(0, 8), {1, 3, 4, 6, 7});
  auto r = w.range(4.5, 5.5);
  EXPECT_DOUBLE_EQ(r.first, 0.5);
  EXPECT_DOUBLE_EQ(r.second, 1.5);
  r = w.range(3.5, 100);
  EXPECT_DOUBLE_EQ(r.first, 0);
  EXPECT_DOUBLE_EQ(r.second, 2);
  EXPECT_EQ(w.describe(), "PWL(0 0 1 2 3 0 4 1) r=1");
}

// NP = 2.5 ends the train mid-period (at 20 s, in the third pulse's top): V1 at the end is in
// the range that reaches it.
TEST(WaveformPulse, RangeToTheEndOfAFractionalTrainHasV1) {
  Waveform w = make(Waveform::Kind::Pulse, {0, 5, 0, 1, 2, 10, 8, 2.5});
  EXPECT_EQ(w.value(19), 5);
  EXPECT_EQ(w.value(20), 0);
  EXPECT_EQ(w.value_before(20), 5);
  const auto r = w.range(19, 20);
  EXPECT_EQ(r.first, 0);
  EXPECT_EQ(r.second, 5);
}

TEST(WaveformPwl, ConstantBeforeFirstPoint) {
  Waveform w = make(Waveform::Kind::Pwl, {1, 2, 3, 4});
  EXPECT_EQ(w.value(0), 2);
  EXPECT_EQ(w.value(2), 3);
  EXPECT_EQ(w.value(7), 4);
  EXPECT_EQ(w.derivative(0), 0);
  EXPECT_EQ(w.derivative(1), 1);
  auto r = w.range(0, 0.5);
  EXPECT_EQ(r.first, 2);
  EXPECT_EQ(r.second, 2);
}

TEST(WaveformDescribe, DcWithTransientFunction) {
  Waveform w = make(Waveform::Kind::Sin, {0, 10, 50});
  w.dc = 1;
  EXPECT_EQ(w.describe(), "DC 1 SIN(0 10 50)");
}

TEST(WaveformUnresolved, EvaluatesWithZeroAnalysisDefaults) {
  Waveform w;
  w.kind = Waveform::Kind::Pulse;
  w.params = {0, 1};
  EXPECT_EQ(w.value(0), 0);  // zero-length pulse: back to V1 at once
  EXPECT_FALSE(w.resolved);
}

}  // namespace
}  // namespace lcs

namespace lcs {
namespace {

TEST(WaveformReresolve, DefaultsFollowTheNewAnalysis) {
  Waveform w;
  w.kind = Waveform::Kind::Pulse;
  w.params = {0, 1};  // TD TR TF PW PER all defaulted
  w.resolve(0, 0);
  w.reresolve(0.25, 1.0);
  ASSERT_EQ(w.params.size(), 7u);
  EXPECT_EQ(w.params[3], 0.25);  // TR = TSTEP
  EXPECT_EQ(w.params[5], 1.0);   // PW = TSTOP
  EXPECT_DOUBLE_EQ(w.value(0.5), 1.0);
  Waveform s;
  s.kind = Waveform::Kind::Sin;
  s.params = {0, 1};
  s.resolve(0, 0);
  s.reresolve(0.1, 2.0);
  EXPECT_DOUBLE_EQ(s.params[2], 0.5);  // FREQ = 1/TSTOP
}

}  // namespace
}  // namespace lcs

// EXP, SFFM and AM against ngspice's formulas (vsrcload.c, ngspice 40+), written out here
// independently at chosen times.
namespace lcs {
namespace {

TEST(WaveformExp, TwoExponentialsWithCornersAtTd1AndTd2) {
  // EXP(V1=1 V2=3 TD1=0.2m TAU1=0.1m TD2=0.6m TAU2=0.3m)
  Waveform w = make(Waveform::Kind::Exp, {1, 3, 0.2e-3, 0.1e-3, 0.6e-3, 0.3e-3}, 1e-5, 2e-3);
  EXPECT_EQ(w.value(0.1e-3), 1.0);
  EXPECT_NEAR(w.value(0.3328e-3), 1 + 2 * (1 - std::exp(-1.328)), 1e-15);
  const double t = 0.7328e-3;
  EXPECT_NEAR(w.value(t), 1 + 2 * (1 - std::exp(-(t - 0.2e-3) / 0.1e-3)) - 2 * (1 - std::exp(-(t - 0.6e-3) / 0.3e-3)),
              1e-15);
  // Slope: (V2-V1)/TAU1 e^{..} - (V2-V1)/TAU2 e^{..}
  EXPECT_NEAR(w.derivative(t), 2 / 0.1e-3 * std::exp(-5.328) - 2 / 0.3e-3 * std::exp(-(t - 0.6e-3) / 0.3e-3), 1e-6);
  expect_times(w.breakpoints(0, 2e-3), {0.2e-3, 0.6e-3});
  // Continuous at both corners; the range holds every sample and is reached.
  EXPECT_NEAR(w.value_before(0.6e-3), w.value(0.6e-3), 1e-15);
  auto [lo, hi] = w.range(0, 2e-3);
  double seen_lo = 1e9, seen_hi = -1e9;
  for (int i = 0; i <= 2000; ++i) {
    const double v = w.value(i * 1e-6);
    seen_lo = std::min(seen_lo, v), seen_hi = std::max(seen_hi, v);
  }
  EXPECT_LE(lo, seen_lo);
  EXPECT_GE(hi, seen_hi);
  EXPECT_NEAR(hi, seen_hi, 1e-6);  // the interior maximum of the last piece, found exactly
  EXPECT_EQ(w.describe(), "EXP(1 3 0.0002 0.0001 0.0006 0.0003)");
}

TEST(WaveformExp, DefaultsFromTranAndAZeroTimeConstantIsAJump) {
  Waveform d = make(Waveform::Kind::Exp, {0, 5}, 1e-3, 1);
  ASSERT_EQ(d.params.size(), 6u);
  EXPECT_EQ(d.params[2], 0.0);   // TD1
  EXPECT_EQ(d.params[3], 1e-3);  // TAU1 = TSTEP
  EXPECT_EQ(d.params[4], 1e-3);  // TD2 = TD1 + TSTEP
  EXPECT_EQ(d.params[5], 1e-3);  // TAU2 = TSTEP
  Waveform j = make(Waveform::Kind::Exp, {0, 5, 1, 0, 2, 0});
  EXPECT_EQ(j.value_before(1), 0.0);
  EXPECT_EQ(j.value(1), 5.0);
  EXPECT_EQ(j.value(1.5), 5.0);
  EXPECT_EQ(j.value(2), 0.0);
  EXPECT_EQ(j.derivative(1.5), 0.0);
}

TEST(WaveformSffm, SineOfASineAfterTd) {
  // SFFM(VO=0.1 VA=2 FC=200 MDI=45 FS=10k TD=1m PHASEM=20 PHASEC=10): MDI is limited to FC/FS = 0.02.
  Waveform w = make(Waveform::Kind::Sffm, {0.1, 2, 200, 45, 10e3, 1e-3, 20, 10}, 1e-6, 4e-3);
  EXPECT_DOUBLE_EQ(w.params[3], 0.02);
  EXPECT_EQ(w.value(0.5e-3), 0.0);  // 0 before TD
  EXPECT_EQ(w.value_before(1e-3), 0.0);
  for (double t : {1e-3, 1.3e-3, 2.71e-3}) {
    const double tau = t - 1e-3;
    const double want = 0.1 + 2 * std::sin(2 * kPi * 200 * tau + 10 * kPi / 180 +
                                           0.02 * std::sin(2 * kPi * 10e3 * tau + 20 * kPi / 180));
    EXPECT_NEAR(w.value(t), want, 1e-14) << t;
  }
  const double t = 2e-3, h = 1e-9;
  EXPECT_NEAR(w.derivative(t), (w.value(t + h) - w.value(t - h)) / (2 * h), 1e-4);
  expect_times(w.breakpoints(0, 4e-3), {1e-3});
  EXPECT_EQ(w.range(0, 4e-3), std::make_pair(-1.9, 2.1));
  EXPECT_EQ(w.range(0, 0.5e-3), std::make_pair(0.0, 0.0));
}

TEST(WaveformSffm, DefaultsFromTran) {
  Waveform w = make(Waveform::Kind::Sffm, {0, 1}, 1e-3, 0.5);
  ASSERT_EQ(w.params.size(), 8u);
  EXPECT_DOUBLE_EQ(w.params[2], 10.0);    // FC = 5/TSTOP
  EXPECT_DOUBLE_EQ(w.params[4], 1000.0);  // FS = 500/TSTOP
  EXPECT_DOUBLE_EQ(w.params[3], 0.01);    // MDI = 90, limited to FC/FS
}

TEST(WaveformAm, ProductOfSinusoidsAfterTd) {
  // AM(VO=0.5 VMO=2 VMA=1.8 FM=1k FC=100k TD=1m PHASEM=30 PHASEC=45)
  Waveform w = make(Waveform::Kind::Am, {0.5, 2, 1.8, 1e3, 100e3, 1e-3, 30, 45}, 1e-6, 4e-3);
  EXPECT_EQ(w.value(0.999e-3), 0.0);
  for (double t : {1e-3, 1.0123e-3, 3.3e-3}) {
    const double tau = t - 1e-3;
    const double want = 0.5 + (2 + 1.8 * std::sin(2 * kPi * 1e3 * tau + kPi / 6)) * std::sin(2 * kPi * 100e3 * tau + kPi / 4);
    EXPECT_NEAR(w.value(t), want, 1e-13) << t;
  }
  const double t = 2e-3, h = 1e-10;
  EXPECT_NEAR(w.derivative(t), (w.value(t + h) - w.value(t - h)) / (2 * h), 1e-1);  // slopes ~1e6 V/s
  expect_times(w.breakpoints(0, 4e-3), {1e-3});
  EXPECT_EQ(w.range(0, 4e-3), std::make_pair(0.5 - 3.8, 0.5 + 3.8));
  EXPECT_EQ(w.describe(), "AM(0.5 2 1.8 1000 100000 0.001 30 45)");
}

TEST(WaveformAm, DefaultsFromTran) {
  Waveform w = make(Waveform::Kind::Am, {0, 1}, 1e-3, 0.5);
  ASSERT_EQ(w.params.size(), 8u);
  EXPECT_DOUBLE_EQ(w.params[2], 1.0);     // VMA
  EXPECT_DOUBLE_EQ(w.params[3], 10.0);    // FM = 5/TSTOP
  EXPECT_DOUBLE_EQ(w.params[4], 1000.0);  // FC = 500/TSTOP
}

TEST(WaveformScaled, MultipliesLevelsNotTimes) {
  Waveform am;
  am.kind = Waveform::Kind::Am;
  am.params = {0.5, 2};  // VMA defaults to 1 and is scaled too
  Waveform a2 = am.scaled(2);
  a2.resolve(1e-3, 1);
  am.resolve(1e-3, 1);
  for (double t : {0.013, 0.37}) EXPECT_DOUBLE_EQ(a2.value(t), 2 * am.value(t));
  Waveform pwl = make(Waveform::Kind::Pwl, {0, 1, 1, 3});
  EXPECT_DOUBLE_EQ(pwl.scaled(3).value(0.5), 6.0);
  Waveform exp = make(Waveform::Kind::Exp, {1, 3, 0, 0.5, 2, 0.5});
  EXPECT_DOUBLE_EQ(exp.scaled(2).value(0.7), 2 * exp.value(0.7));
}

}  // namespace
}  // namespace lcs

namespace lcs {
namespace {

// A linear congruential generator's next value in [0, 1).
double next_unit(unsigned& seed) {
  seed = seed * 1103515245u + 12345u;
  return static_cast<double>((seed >> 8) & 0xffff) / 65536.0;
}

// `count` PWL points at random steps of 0.1-1.1 us, values in [-5, 5); every 7th point repeats
// the time before it (a jump). Returns the last time.
double append_random_points(Waveform& w, int count, unsigned& seed) {
  double t = 0;
  for (int i = 0; i < count; ++i) {
    if (i % 7 != 3) t += 1e-6 * (0.1 + next_unit(seed));
    w.params.push_back(t);
    w.params.push_back(10 * next_unit(seed) - 5);
  }
  return t;
}

// A PWL is searched in place (binary search over its parameters, no copy of its points: a
// 20,000-point PWL went from 7.9 s to 0.08 s under event). Against a straight scan of the points:
// value right-continuous, the left limit, the right slope, at random times and exactly at every
// point, with jumps (two points at one time) among them.
TEST(WaveformPwl, ManyPointsWithJumpsAgreeWithAScanOfThePoints) {
  Waveform w;
  w.kind = Waveform::Kind::Pwl;
  unsigned seed = 12345;
  const double t = append_random_points(w, 1000, seed);
  auto next = [&seed] { return next_unit(seed); };
  w.resolve(1e-6, t * 1.1);
  const std::size_t n = w.params.size() / 2;
  auto tk = [&](std::size_t i) { return w.params[2 * i]; };
  auto vk = [&](std::size_t i) { return w.params[2 * i + 1]; };
  auto scan_value = [&](double x) {  // the last point at or before x, then the segment after it
    if (x < tk(0)) return vk(0);
    std::size_t i = 0;
    while (i + 1 < n && tk(i + 1) <= x) ++i;
    if (i + 1 == n) return vk(i);
    return vk(i) + (vk(i + 1) - vk(i)) * (x - tk(i)) / (tk(i + 1) - tk(i));
  };
  auto scan_slope = [&](double x) {
    if (x < tk(0)) return 0.0;
    std::size_t i = 0;
    while (i + 1 < n && tk(i + 1) <= x) ++i;
    return i + 1 == n ? 0.0 : (vk(i + 1) - vk(i)) / (tk(i + 1) - tk(i));
  };
  auto scan_left = [&](double x) {  // the first point at or after x, and the one before it
    if (x <= tk(0)) return vk(0);
    std::size_t j = 0;
    while (j < n && tk(j) < x) ++j;
    if (j == n) return vk(n - 1);
    return vk(j - 1) + (vk(j) - vk(j - 1)) * (x - tk(j - 1)) / (tk(j) - tk(j - 1));
  };
  std::vector<double> times;
  for (std::size_t i = 0; i < n; ++i) times.push_back(tk(i));
  for (int i = 0; i < 3000; ++i) times.push_back(t * 1.05 * next());
  for (double x : times) {
    EXPECT_DOUBLE_EQ(w.value(x), scan_value(x)) << x;
    EXPECT_DOUBLE_EQ(w.derivative(x), scan_slope(x)) << x;
    EXPECT_DOUBLE_EQ(w.value_before(x), scan_left(x)) << x;
  }
}

// A 1000-point PWL with jumps and r= at one of its points, read in place (the repeated stretch
// is not copied out at each evaluation): against the same waveform written out as a plain PWL
// over four periods (the stretch's points shifted by last + k per, each period closing with its
// left limit and a jump to the stretch's first value), at random times and midway between points.
TEST(WaveformPwl, RepeatOfManyPointsAgreesWithItsCopiesWrittenOut) {
  Waveform w;
  w.kind = Waveform::Kind::Pwl;
  unsigned seed = 777;
  const double t = append_random_points(w, 1000, seed);
  auto next = [&seed] { return next_unit(seed); };
  const std::size_t n = w.params.size() / 2, r_index = 400;
  const double from = w.params[2 * r_index], last = t, per = last - from;
  w.repeat_from = from;
  w.resolve(1e-6, last + 5 * per);
  Waveform plain;
  plain.kind = Waveform::Kind::Pwl;
  plain.params = std::vector<double>(w.params.begin(), w.params.end());
  const double end_value = w.params[2 * n - 1];  // the left limit at the period's end
  for (int k = 0; k < 4; ++k) {
    for (std::size_t i = r_index; i < n && w.params[2 * i] < last; ++i) {
      plain.params.push_back(last + k * per + (w.params[2 * i] - from));
      plain.params.push_back(w.params[2 * i + 1]);
    }
    plain.params.push_back(last + (k + 1) * per);
    plain.params.push_back(end_value);
  }
  plain.resolve(1e-6, last + 5 * per);
  std::vector<double> times;
  for (int i = 0; i < 4000; ++i) times.push_back(last + 4 * per * next());
  for (std::size_t i = r_index; i + 1 < n; ++i)
    for (int k = 0; k < 4 && w.params[2 * i] < w.params[2 * i + 2]; ++k)  // not at a jump
      times.push_back(last + k * per + 0.5 * (w.params[2 * i] + w.params[2 * i + 2]) - from);
  int compared = 0;
  for (double x : times) {
    if (x >= last + 4 * per) continue;
    // slopes are up to 1e8 V/s: 1e-9 V is a shift of 1e-17 s, a few ulps of x
    EXPECT_NEAR(w.value(x), plain.value(x), 1e-9) << x;
    EXPECT_NEAR(w.value_before(x), plain.value_before(x), 1e-9) << x;
    const double slope = plain.derivative(x);
    EXPECT_NEAR(w.derivative(x), slope, 1e-9 * std::max(1.0, std::fabs(slope))) << x;
    ++compared;
  }
  EXPECT_GT(compared, 6000);
}

}  // namespace
}  // namespace lcs
