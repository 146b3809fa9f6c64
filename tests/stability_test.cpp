// The stability study (docs/stability.md): where each integration method fails, shown on the
// netlists of circuits/stability/. Every test asserts a number that would be false if the method
// did not fail that way, and runs a contrast method that does not fail. The measured numbers are
// printed ("stability<TAB>case<TAB>quantity<TAB>value") and quoted in docs/stability.md.
//
// Adding a case: a netlist in circuits/stability/ whose title line says what it shows, a test
// here (suite name starting with "Stability"), and one row in the summary table of
// docs/stability.md naming both. StabilityStudy.EveryCaseHasANetlistARowAndATest checks the three
// stay in step.
#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <fstream>
#include <set>

#include <gtest/gtest.h>

#include "netlist/netlist.h"
#include "ngspice/deck_translation.h"
#include "ngspice/ngspice_session.h"
#include "solver/integrators/transient.h"
#include "solver/lcp/lcp.h"
#include "solver/model/initial_state.h"
#include "solver/model/smooth_netlist.h"
#include "solver/devices/diode.h"
#include "tests/cli_support.h"

namespace lcs {
namespace {

using cli_testing::read_file;
using cli_testing::source_path;

// ---------------------------------------------------------------------------------------------
// Running a case in-process

Netlist stability_netlist(const std::string& name) {
  return parse_netlist_file(source_path("circuits/stability/" + name + ".cir").string());
}

struct Simulation {
  MemorySink sink;
  TransientSummary summary;
  std::vector<double> column(const std::string& probe) const {
    const int c = sink.column(probe);
    EXPECT_GE(c, 0) << "no probe " << probe;
    std::vector<double> y;
    for (const Eigen::VectorXd& row : sink.rows) y.push_back(c >= 0 ? row(c) : NAN);
    return y;
  }
};

struct RunOptions {
  double theta = 0.5;  // for "theta"
  double tstop = 0;    // 0: the netlist's .tran TSTOP
  double rtol = 0, atol = 0;
  // false, the default: the θ-method's own steps (the method studied here); true
  // (`--euler-at-switching`) checks stiff switching steps against implicit Euler's
  // (euler_at_switching.h).
  bool euler_at_switching = false;
};

RunOptions checked() {
  RunOptions ro;
  ro.euler_at_switching = true;
  return ro;
}

RunOptions own_steps() {
  RunOptions ro;
  ro.euler_at_switching = false;
  return ro;
}

// The netlist's .print probes, its .tran TSTOP and UIC; `h` is the fixed step (or, for adaptive
// methods, the output spacing).
Simulation simulate(const Netlist& netlist, const std::string& method, double h, const RunOptions& ro = {}) {
  ModelOptions mo;
  mo.t1 = ro.tstop > 0 ? ro.tstop : netlist.tran->tstop;
  CircuitModel model = CircuitModel::build(netlist, mo);
  TransientOptions o;
  o.method = method;
  o.method_options.theta = ro.theta;
  o.method_options.rtol = ro.rtol;
  o.method_options.atol = ro.atol;
  o.method_options.euler_at_switching = ro.euler_at_switching;
  o.step = h;
  o.tstop = mo.t1;
  o.uic = netlist.tran->uic;
  Simulation r;
  r.summary = run_transient(model, model.output_map(netlist.probes), o, r.sink);
  return r;
}

void report(const char* study_case, const char* quantity, double value) {
  std::printf("stability\t%s\t%s\t%.6g\n", study_case, quantity, value);
}

// Linear interpolation of (t, y) at s, clamped at the ends.
double interpolate(const std::vector<double>& t, const std::vector<double>& y, double s) {
  if (s <= t.front()) return y.front();
  if (s >= t.back()) return y.back();
  const size_t k = std::upper_bound(t.begin(), t.end(), s) - t.begin();
  const double w = (s - t[k - 1]) / (t[k] - t[k - 1]);
  return y[k - 1] + w * (y[k] - y[k - 1]);
}

// Index of the first row where the diode current is positive (the size if none).
size_t first_conducting(const std::vector<double>& diode_current) {
  size_t n = 0;
  while (n < diode_current.size() && !(diode_current[n] > 0)) ++n;
  return n;
}

// ---------------------------------------------------------------------------------------------
// Case 1. The trapezoidal rule (theta = 1/2) on an index-one pair rings after the switch.
//
// circuits/stability/capacitor_clamp_ringing.cir: C dv/dt = (Vs - v)/R - z,
// 0 <= z ⟂ VON - v >= 0 (D = 0, CB = 1/C: index one, Stewart 4.5). Once clamped, v = VON on
// both ends of a step, so the theta-method's step (8.4.1; θ = 1/2 is the trapezoidal rule of
// Figure 8.1(b), θ = 1 implicit Euler, the one-stage Radau IIA method of Figure 8.2)
//   0 = h(1-θ)(I - z_n) + hθ(I - z_{n+1}),   I = (Vs - VON)/R,
// leaves z_{n+1} - I = -((1-θ)/θ)(z_n - I): the error of the first clamped step is multiplied by
// -1 every step at θ = 1/2 (the trapezoidal rule is A- but not L-stable: its stability function
// tends to -1 at infinite stiffness, and an index-one constraint is infinitely stiff), and
// removed in one step at θ = 1 (implicit Euler, L-stable). The capacitor current
// i(c1) = I - z, zero in the exact solution, alternates in sign and never decays.
//
// The first clamped step starts from the free state v_old < VON; with z_old = 0 it gives
//   z_on = (Vs - v_old)/R + I - 2C(VON - v_old)/h,
// so the ringing amplitude |z_on - I| is fixed by where the switch falls within the step.

TEST(StabilityTrapezoidRinging, CapacitorCurrentAlternatesWithoutDecayAfterTheClamp) {
  const Netlist netlist = stability_netlist("capacitor_clamp_ringing");
  const double Vs = 10, R = 1e3, C = 1e-6, VON = 5, h = 10e-6, I = (Vs - VON) / R;

  const Simulation trap = simulate(netlist, "theta", h, own_steps());
  const std::vector<double> v = trap.column("v(a)"), ic = trap.column("i(c1)"),
                            id = trap.column("i(d1)");
  const size_t on = first_conducting(id);
  ASSERT_GT(on, 0u);
  ASSERT_LT(on + 100, id.size()) << "the clamp must engage well before TSTOP";
  const double z_on = (Vs - v[on - 1]) / R + I - 2 * C * (VON - v[on - 1]) / h;
  const double amplitude = std::abs(z_on - I);
  EXPECT_NEAR(std::abs(ic[on]), amplitude, 1e-9 * I);
  EXPECT_GT(amplitude, 0.3 * I);  // measured 0.374 I: not a rounding-level effect
  long alternations = 0;
  for (size_t n = on + 1; n < ic.size(); ++n) {
    EXPECT_NEAR(v[n], VON, 1e-12 * VON) << "step " << n;
    alternations += ic[n] * ic[n - 1] < 0;
  }
  EXPECT_EQ(alternations, static_cast<long>(ic.size() - on - 1));  // every step after the clamp
  const double non_decay = std::abs(ic.back()) / std::abs(ic[on]);
  EXPECT_NEAR(non_decay, 1.0, 1e-9);
  report("trapezoid ringing", "steps after the clamp", static_cast<double>(ic.size() - on - 1));
  report("trapezoid ringing", "sign alternations", static_cast<double>(alternations));
  report("trapezoid ringing", "amplitude / I", std::abs(ic[on]) / I);
  report("trapezoid ringing", "last / first amplitude", non_decay);

  // Contrast: implicit Euler absorbs the overshoot in the first clamped step.
  const Simulation euler = simulate(netlist, "euler", h);
  const std::vector<double> ic_e = euler.column("i(c1)"), id_e = euler.column("i(d1)");
  const size_t on_e = first_conducting(id_e);
  ASSERT_LT(on_e + 100, id_e.size());
  double worst = 0;
  for (size_t n = on_e + 1; n < ic_e.size(); ++n) worst = std::max(worst, std::abs(ic_e[n]));
  EXPECT_LT(worst, 1e-12 * I);
  report("trapezoid ringing", "euler max |i(c1)| / I after the clamp", worst / I);

  // With --euler-at-switching theta checks its stiff switching steps against implicit Euler's
  // (euler_at_switching.h) and keeps this one: both end clamped at VON, so neither the mode nor
  // the state differ, and the ringing of z (v exact throughout) is the same.
  const Simulation with_check = simulate(netlist, "theta", h, checked());
  EXPECT_EQ(with_check.summary.stepper.switching_steps_by_euler, 0);
  EXPECT_EQ(with_check.column("i(c1)"), ic);
}

// At h = 100 tau the ringing is the whole diode current, and the diode switches at every step.
// With a = h/(2 tau), an off step from (VON, z_on) ends at VON - e and the next on step gives
// z_on = 2I + e(1 - 1/a)/R; the off step after it ends at VON - e (a-1)/(a+1) (the size of the
// trapezoidal stability function (1 + h lambda/2)/(1 - h lambda/2) at h lambda = -2a). So e -> 0 by (a-1)/(a+1) = 49/51 per two steps while
// z alternates between 0 and 2I: a period-two solution that satisfies every step's LCP, x = VON
// throughout, i(c1) = ±I. Implicit Euler is exact from the second step.
TEST(StabilityTrapezoidRinging, AtHundredTauTheDiodeTogglesEveryStepAndRingsWithTheFullCurrent) {
  const Netlist netlist = stability_netlist("capacitor_clamp_ringing");
  const double Vs = 10, R = 1e3, C = 1e-6, VON = 5, I = (Vs - VON) / R, h = 100 * R * C;
  RunOptions ro = own_steps();
  ro.tstop = 1000 * h;
  const Simulation trap = simulate(netlist, "theta", h, ro);
  const std::vector<double> v = trap.column("v(a)"), ic = trap.column("i(c1)"), id = trap.column("i(d1)");
  ASSERT_EQ(v.size(), 1001u);
  long toggles = 0;
  for (size_t n = 2; n < id.size(); ++n) toggles += (id[n] > 0) != (id[n - 1] > 0);
  EXPECT_EQ(toggles, 999);
  const double a = h / (2 * R * C), per_two_steps = (a - 1) / (a + 1);
  // Off steps are the even ones; e from step 2 to step 402 (200 pairs): 3.3e-4.
  ASSERT_EQ(id[2], 0.0);
  ASSERT_EQ(id[402], 0.0);
  const double e_ratio = (VON - v[402]) / (VON - v[2]);
  EXPECT_NEAR(std::log(e_ratio) / std::log(std::pow(per_two_steps, 200)), 1.0, 1e-6);
  EXPECT_NEAR(std::abs(ic.back()), I, 1e-6 * I);  // measured 1 + 2e-9
  EXPECT_NEAR(std::abs(ic[ic.size() - 2]), I, 1e-6 * I);
  report("trapezoid ringing h = 100 tau", "diode toggles in 1000 steps", static_cast<double>(toggles));
  report("trapezoid ringing h = 100 tau", "|i(c1)| / I at the end", std::abs(ic.back()) / I);
  report("trapezoid ringing h = 100 tau", "e ratio per two steps", std::pow(e_ratio, 1.0 / 200));

  // Implicit Euler, and theta with its switching steps checked (--euler-at-switching), are exact
  // from step 2.
  ro.euler_at_switching = true;
  for (const char* method : {"euler", "theta"}) {
    const Simulation euler = simulate(netlist, method, h, ro);
    const std::vector<double> v_e = euler.column("v(a)"), ic_e = euler.column("i(c1)");
    for (size_t n = 2; n < v_e.size(); ++n) {
      EXPECT_NEAR(v_e[n], VON, 1e-12 * VON) << method << " step " << n;
      EXPECT_LT(std::abs(ic_e[n]), 1e-12 * I) << method << " step " << n;
    }
  }
}

// The same recursion for 1/2 < θ < 1: the ringing decays by exactly -(1-θ)/θ per step.
TEST(StabilityTrapezoidRinging, ThetaAboveOneHalfDampsItByMinusOneMinusThetaOverTheta) {
  const Netlist netlist = stability_netlist("capacitor_clamp_ringing");
  for (double theta : {0.5, 0.6, 0.75}) {
    SCOPED_TRACE("theta = " + std::to_string(theta));
    RunOptions ro = own_steps();
    ro.theta = theta;
    const Simulation r = simulate(netlist, "theta", 10e-6, ro);
    const std::vector<double> ic = r.column("i(c1)"), id = r.column("i(d1)");
    const size_t on = first_conducting(id);
    ASSERT_LT(on + 10, id.size());
    for (size_t n = on + 1; n <= on + 10; ++n)  // ten steps: (2/3)^10 still far above rounding
      EXPECT_NEAR(ic[n] / ic[n - 1], -(1 - theta) / theta, 1e-9) << "step " << n;
  }
}

// ---------------------------------------------------------------------------------------------
// Case 1, continued. theta < 1 settles at a wrong value when h >> tau.
//
// circuits/stability/diode_charged_rc_large_step.cir: C dv/dt = z, 0 <= z ⟂ R z + v - E >= 0
// (E = V - VON = 9.3 V, tau = RC = 1 ms, index zero), started empty with z(0+) = E/R. The
// theta-method's first step carries the initial current over (1-θ)h:
//   v_1 = (1-θ) h z_0 / C + θ h z_1 / C.
// With the diode on at the end of the step, v_1 = (h/tau) E / (1 + θ h/tau), which exceeds E
// (so z_1 = (E - v_1)/R < 0) whenever (1-θ) h/tau > 1. Then z_1 = 0 is the LCP's answer,
// v_1 = (1-θ)(h/tau) E, and the diode, now reverse-biased, holds the capacitor there for good.
// Implicit Euler (θ = 1) has no explicit part: v_n = E (1 - (1 + h/tau)^-n), within 1 % of E
// after one step at h = 100 tau.

TEST(StabilityTrapezoidLargeStep, SettlesAtOneMinusThetaTimesHOverTauTimesTheTarget) {
  const Netlist netlist = stability_netlist("diode_charged_rc_large_step");
  const double E = 10 - 0.7, tau = 1e-3, h = 100e-3;
  for (double theta : {0.5, 0.75}) {
    SCOPED_TRACE("theta = " + std::to_string(theta));
    RunOptions ro = own_steps();
    ro.theta = theta;
    const Simulation r = simulate(netlist, "theta", h, ro);
    const std::vector<double> v = r.column("v(out)"), id = r.column("i(d1)");
    ASSERT_EQ(v.size(), 11u);
    // z_0 comes from the start-up LCP (a step of 1e-8 tau): 1e-8 relative.
    EXPECT_NEAR(v[1] / E, (1 - theta) * h / tau, 1e-6 * h / tau);
    for (size_t n = 1; n < v.size(); ++n) {
      EXPECT_EQ(v[n], v[1]) << "step " << n << ": the diode holds the overshoot";
      EXPECT_EQ(id[n], 0.0) << "step " << n;
    }
    report(theta == 0.5 ? "theta 0.5, h = 100 tau" : "theta 0.75, h = 100 tau",
           "settled v(out) / (V - VON)", v.back() / E);
  }
  // Contrast: implicit Euler.
  const Simulation euler = simulate(netlist, "euler", h);
  const std::vector<double> v = euler.column("v(out)");
  for (size_t n = 0; n < v.size(); ++n)
    EXPECT_NEAR(v[n], E * (1 - std::pow(1 + h / tau, -static_cast<double>(n))), 1e-9 * E) << n;
  EXPECT_NEAR(v.back(), E, 1e-12 * E);
  report("euler, h = 100 tau", "settled v(out) / (V - VON)", v.back() / E);

  // The cure, --euler-at-switching: the first step, which turns the diode off at the overshoot, is
  // implicit Euler's (v_1 = E (h/tau) / (1 + h/tau)); from there v rises to E and never past it.
  for (double theta : {0.5, 0.75}) {
    SCOPED_TRACE("theta = " + std::to_string(theta) + ", Euler at switching");
    RunOptions ro = checked();
    ro.theta = theta;
    const std::vector<double> vc = simulate(netlist, "theta", h, ro).column("v(out)");
    EXPECT_NEAR(vc[1], E * (h / tau) / (1 + h / tau), 1e-9 * E);
    for (size_t n = 1; n < vc.size(); ++n) EXPECT_LE(vc[n], E * (1 + 1e-12)) << "step " << n;
    EXPECT_NEAR(vc.back(), E, 1e-9 * E);
  }
}

// ---------------------------------------------------------------------------------------------
// Case 2. Implicit Euler damps an undamped oscillation; the trapezoidal rule does not.
//
// circuits/stability/lc_tank_numerical_damping.cir: while the bridge conducts (always, but at
// the zero crossings) the tank obeys v'' + 2 alpha v' + w0^2 v = 0 with alpha = 1/(2RC) = 0.5/s,
// w0 = 1e4 rad/s, and every mode of the bridge gives the same linear system, so the time-stepping
// is exactly the linear method applied to it. Per step each eigenvalue lambda = -alpha ± i wd is
// multiplied by
//   implicit Euler   1/(1 - h lambda)                (|.| = (1 + w0^2 h^2)^(-1/2) at alpha = 0),
//   trapezoidal      (1 + h lambda/2)/(1 - h lambda/2) (|.| = 1 at alpha = 0),
// and the energy E = C v^2/2 + L i^2/2 by the squared modulus, up to a ripple of order
// alpha/w0 = 5e-5 within a period. Implicit Euler's extra damping rate is
// -ln|1/(1 - h lambda)|/h - alpha ≈ w0^2 h / 2: 50/s at h = 1 us, 100 times the load's.

double tank_energy(const Simulation& r, size_t n) {
  const double C = 1e-6, L = 10e-3;
  const double v = r.sink.rows[n](r.sink.column("v(a)")), i = r.sink.rows[n](r.sink.column("i(l1)"));
  return 0.5 * C * v * v + 0.5 * L * i * i;
}

TEST(StabilityImplicitEulerDamping, TankEnergyShrinksByTheAmplificationFactorSquaredPerStep) {
  const Netlist netlist = stability_netlist("lc_tank_numerical_damping");
  const double R = 1e6, L = 10e-3, C = 1e-6;
  const double alpha = 1 / (2 * R * C), w0 = 1 / std::sqrt(L * C);
  const std::complex<double> lambda(-alpha, std::sqrt(w0 * w0 - alpha * alpha));
  for (double h : {1e-6, 4e-6}) {
    SCOPED_TRACE("h = " + std::to_string(h));
    const Simulation r = simulate(netlist, "euler", h);
    const size_t steps = r.sink.times.size() - 1;
    const double predicted = std::abs(1.0 / (1.0 - h * lambda));  // amplitude factor per step
    const double measured = std::pow(tank_energy(r, steps) / tank_energy(r, 0), 0.5 / steps);
    // Compared as damping rates -ln(factor)/h; the ripple moves the measured one by about
    // alpha/w0 = 5e-5 relative.
    const double rate_measured = -std::log(measured) / h, rate_predicted = -std::log(predicted) / h;
    EXPECT_NEAR(rate_measured / rate_predicted, 1.0, 2e-4);  // measured 5e-5 and 1.4e-5
    // The numerical part alone: w0^2 h / 2 to first order (the exact -ln(1 + w0^2 h^2)/(2h) is
    // 1e-4 (h = 1 us) and 8e-4 (h = 4 us) below it).
    EXPECT_NEAR((rate_measured - alpha) / (w0 * w0 * h / 2), 1.0, 2e-3);
    report(h == 1e-6 ? "euler tank h = 1 us" : "euler tank h = 4 us", "damping rate [1/s]", rate_measured);
    report(h == 1e-6 ? "euler tank h = 1 us" : "euler tank h = 4 us", "(rate - alpha) / (w0^2 h / 2)",
           (rate_measured - alpha) / (w0 * w0 * h / 2));
    report(h == 1e-6 ? "euler tank h = 1 us" : "euler tank h = 4 us", "energy left after 5 ms",
           tank_energy(r, steps) / tank_energy(r, 0));
  }

  // Contrast: the trapezoidal rule loses only what the 1 MOhm load dissipates, E0 exp(-2 alpha t),
  // at every step, within the ripple.
  const double h = 4e-6;
  const Simulation trap = simulate(netlist, "theta", h);
  double worst = 0;
  for (size_t n = 0; n < trap.sink.times.size(); ++n)
    worst = std::max(worst, std::abs(tank_energy(trap, n) / (tank_energy(trap, 0) *
                                                         std::exp(-2 * alpha * trap.sink.times[n])) - 1));
  EXPECT_LT(worst, 1e-4);
  report("theta 0.5 tank h = 4 us", "max |E / (E0 exp(-2 alpha t)) - 1|", worst);
}

// ---------------------------------------------------------------------------------------------
// Case 3. Explicit time-stepping of a stiff LCS diverges above h = 2/|lambda_max|.
//
// lcspice has no explicit method, for this reason; the oracle lives only here. Forward Euler with
// one LCP per step at the old state, the explicit end of 8.4.1 applied to the LCS of 4.5:
//   z_n from LCP(C x_n + F u_n, D),   x_{n+1} = x_n + h (A x_n + B z_n + E u_n).
// It needs D to be a P-matrix (index zero, every diode with RON or a resistor in its own loop):
// then z_n is a Lipschitz function of x_n, the LCS is an ODE with a piecewise-linear right-hand
// side, and in each mode forward Euler multiplies the mode's eigen-components by 1 + h lambda.
// With a real lambda_max that is > 1 in size once h > 2/|lambda_max|, whatever the diode does.
//
// circuits/stability/stiff_rc_rectifier.cir: the 10 ohm / 1 uF output filter gives
// lambda_max ≈ -1/(R2 C2) (1 + C2/C1) = -1.01e5/s in both diode modes (h_crit = 19.8 us); the
// rectifier's own time constant is 10 ms.

struct ExplicitRun {
  std::vector<double> t;
  std::vector<Eigen::VectorXd> x;
};

ExplicitRun forward_euler_lcp(const CircuitModel& model, const Eigen::VectorXd& x0, double h, double tstop) {
  const Lcs& s = model.lcs();
  ExplicitRun r;
  Eigen::VectorXd x = x0;
  const long steps = std::lround(tstop / h);
  for (long n = 0; n <= steps; ++n) {
    r.t.push_back(n * h);
    r.x.push_back(x);
    if (!(x.norm() < 1e100)) break;  // diverged: stop before overflow
    const Eigen::VectorXd u = model.input_values(n * h);
    const LcpSolution sol = solve_lemke(s.D, s.C * x + s.F * u);
    EXPECT_EQ(sol.status, LcpStatus::Solved) << "t = " << n * h;
    x += h * (s.A * x + s.B * sol.z + s.E * u);
  }
  return r;
}

// Largest |eigenvalue| of the dynamics over every mode of a one-pair LCS with D > 0: off
// (z = 0): A; on (w = 0): A - B D^-1 C.
double stiffest_rate(const Lcs& s) {
  double rate = 0;
  for (const Eigen::MatrixXd& M : {Eigen::MatrixXd(s.A), Eigen::MatrixXd(s.A - s.B * s.D.inverse() * s.C)}) {
    const Eigen::VectorXcd ev = Eigen::EigenSolver<Eigen::MatrixXd>(M).eigenvalues();
    for (int k = 0; k < ev.size(); ++k) {
      EXPECT_LE(std::abs(ev(k).imag()), 1e-9 * M.norm()) << "an RC circuit has real eigenvalues";
      rate = std::max(rate, std::abs(ev(k)));
    }
  }
  return rate;
}

TEST(StabilityExplicitStepping, ForwardEulerDivergesAboveTwoOverLambdaMaxImplicitEulerDoesNot) {
  const Netlist netlist = stability_netlist("stiff_rc_rectifier");
  ModelOptions mo;
  mo.t1 = netlist.tran->tstop;
  const CircuitModel model = CircuitModel::build(netlist, mo);
  const Lcs& s = model.lcs();
  ASSERT_EQ(s.pairs(), 1);
  ASSERT_GT(s.D(0, 0), 0.0) << "the oracle needs index zero";
  ASSERT_TRUE(s.Gamma.isZero()) << "the oracle integrates x, which must then be the physical state";
  ASSERT_EQ(model.states().size(), 2u);
  ASSERT_EQ(model.states()[0].label, "v(c1)");  // v(a)
  ASSERT_EQ(model.states()[1].label, "v(c2)");  // v(b)
  const double lambda_max = stiffest_rate(s), h_crit = 2 / lambda_max;
  EXPECT_NEAR(lambda_max, 1.01e5, 0.01e5);
  report("stiff rectifier", "lambda_max [1/s]", lambda_max);
  const Eigen::VectorXd x0 = initial_state(model, netlist.tran->uic, 0.0).x;
  const double tstop = netlist.tran->tstop;

  // Reference: implicit Euler at 1 us (its own error, about 1/25 of the 25 us run's, is ~5e-5 of
  // the range). Compared on v(b), the output node, where the fast mode lives.
  const Simulation ref = simulate(netlist, "euler", 1e-6);
  const std::vector<double> ref_b = ref.column("v(b)");
  double range = 0;
  for (double y : ref_b) range = std::max(range, std::abs(y));
  auto error_vs_reference = [&](const std::vector<double>& t, auto value_b) {
    double e = 0;
    for (size_t n = 0; n < t.size(); ++n)
      e = std::max(e, std::abs(value_b(n) - interpolate(ref.sink.times, ref_b, t[n])));
    return e / range;
  };

  // Above: h = 25 us = 1.26 h_crit. The error grows by |1 - h lambda_max| = 1.525 per step.
  const double h_above = 25e-6;
  ASSERT_GT(h_above, 1.2 * h_crit);
  const ExplicitRun above = forward_euler_lcp(model, x0, h_above, tstop);
  ASSERT_GT(above.x.size(), 400u);
  const double growth = std::pow(above.x[400].norm() / above.x[200].norm(), 1.0 / 200);
  EXPECT_NEAR(growth, std::abs(1 - h_above * lambda_max), 1e-4);  // measured 1.2e-5 off
  const double at_5ms = above.x[200].norm();
  EXPECT_GT(at_5ms, 1e25);  // volts, from a 10 V source; measured 2.4e30
  report("forward euler h = 25 us", "h / h_crit", h_above / h_crit);
  report("forward euler h = 25 us", "growth per step", growth);
  report("forward euler h = 25 us", "|x| at 5 ms [V]", at_5ms);
  report("forward euler h = 25 us", "steps to |x| > 1e100", static_cast<double>(above.x.size() - 1));

  // Below: h = 16 us = 0.81 h_crit converges to the reference.
  const double h_below = 16e-6;
  ASSERT_LT(h_below, 0.85 * h_crit);
  const ExplicitRun below = forward_euler_lcp(model, x0, h_below, tstop);
  ASSERT_EQ(below.x.size(), 2501u);
  const double e_below = error_vs_reference(below.t, [&](size_t n) { return below.x[n](1); });
  EXPECT_LT(e_below, 3e-3);  // measured 8.5e-4
  report("forward euler h = 16 us", "h / h_crit", h_below / h_crit);
  report("forward euler h = 16 us", "max |v(b) - ref| / max|v(b)|", e_below);

  // Contrast: implicit Euler at the unstable step and at 10 h_crit stays bounded and accurate.
  for (double h : {h_above, 200e-6}) {
    SCOPED_TRACE("implicit Euler, h = " + std::to_string(h));
    const Simulation r = simulate(netlist, "euler", h);
    const std::vector<double> b = r.column("v(b)");
    const double e = error_vs_reference(r.sink.times, [&](size_t n) { return b[n]; });
    EXPECT_LT(e, h == h_above ? 3e-3 : 2e-2);  // measured 1.2e-3 and 9.8e-3
    report(h == h_above ? "implicit euler h = 25 us" : "implicit euler h = 200 us",
           "max |v(b) - ref| / max|v(b)|", e);
  }
}

// ---------------------------------------------------------------------------------------------
// Case 4. ngspice is silently wrong with a sharp diode and a coarse maximum step.
//
// circuits/stability/half_wave_coarse_max_step.cir through the in-process bridge, with the
// ideal diode translated to a VON source plus a Shockley diode of emission coefficient N = 0.01
// (docs/model_convergence.md), and TMAX = 125 TSTEP. ngspice reports success, and its
// waveform, read at its own time points (no interpolation error), is several times the range
// off lcspice's and off its own run with TMAX = TSTEP. Why is not analysed here (with
// method=gear it is still 1.2 ranges off, so it is not only case 1's trapezoidal ringing).

TEST(StabilityNgspiceCoarseMaxStep, FinishesWithoutAnErrorAndSeveralRangesOff) {
  const Netlist netlist = stability_netlist("half_wave_coarse_max_step");
  ModelOptions mo;
  mo.t1 = netlist.tran->tstop;
  const CircuitModel model = CircuitModel::build(netlist, mo);
  const std::vector<Probe>& probes = netlist.probes;
  const double tstep = netlist.tran->tstep, tstop = netlist.tran->tstop;

  // lcspice: implicit Euler at TSTEP/10, as `lcspice validate` runs it.
  const Simulation ours = simulate(netlist, "euler", tstep / 10);

  auto run_ngspice = [&](double max_step) {
    TranslationOptions topt;
    topt.emission = 0.01;
    topt.max_step = max_step;
    const TranslatedDeck deck = translate_to_ngspice(model, probes, topt);
    NgspiceRun nr;
    nr.deck = deck.lines;
    nr.timeout_seconds = 60;
    NgspiceResult result = run_ngspice_transient(nr);  // throws NgspiceError on any failure
    return std::make_pair(deck, result);
  };
  const auto [coarse_deck, coarse] = run_ngspice(125 * tstep);
  const auto [fine_deck, fine] = run_ngspice(0);  // TMAX = TSTEP

  // The silence: no NgspiceError above, the whole interval covered, nothing it printed (but the
  // echo of the title) says error or warning.
  EXPECT_NEAR(coarse.time.back(), tstop, 1e-9 * tstop);
  for (const std::string& m : coarse.messages) {
    if (m.rfind("Circuit:", 0) == 0) continue;
    std::string lower = m;
    for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    EXPECT_EQ(lower.find("error"), std::string::npos) << m;
    EXPECT_EQ(lower.find("warning"), std::string::npos) << m;
    EXPECT_EQ(lower.find("too small"), std::string::npos) << m;
  }

  for (size_t p = 0; p < ours.sink.names.size(); ++p) {
    const std::string& name = ours.sink.names[p];
    SCOPED_TRACE(name);
    auto series = [&](const TranslatedDeck& deck, const NgspiceResult& r) {
      const ProbeSource& src = deck.probes.at(name);
      std::vector<double> y = r.vectors.at(src.plus);
      if (!src.minus.empty())
        for (size_t k = 0; k < y.size(); ++k) y[k] -= r.vectors.at(src.minus)[k];
      return y;
    };
    const std::vector<double> y_coarse = series(coarse_deck, coarse), y_fine = series(fine_deck, fine);
    const std::vector<double> y_ours = ours.column(name);
    double lo = INFINITY, hi = -INFINITY;
    for (double y : y_ours) lo = std::min(lo, y), hi = std::max(hi, y);
    const double range = hi - lo;
    double vs_ours = 0, vs_fine = 0, fine_vs_ours = 0;
    for (size_t k = 0; k < coarse.time.size(); ++k) {
      vs_ours = std::max(vs_ours, std::abs(y_coarse[k] - interpolate(ours.sink.times, y_ours, coarse.time[k])));
      vs_fine = std::max(vs_fine, std::abs(y_coarse[k] - interpolate(fine.time, y_fine, coarse.time[k])));
    }
    for (size_t k = 0; k < fine.time.size(); ++k)
      fine_vs_ours = std::max(fine_vs_ours, std::abs(y_fine[k] - interpolate(ours.sink.times, y_ours, fine.time[k])));
    // Measured: v(out) 2.38 and 2.38, i(l1) 2.85 and 2.84 ranges; TMAX = TSTEP: 0.26 % and
    // 7.8 % (ngspice's own error at N = 0.01 with default tolerances, docs/model_convergence.md).
    EXPECT_GT(vs_ours / range, 1.5);
    EXPECT_GT(vs_fine / range, 1.5);
    EXPECT_LT(fine_vs_ours / range, 0.12);
    report(("ngspice TMAX = 125 TSTEP " + name).c_str(), "max error / range vs lcspice", vs_ours / range);
    report(("ngspice TMAX = 125 TSTEP " + name).c_str(), "max error / range vs ngspice TMAX = TSTEP", vs_fine / range);
    report(("ngspice TMAX = TSTEP " + name).c_str(), "max error / range vs lcspice", fine_vs_ours / range);
  }
  report("ngspice TMAX = 125 TSTEP", "time points", static_cast<double>(coarse.time.size()));
  report("ngspice TMAX = TSTEP", "time points", static_cast<double>(fine.time.size()));
}

// ---------------------------------------------------------------------------------------------
// Case 5. Smoothing (8.2) needs steps that shrink with the smoothing parameter.
//
// circuits/stability/smoothed_diode_rc.cir with its ideal diode replaced by the smooth one the
// `smooth` method integrates (a VON source and a Shockley diode of emission N):
//   C dv/dt = IS (exp((V - VON - v)/(N Vt)) - 1) - v/R.
// Near its equilibrium the diode's conductance is g = (I + IS)/(N Vt), so the linearised rate is
// lambda = -(g + 1/R)/C and forward Euler is stable only for h < 2/|lambda| ~ 2 C N Vt / I: the
// smoother the diode, the larger the step; halve N and the step must halve. The smoothing error
// itself, N Vt ln(I/IS), is proportional to N. IDA (implicit, variable-order BDF, adaptive) does
// not pay for small N: its step count stays flat.

double smoothed_rc_rate(double v, double N) {  // f(v) = C dv/dt and f'(v)
  const double V = 5, VON = 0.7, R = 100, IS = 1e-14, nvt = N * kThermalVoltage;
  return IS * (std::exp((V - VON - v) / nvt) - 1) - v / R;
}

double smoothed_rc_equilibrium(double N) {
  const double VON = 0.7, V = 5, R = 100, IS = 1e-14, nvt = N * kThermalVoltage;
  double v = V - VON - nvt * std::log(((V - VON) / R) / IS);  // near the root; Newton from there
  for (int k = 0; k < 50; ++k) {
    const double e = IS * std::exp((V - VON - v) / nvt);
    const double f = e - IS - v / R, df = -e / nvt - 1 / R;
    v -= f / df;
  }
  return v;
}

// Forward Euler from the equilibrium plus a deviation small against N Vt (the linear regime):
// has the deviation shrunk after 2000 steps?
bool forward_euler_settles(double N, double h) {
  const double C = 10e-6, vstar = smoothed_rc_equilibrium(N), dev = 1e-4 * N * kThermalVoltage;
  double v = vstar + dev;
  for (int k = 0; k < 2000; ++k) {
    v += h / C * smoothed_rc_rate(v, N);
    if (!std::isfinite(v) || std::abs(v - vstar) > 1) return false;
  }
  return std::abs(v - vstar) < dev;
}

TEST(StabilitySmoothing, ExplicitStepsShrinkWithTheEmissionCoefficientAdaptiveBdfDoesNot) {
  const Netlist ideal = stability_netlist("smoothed_diode_rc");
  const double C = 10e-6, R = 100, IS = 1e-14;
  double previous_h = 0, previous_gap = 0;
  long fewest = 1L << 40, most = 0;
  for (double N : {0.1, 0.05, 0.025, 0.0125}) {
    // Largest stable forward Euler step, by bisection.
    double lo = 1e-12, hi = 1e-3;
    for (int k = 0; k < 60; ++k) {
      const double mid = std::sqrt(lo * hi);
      (forward_euler_settles(N, mid) ? lo : hi) = mid;
    }
    const double vstar = smoothed_rc_equilibrium(N);
    const double I = vstar / R, g = (I + IS) / (N * kThermalVoltage);
    EXPECT_NEAR(lo / (2 * C / (g + 1 / R)), 1.0, 0.01) << "N = " << N;  // the predicted limit
    if (previous_h > 0) {
      EXPECT_NEAR(lo / previous_h, 0.5, 0.01) << "N = " << N;
    }
    report("smoothed diode RC", ("largest stable forward Euler step at N = " + std::to_string(N)).c_str(), lo);

    // The smooth method (IDA) on the same circuit: the smoothing error is proportional to N,
    // the step count is not.
    SmoothingOptions so;
    so.emission = N;
    const Simulation r = simulate(smooth_netlist(ideal, so), "smooth", ideal.tran->tstep);
    const double v_end = r.column("v(out)").back();
    EXPECT_NEAR(v_end, vstar, 1e-6 * vstar) << "N = " << N;
    const double gap = (5 - 0.7) - v_end;  // against the ideal diode's 4.3 V
    if (previous_gap > 0) {
      EXPECT_NEAR(gap / previous_gap, 0.5, 0.01) << "N = " << N;
    }
    fewest = std::min(fewest, r.summary.stepper.steps);
    most = std::max(most, r.summary.stepper.steps);
    report("smoothed diode RC", ("IDA steps at N = " + std::to_string(N)).c_str(), r.summary.stepper.steps);
    report("smoothed diode RC", ("gap to the ideal diode at N = " + std::to_string(N)).c_str(), gap);
    previous_h = lo;
    previous_gap = gap;
  }
  // Measured 98 to 110 steps from N = 0.1 to 0.0125 while the explicit limit fell 8-fold.
  EXPECT_LT(static_cast<double>(most) / fewest, 1.3);
}

// ---------------------------------------------------------------------------------------------
// Case 6. Event-driven integration near a grazing contact (8.3.3, 8.3.5).
//
// A constraint that touches zero tangentially (w = 0 and w' = 0 at the same instant) is where an
// event method can chatter: each restart finds the pair at zero and may pick a mode that the
// next bracket refutes (EventOptions::max_events_at_one_time stops that with "event chattering",
// exit 3). Two circuits probe it.
//
// circuits/stability/grazing_sine_threshold.cir: w = VON + RON i - (u - v(out)) with u = A sin(wt)
// and A = VON + delta. For delta > 0 the diode conducts for 2 sqrt(2 delta / A) / w around each
// peak with a current of at most delta / (R + RON): two events per peak. The test sweeps delta
// down to 0 (and below) and counts events, against implicit Euler at the same step, whose work
// does not depend on delta and which sees a conduction window only when a step ends inside it.
// The event method never chatters; it stops resolving the touch when delta falls under its
// constraint tolerance (1e-12 of the row's terms) or, off the grid, under the error of the cubic
// through a step's end values and slopes, about (w h)^4/384 of A: then it misses the window
// silently (a current of at most delta/(R + RON)).
//
// circuits/stability/grazing_clamped_tank.cir: one clamp leaves the lossless tank at amplitude
// VON exactly, and every later peak grazes w = VON - v within rounding: a repeated exact graze.

// Rows that are neither multiples of the output step nor TSTOP: the events the method emitted.
std::vector<size_t> event_rows(const Simulation& r, double tstep) {
  std::vector<size_t> rows;
  for (size_t n = 0; n + 1 < r.sink.times.size(); ++n) {
    const double t = r.sink.times[n];
    if (std::abs(t - std::round(t / tstep) * tstep) > 1e-9 * tstep) rows.push_back(n);
  }
  return rows;
}

std::string g_format(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", x);
  return buf;
}

// Maximal runs of rows with a positive diode current.
int conduction_windows(const std::vector<double>& current) {
  int windows = 0;
  for (size_t n = 0; n < current.size(); ++n)
    windows += current[n] > 0 && (n == 0 || !(current[n - 1] > 0));
  return windows;
}

Netlist with_peak(Netlist netlist, double peak) {
  for (Element& e : netlist.elements)
    if (e.name == "v1") e.waveform.params.at(1) = peak;
  return netlist;
}

TEST(StabilityEventGrazing, SineReachingTheThresholdNeverChattersAndIsUnresolvedBelowTheTolerance) {
  const Netlist base = stability_netlist("grazing_sine_threshold");
  const double VON = 0.7, RON = 1, R = 100, f = 50, w = 2 * 3.14159265358979323846 * f;
  const double tstep = base.tran->tstep, tstop = base.tran->tstop;
  const int peaks = static_cast<int>(tstop * f);  // 5
  ASSERT_EQ(peaks, 5);
  const long euler_steps = static_cast<long>(std::ceil(tstop / tstep));  // 3333 and a last partial
  struct Row {
    double delta;
    long events;  // measured, asserted exactly
    int euler_windows;
  };
  // Measured 2026-11-21 (TSTEP = 30 us: the peaks fall between grid times).
  const std::vector<Row> sweep = {{1e-3, 10, 5},  {1e-6, 10, 1},  {1e-9, 10, 1}, {1e-10, 10, 1},
                                  {1e-11, 2, 1},  {1e-12, 0, 1},  {0, 0, 0},     {-1e-9, 0, 0}};
  for (const Row& row : sweep) {
    SCOPED_TRACE("delta = " + g_format(row.delta));
    const Netlist netlist = with_peak(base, VON + row.delta);
    const Simulation ev = simulate(netlist, "event", tstep);  // throws on "event chattering"
    const Simulation eu = simulate(netlist, "euler", tstep);
    const std::vector<double> id = ev.column("i(d1)"), vd = ev.column("v(in,out)");
    const std::vector<size_t> rows = event_rows(ev, tstep);
    EXPECT_EQ(ev.summary.stepper.events, row.events);
    EXPECT_EQ(static_cast<long>(rows.size()), row.events);
    EXPECT_LE(ev.summary.stepper.events, 2 * peaks);  // never more than two per touch
    EXPECT_EQ(conduction_windows(id), static_cast<int>(row.events / 2));
    // At every event the switching diode sits at its threshold with zero current: z = w = 0.
    double worst_w = 0, worst_z = 0, worst_t = 0;
    for (size_t n : rows) {
      worst_w = std::max(worst_w, std::abs(VON + RON * id[n] - vd[n]));
      worst_z = std::max(worst_z, std::abs(id[n]));
      // where A sin(w t) = VON: the crossing times of the sine (ill-conditioned as delta -> 0:
      // the slope of w there is A w sqrt(2 delta / A))
      const double t = ev.sink.times[n], phase = std::fmod(w * t, 2 * 3.14159265358979323846);
      const double t0 = std::asin(VON / (VON + row.delta)) / w;
      const double period_start = t - phase / w;
      worst_t = std::max(worst_t, std::min(std::abs(t - period_start - t0),
                                           std::abs(t - period_start - (1 / (2 * f) - t0))));
    }
    // An event is placed where w first reads below -1e-12 of its terms (|VON| + |u| = 1.4 V):
    // measured max |w| 1.40e-12 V, |z| 1.39e-14 A at every delta that has events.
    EXPECT_LT(worst_w, 3e-12);
    EXPECT_LT(worst_z, 3e-14);
    // Its time is that band over the slope of w at the crossing, A w sqrt(2 delta / A): measured
    // 1.2e-13 s at delta = 1e-3 up to 1.2e-9 s at 1e-11, each within 1.1 times the bound.
    if (row.events > 0) {
      const double A = VON + row.delta;
      EXPECT_LT(worst_t, 2 * 1.5e-12 / (A * w * std::sqrt(2 * row.delta / A)));
    }
    // Whatever it does not resolve carries less than delta / (R + RON).
    for (size_t n = 0; n < id.size(); ++n)
      EXPECT_LE(id[n], std::max(0.0, row.delta) / (R + RON) * (1 + 1e-6) + 1e-18) << n;
    // Implicit Euler: the same work whatever delta, and a window only where a step lands in it.
    EXPECT_EQ(eu.summary.stepper.steps, euler_steps);
    EXPECT_EQ(conduction_windows(eu.column("i(d1)")), row.euler_windows);
    const std::string c = "grazing sine delta = " + g_format(row.delta);
    report(c.c_str(), "event: events", static_cast<double>(ev.summary.stepper.events));
    report(c.c_str(), "event: steps (exponential products)", static_cast<double>(ev.summary.stepper.steps));
    report(c.c_str(), "event: max |w| at events [V]", worst_w);
    report(c.c_str(), "event: max |z| at events [A]", worst_z);
    report(c.c_str(), "event: max |t - crossing| [s]", worst_t);
    report(c.c_str(), "euler: steps", static_cast<double>(eu.summary.stepper.steps));
    report(c.c_str(), "euler: conduction windows seen", conduction_windows(eu.column("i(d1)")));
  }
}

// Where it finally fails: silently, by missing a shallow crossing between grid times. Off the
// grid, a dip is found only if the cubic through a step's end values and slopes dips below zero;
// its error is about (w h)^4/384 of A (7.2e-5 at TSTEP = 1.3 ms, w h = 0.41), and a touch less
// deep than that is stepped over. The first peak (5 ms) is found by the grid's finer start.
TEST(StabilityEventGrazing, CoarseOutputStepStepsOverTouchesShallowerThanTheCubicsError) {
  const Netlist base = stability_netlist("grazing_sine_threshold");
  const double VON = 0.7, w = 2 * 3.14159265358979323846 * 50, tstep = 1.3e-3;
  const double cubic = std::pow(w * tstep, 4) / 384;
  EXPECT_NEAR(cubic, 7.2e-5, 0.1e-5);
  for (auto [delta, expected] : {std::pair<double, long>{1e-4, 10}, {1e-5, 2}, {1e-9, 2}}) {
    SCOPED_TRACE("delta = " + g_format(delta));
    const Simulation ev = simulate(with_peak(base, VON + delta), "event", tstep);
    EXPECT_EQ(ev.summary.stepper.events, expected);  // 10 = every touch
    const std::string c = "grazing sine TSTEP = 1.3 ms delta = " + g_format(delta);
    report(c.c_str(), "event: events (10 = all)", static_cast<double>(ev.summary.stepper.events));
    report(c.c_str(), "delta / A over (w h)^4/384", delta / (VON + delta) / cubic);
  }
}

TEST(StabilityEventGrazing, TankClampedToItsThresholdGrazesEveryPeriodWithTwoEventsInAll) {
  const Netlist netlist = stability_netlist("grazing_clamped_tank");
  const double L = 100e-6, C = 1e-6, VON = 0.9, tstep = netlist.tran->tstep;
  const double w = 1 / std::sqrt(L * C), period = 2 * 3.14159265358979323846 / w;
  auto amplitude = [&](const Simulation& r, size_t n) {
    const double v = r.sink.rows[n](r.sink.column("v(a)")), i = r.sink.rows[n](r.sink.column("i(l1)"));
    return std::sqrt(v * v + (L / C) * i * i);
  };
  const Simulation ev = simulate(netlist, "event", tstep);
  ASSERT_EQ(ev.summary.stepper.events, 2);  // the clamp on, the clamp off
  const std::vector<size_t> rows = event_rows(ev, tstep);
  ASSERT_EQ(rows.size(), 2u);
  const double released = ev.sink.times[rows[1]];
  const int grazes = static_cast<int>((netlist.tran->tstop - released) / period);
  EXPECT_EQ(grazes, 31);
  // At the events: the clamp's w = VON - v(a) is zero (its current jumps to i(l1) at the first
  // and is back to zero at the second).
  const std::vector<double> va = ev.column("v(a)"), id = ev.column("i(d1)");
  EXPECT_LT(std::abs(VON - va[rows[0]]), 1e-12);
  EXPECT_LT(std::abs(VON - va[rows[1]]), 1e-12);
  EXPECT_LT(std::abs(id[rows[1]]), 1e-12);
  double drift = 0;
  for (size_t n = rows[1]; n < ev.sink.times.size(); ++n) {
    drift = std::max(drift, std::abs(amplitude(ev, n) - VON));
    EXPECT_EQ(id[n], 0.0) << "t = " << ev.sink.times[n];
  }
  EXPECT_LT(drift, 1e-12);  // measured 1.0e-13 V after 30 grazes
  report("grazing tank", "event: events", static_cast<double>(ev.summary.stepper.events));
  report("grazing tank", "event: grazes after the release", grazes);
  report("grazing tank", "event: max |amplitude - VON| after the release [V]", drift);
  report("grazing tank", "event: steps", static_cast<double>(ev.summary.stepper.steps));

  // Time-stepping does not graze at all: the release leaves the amplitude off VON by the
  // method's own error, below it (no further contact) or above it (a spurious clamp).
  for (auto [method, h] : {std::pair<const char*, double>{"euler", 1e-6}, {"theta", 1e-6},
                           {"radau5", 1e-6}, {"radau5", 1e-7}}) {
    const Simulation r = simulate(netlist, method, h);
    const std::vector<double> i = r.column("i(d1)");
    size_t n0 = 0;
    while (n0 < r.sink.times.size() && r.sink.times[n0] < released + tstep) ++n0;
    const double first = amplitude(r, n0), last = amplitude(r, r.sink.times.size() - 1);
    int later = 0;
    for (size_t n = n0 + 1; n < i.size(); ++n) later += i[n] > 0 && !(i[n - 1] > 0);
    const std::string c = std::string("grazing tank ") + method + " h = " + g_format(h);
    report(c.c_str(), "amplitude after the release - VON [V]", first - VON);
    report(c.c_str(), "amplitude at the end - VON [V]", last - VON);
    report(c.c_str(), "later clamps", later);
    // Measured: euler -0.116 V (and decaying to -0.90 V), theta 0.5 -2.1e-3 V, radau5 at 1 us
    // -7.4e-5 V, none touching again; radau5 at 0.1 us +6.1e-7 V and one more (spurious) clamp.
    if (std::string(method) == "euler") {
      EXPECT_LT(first - VON, -0.05);
      EXPECT_LT(last - VON, -0.8);
    } else if (std::string(method) == "theta") {
      EXPECT_LT(first - VON, -1e-3);
      EXPECT_GT(first - VON, -4e-3);
    } else if (h == 1e-6) {
      EXPECT_LT(first - VON, -3e-5);
      EXPECT_GT(first - VON, -2e-4);
    } else {
      EXPECT_GT(first - VON, 3e-7);
      EXPECT_LT(first - VON, 2e-6);
    }
    EXPECT_EQ(later, std::string(method) == "radau5" && h == 1e-7 ? 1 : 0);
  }
}

// ---------------------------------------------------------------------------------------------
// The study's bookkeeping: every netlist in circuits/stability/ has a row in the summary table of
// docs/stability.md, and every row names an existing netlist and a test registered here.

struct TableRow {
  std::string netlist, test;
};

std::vector<std::string> backticked(const std::string& cell) {
  std::vector<std::string> out;
  size_t a = cell.find('`');
  while (a != std::string::npos) {
    const size_t b = cell.find('`', a + 1);
    if (b == std::string::npos) break;
    out.push_back(cell.substr(a + 1, b - a - 1));
    a = cell.find('`', b + 1);
  }
  return out;
}

std::vector<TableRow> summary_table() {
  std::vector<TableRow> rows;
  std::istringstream in(read_file(source_path("docs/stability.md")));
  std::string line;
  bool in_table = false;
  while (std::getline(in, line)) {
    if (line.rfind("| case |", 0) == 0) {
      in_table = true;
      continue;
    }
    if (!in_table) continue;
    if (line.rfind("|", 0) != 0) break;
    if (line.rfind("|---", 0) == 0) continue;
    std::vector<std::string> cells(1);  // split at '|', but not at an escaped "\|"
    for (size_t k = 1; k < line.size(); ++k) {
      if (line[k] == '\\' && k + 1 < line.size() && line[k + 1] == '|') {
        cells.back() += '|';
        ++k;
      } else if (line[k] == '|') {
        cells.emplace_back();
      } else {
        cells.back() += line[k];
      }
    }
    if (cells.back().empty()) cells.pop_back();
    EXPECT_GE(cells.size(), 6u) << line;
    if (cells.size() < 6) continue;
    TableRow row;
    for (const std::string& b : backticked(cells[0]))
      if (b.rfind("circuits/stability/", 0) == 0) row.netlist = b;
    const std::vector<std::string> tests = backticked(cells[4]);
    if (!tests.empty()) row.test = tests.front();
    rows.push_back(row);
  }
  return rows;
}

TEST(StabilityStudy, EveryCaseHasANetlistARowAndATest) {
  std::set<std::string> registered;
  const ::testing::UnitTest& unit = *::testing::UnitTest::GetInstance();
  for (int i = 0; i < unit.total_test_suite_count(); ++i) {
    const ::testing::TestSuite& suite = *unit.GetTestSuite(i);
    for (int j = 0; j < suite.total_test_count(); ++j)
      registered.insert(std::string(suite.name()) + "." + suite.GetTestInfo(j)->name());
  }
  const std::vector<TableRow> rows = summary_table();
  EXPECT_FALSE(rows.empty()) << "docs/stability.md has no summary table";
  std::set<std::string> in_table;
  for (const TableRow& row : rows) {
    EXPECT_FALSE(row.netlist.empty()) << "a row without a circuits/stability/ netlist";
    EXPECT_TRUE(cli_testing::fs::exists(source_path(row.netlist))) << row.netlist;
    EXPECT_TRUE(registered.count(row.test)) << "no test " << row.test << " (row of " << row.netlist << ")";
    EXPECT_EQ(row.test.rfind("Stability", 0), 0u) << row.test;
    in_table.insert(row.netlist);
  }
  for (const auto& entry : cli_testing::fs::directory_iterator(source_path("circuits/stability"))) {
    if (entry.path().extension() != ".cir") continue;
    const std::string rel = "circuits/stability/" + entry.path().filename().string();
    EXPECT_TRUE(in_table.count(rel)) << rel << " has no row in docs/stability.md";
    std::string title;
    std::ifstream file(entry.path());
    std::getline(file, title);
    EXPECT_GT(title.size(), 40u) << rel << ": the title line says what the case shows";
  }
}

}  // namespace
}  // namespace lcs
