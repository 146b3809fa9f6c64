// Ideal switches (S, W) with the event method (issue 13: a switch is a mode of the circuit):
// switching instants where the control crosses VT + VH (on) or VT - VH (off), located as events
// along the exact trajectory, against their closed forms; a relaxation oscillator's period; the
// event method against euler at a small step; chattering; event as the default on switch decks;
// smooth, which locates them as roots of IDA.
#include <cmath>
#include <fstream>

#include <gtest/gtest.h>

#include "tests/cli_support.h"

namespace lcs {
namespace {

using namespace cli_testing;

// The event method locates a crossing to a bisection bracket of 2^-43 TSTEP, past the threshold
// by at most 1e-12 of the control's size: far inside 1e-9 of the time.
constexpr double kTimeRel = 1e-9;

// v(c) ramps 0 -> 0.9 V over 1 ms; S1 (VT 0.4 V, VH 0.1 V) closes where v(c) reaches 0.5 V,
// t_on = 0.5/0.9 ms, and charges C1 = 1 uF from 5 V. Off: through ROFF = 1e12 (tau_off = 1e6 s),
// on: through RON = 1 k (tau = 1 ms). Both pieces are exact exponentials.
const char* const kRampedRc = R"(RC charged through a voltage-controlled switch
VDD dd 0 DC 5
VC c 0 PWL(0 0 1m 0.9)
S1 dd out c 0 sw1
C1 out 0 1u
.model sw1 SW(VT=0.4 VH=0.1 RON=1k ROFF=1e12)
.tran 1u 3m UIC
.end
)";

double ramped_rc(double t) {
  const double t_on = 0.5e-3 / 0.9, tau_off = 1e12 * 1e-6, tau = 1e-3;
  if (t < t_on) return 5 * -std::expm1(-t / tau_off);
  const double v_on = 5 * -std::expm1(-t_on / tau_off);
  return 5 - (5 - v_on) * std::exp(-(t - t_on) / tau);
}

TEST(EventSwitches, RcChargedThroughARampedSwitchIsTheClosedForm) {
  const fs::path deck = write_deck("event_switch_deck_", "ramped_rc", kRampedRc);
  const double t_on = 0.5e-3 / 0.9;
  const Csv csv = run_csv(deck, "event", "--probe 'v(out),v(c)'");
  const std::vector<double> t = column(csv, "time"), v = column(csv, "v(out)"), c = column(csv, "v(c)");
  const size_t k_on = row_at(t, t_on);
  EXPECT_NEAR(t[k_on], t_on, kTimeRel * t_on);
  EXPECT_NEAR(c[k_on], 0.5, 1e-9);  // the row at the switching instant: the control at VT + VH
  // Rows: every multiple of the 1 us step (3001) and the switching instant.
  EXPECT_EQ(t.size(), 3002u);
  // Matrix exponentials: the closed form to rounding (1e-12 of 5 V, with margin).
  for (size_t k = 0; k < t.size(); ++k) ASSERT_NEAR(v[k], ramped_rc(t[k]), 1e-11) << t[k];
}

// Implicit Euler at h = 0.1 us against the event method on the same grid: the RC's first-order
// global error (h / 2 tau) (t / tau) e^(-t / tau) 5 V, at most 9.197e-5 V at t - t_on = tau
// (measured 9.196e-5 V), and the switching instant, exact for this linear control in both.
TEST(EventSwitches, EventAgreesWithEulerAtASmallStep) {
  const fs::path deck = write_deck("event_switch_deck_", "ramped_rc_euler", kRampedRc);
  const Csv ev = run_csv(deck, "event", "--step 0.1u --probe 'v(out)'");
  const Csv eu = run_csv(deck, "euler", "--step 0.1u --probe 'v(out)'");
  const std::vector<double> te = column(ev, "time"), ve = column(ev, "v(out)");
  const std::vector<double> tu = column(eu, "time"), vu = column(eu, "v(out)");
  ASSERT_EQ(te.size(), tu.size());  // the same grid and the same one switching row
  double worst = 0;
  for (size_t k = 0; k < te.size(); ++k) {
    ASSERT_NEAR(te[k], tu[k], 1e-12) << k;
    worst = std::max(worst, std::abs(ve[k] - vu[k]));
  }
  EXPECT_LT(worst, 9.2e-5);
  EXPECT_GT(worst, 1e-6);  // euler's own error is there to see: the two are different methods
}

// A triangle 0 -> 1 -> 0 V into a switch with VT = 0.5 V, VH = 0.205 V: on at 0.705 ms on the way
// up, off at 0.295 V (1.705 ms) on the way down, not at 0.705 V (1.295 ms). Resistive load: the
// output is 5 * 1000/1001 while on, 5 * 1000 / (1e12 + 1000) while off.
TEST(EventSwitches, HysteresisOpensAtVtMinusVh) {
  const fs::path deck = write_deck("event_switch_deck_", "hysteresis", R"(switch hysteresis
VDD dd 0 DC 5
VC c 0 PWL(0 0 1m 1 2m 0)
S1 dd out c 0 sw1
R1 out 0 1k
.model sw1 SW(VT=0.5 VH=0.205 RON=1 ROFF=1e12)
.tran 10u 2m
.end
)");
  const Csv csv = run_csv(deck, "event", "--probe 'v(out),v(c)'");
  const std::vector<double> t = column(csv, "time"), v = column(csv, "v(out)"), c = column(csv, "v(c)");
  EXPECT_NEAR(t[row_at(t, 0.705e-3)], 0.705e-3, kTimeRel * 0.705e-3);
  EXPECT_NEAR(t[row_at(t, 1.705e-3)], 1.705e-3, kTimeRel * 1.705e-3);
  EXPECT_NEAR(c[row_at(t, 1.705e-3)], 0.295, 1e-9);
  for (size_t k = 0; k < t.size(); ++k) {
    const bool on = t[k] >= 0.705e-3 * (1 - kTimeRel) && t[k] < 1.705e-3 * (1 - kTimeRel);
    EXPECT_NEAR(v[k], on ? 5 * 1000.0 / 1001 : 5 * 1000 / (1e12 + 1000), 1e-12) << t[k];
  }
}

// A control that jumps: PULSE with zero edges steps v(c) 0 -> 1 V at 0.5 ms and back at 1.5 ms,
// past VT + VH = 0.6 V and VT - VH = 0.4 V at the source's breakpoints themselves. S1 (RON = 1 k)
// closes there: C1 = 1 uF charges toward 2.5 V with tau = 0.5 ms (RON || R1), then discharges
// through R1 || ROFF (tau 1 ms) toward 5 nV. Every row is that closed form (the breakpoint is the
// switching instant, not a bisection bracket after it).
TEST(EventSwitches, ControlJumpingAtASourceBreakpoint) {
  const fs::path deck = write_deck("event_switch_deck_", "jump", R"(switch on a jumping control
VDD dd 0 DC 5
VC c 0 PULSE(0 1 0.5m 0 0 1m 2m)
S1 dd out c 0 sw1
R1 out 0 1k
C1 out 0 1u
.model sw1 SW(VT=0.5 VH=0.1 RON=1k ROFF=1e12)
.tran 10u 2m UIC
.end
)");
  const Csv csv = run_csv(deck, "event", "--probe 'v(out)' --stats");
  const std::vector<double> t = column(csv, "time"), v = column(csv, "v(out)");
  const double roff = 1e12, R = 1e3, C = 1e-6;
  const double v_off = 5 * R / (R + roff), tau_off = C * R * roff / (R + roff);
  const double v0 = v_off * -std::expm1(-0.5e-3 / tau_off);
  const double v1 = 2.5 - (2.5 - v0) * std::exp(-1e-3 / 0.5e-3);
  auto expected = [&](double s) {
    if (s <= 0.5e-3) return v_off * -std::expm1(-s / tau_off);
    if (s <= 1.5e-3) return 2.5 - (2.5 - v0) * std::exp(-(s - 0.5e-3) / 0.5e-3);
    return v_off + (v1 - v_off) * std::exp(-(s - 1.5e-3) / tau_off);
  };
  EXPECT_EQ(t.size(), 201u);  // the grid only: both changes fall on grid times
  for (size_t k = 0; k < t.size(); ++k) ASSERT_NEAR(v[k], expected(t[k]), 1e-11) << t[k];
}

// A W switch: i(vsense) = v(in)/1k ramps 0 -> 1 mA over 1 ms; IT = 0.5 mA, IH = 0.105 mA: on at
// 0.605 mA, t = 0.605 ms. The output: 5 * 1000/1001 V on, 5 * 1000 / (1e12 + 1000) V off.
TEST(EventSwitches, CurrentControlledSwitch) {
  const fs::path deck = write_deck("event_switch_deck_", "wswitch", R"(current-controlled switch
VIN in 0 PWL(0 0 1m 1)
VSENSE in m 0
RS m 0 1k
VDD dd 0 DC 5
W1 dd out vsense wsw
R1 out 0 1k
.model wsw CSW(IT=0.5m IH=0.105m RON=1 ROFF=1e12)
.tran 10u 1m
.end
)");
  const Csv csv = run_csv(deck, "event", "--probe 'v(out),i(vsense)'");
  const std::vector<double> t = column(csv, "time"), v = column(csv, "v(out)");
  EXPECT_NEAR(t[row_at(t, 0.605e-3)], 0.605e-3, kTimeRel * 0.605e-3);
  for (size_t k = 0; k < t.size(); ++k)
    EXPECT_NEAR(v[k], t[k] >= 0.605e-3 * (1 - kTimeRel) ? 5 * 1000.0 / 1001 : 5 * 1000 / (1e12 + 1000), 1e-12)
        << t[k];
}

// Relaxation oscillator: C charges from VDD = 5 V through R = 10 k; S1 across C (RON = 100)
// closes when v(c) rises above VT + VH = 3.5 V and opens when it falls below VT - VH = 1.5 V.
// Charging (S1 off, ROFF in parallel): toward Vth = 5 ROFF/(R + ROFF) with Rth = R || ROFF;
// discharging toward 5 RON/(R + RON) with R || RON. Each phase's length is Rth C ln(ratio):
//   first rise    t1 = Rth C ln(Vth / (Vth - 3.5))            (from 0 V, UIC)
//   discharge     td = Rd C ln((3.5 - Vd) / (1.5 - Vd))
//   rise          tr = Rth C ln((Vth - 1.5) / (Vth - 3.5)),   period tr + td.
TEST(EventSwitches, RelaxationOscillatorPeriodIsTheClosedForm) {
  const fs::path deck = write_deck("event_switch_deck_", "relaxation", R"(relaxation oscillator: a capacitor and a switch with hysteresis
VDD dd 0 DC 5
R1 dd c 10k
C1 c 0 1n
S1 c 0 c 0 swr
.model swr SW(VT=2.5 VH=1 RON=100 ROFF=1e12)
.tran 0.1u 40u UIC
.end
)");
  const double C = 1e-9, R = 1e4, roff = 1e12, ron = 100;
  const double rth = R * roff / (R + roff), vth = 5 * roff / (R + roff);
  const double rd = R * ron / (R + ron), vd = 5 * ron / (R + ron);
  const double t1 = rth * C * std::log(vth / (vth - 3.5));
  const double td = rd * C * std::log((3.5 - vd) / (1.5 - vd));
  const double tr = rth * C * std::log((vth - 1.5) / (vth - 3.5));
  const Csv csv = run_csv(deck, "event", "--probe 'v(c)' --stats");
  const std::vector<double> t = column(csv, "time"), v = column(csv, "v(c)");
  // The switching instants: closes at t1 + k (td + tr), opens td later.
  int closings = 0;
  for (int k = 0;; ++k) {
    const double on = t1 + k * (td + tr), off = on + td;
    if (off > 40e-6) break;
    SCOPED_TRACE(k);
    const size_t kon = row_at(t, on), koff = row_at(t, off);
    EXPECT_NEAR(t[kon], on, kTimeRel * on);
    EXPECT_NEAR(v[kon], 3.5, 1e-9);
    EXPECT_NEAR(t[koff], off, kTimeRel * off);
    EXPECT_NEAR(v[koff], 1.5, 1e-9);
    ++closings;
  }
  EXPECT_EQ(closings, 4);
  // Never outside the window after the first rise (the switch changes exactly at its ends).
  for (size_t k = 0; k < t.size(); ++k) {
    if (t[k] <= t1) continue;
    ASSERT_TRUE(v[k] > 1.5 - 1e-9 && v[k] < 3.5 + 1e-9) << t[k] << " " << v[k];
  }
}

// A buck converter: S1 (driven by a 100 kHz PULSE gate, 10 ns edges) and a freewheeling diode D1
// on an LC filter: switch changes and diode mode changes interleave. The switch closes where the
// gate rises through VT + VH = 3 V (6 ns into each rising edge) and opens where it falls through
// 2 V (4.016 us into each period): rows there, to 1e-9. Between them the event method is exact, so
// implicit Euler converges to it at first order: its distance to the event rows halves with h
// (measured: 9.5e-5 V and 2.4e-5 A at h = 1 ns), away from the switching rows (where the two
// methods' rows fall on either side of the same instant).
TEST(EventSwitches, BuckConverterSwitchAndDiodeEulerConvergesToEvent) {
  const fs::path deck = write_deck("event_switch_deck_", "buck", R"(buck converter: ideal switch, freewheeling diode
VIN in 0 DC 12
VG g 0 PULSE(0 5 0 10n 10n 4u 10u)
S1 in sw g 0 swm
D1 0 sw dfw
L1 sw out 100u
C1 out 0 10u
RL out 0 5
.model swm SW(VT=2.5 VH=0.5 RON=0.05 ROFF=1e9)
.model dfw D(VON=0.5 RON=0.01)
.tran 1u 100u UIC
.end
)");
  const Csv ev = run_csv(deck, "event", "--probe 'v(out),i(l1)'");
  const std::vector<double> te = column(ev, "time"), ve = column(ev, "v(out)"), ie = column(ev, "i(l1)");
  for (int k = 0; k < 10; ++k) {
    const double on = k * 10e-6 + 6e-9, off = k * 10e-6 + 4.016e-6;
    EXPECT_NEAR(te[row_at(te, on)], on, kTimeRel * on) << k;
    EXPECT_NEAR(te[row_at(te, off)], off, kTimeRel * off) << k;
  }
  // Euler's largest distance to the event method's rows at the 1 us grid times.
  auto distance = [&](const char* step) {
    const Csv eu = run_csv(deck, "euler", std::string("--step ") + step + " --probe 'v(out),i(l1)'");
    const std::vector<double> tu = column(eu, "time"), vu = column(eu, "v(out)"), iu = column(eu, "i(l1)");
    std::pair<double, double> worst{0, 0};
    size_t j = 0;
    for (size_t k = 0; k < te.size(); ++k) {
      const double grid = std::round(te[k] / 1e-6) * 1e-6;
      if (std::abs(te[k] - grid) > 1e-15) continue;  // an event row
      while (j < tu.size() && tu[j] < te[k] - 1e-15) ++j;
      if (j == tu.size() || std::abs(tu[j] - te[k]) > 1e-15) continue;
      worst.first = std::max(worst.first, std::abs(vu[j] - ve[k]));
      worst.second = std::max(worst.second, std::abs(iu[j] - ie[k]));
    }
    return worst;
  };
  const auto fine = distance("1n"), coarse = distance("2n");
  EXPECT_LT(fine.first, 2e-4);
  EXPECT_LT(fine.second, 5e-5);
  EXPECT_NEAR(coarse.first / fine.first, 2.0, 0.2);
  EXPECT_NEAR(coarse.second / fine.second, 2.0, 0.2);
}

// The relaxation oscillator against ngspice (validate, its default method event): ngspice
// changes the switch at one of its time points, so its period depends on its step; at
// --max-step 1e-10 (about 1e-4 of the 86 ns discharge per switching) every probe stays inside
// the tube over four periods (4.9e-5 of v(c)'s range outside it, measured; at 1e-9 the phase
// has drifted 13 % of the range out by 38 us).
TEST(EventSwitches, RelaxationOscillatorAgreesWithNgspice) {
  const fs::path deck = write_deck("event_switch_deck_", "relax_validate", R"(relaxation oscillator
VDD dd 0 DC 5
R1 dd c 10k
C1 c 0 1n
S1 c 0 c 0 swr
.model swr SW(VT=2.5 VH=1 RON=100 ROFF=1e12)
.tran 0.1u 40u UIC
.end
)");
  const Result r = run_lcspice("validate '" + deck.string() + "' --max-step 1e-10", deck.parent_path());
  EXPECT_EQ(r.code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("lcspice: ideal diodes, event,"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("PASS: every probe within 0.02 of its range"), std::string::npos) << r.out;
}

// S1 is controlled by v(c) = v(r) - v(out): the ramp r (2 V/ms) brings v(c) to VT = 1 V at 0.5 ms
// + 2.5 ps (v(out) = 5 nV through ROFF), S1 closes, the output jumps to 5 V and the control to
// -4 V: S1 opens at once, the control is back at 1 V, and so on at one instant. Both kinds of
// method report it the same way.
TEST(EventSwitches, ChatteringIsANumericalFailure) {
  const fs::path deck = write_deck("event_switch_deck_", "chatter", R"(a switch that undoes itself
VDD dd 0 DC 5
VR r 0 PWL(0 0 1m 2)
E1 c 0 r out 1
S1 dd out c 0 sw1
R1 out 0 1k
.model sw1 SW(VT=1 RON=1 ROFF=1e12)
.tran 10u 1m
.end
)");
  for (const char* method : {"event", "euler"}) {
    SCOPED_TRACE(method);
    const Result r = run_lcspice("run '" + deck.string() + "' --method " + method + " -o -", deck.parent_path());
    EXPECT_EQ(r.code, 3) << r.err;
    EXPECT_NE(r.err.find("lcspice: error: numerical failure at t = 0.00050000000"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(" s: the switches change more than 64 times at one instant (chattering: s1 off)"),
              std::string::npos)
        << r.err;
  }
}

// Without --method a switch deck runs with the event method (SPEC §1: event wherever it applies).
TEST(EventSwitches, EventIsTheDefaultOnSwitchDecks) {
  const fs::path deck = write_deck("event_switch_deck_", "default", kRampedRc);
  const fs::path dir = deck.parent_path();
  const Result r = run_lcspice("run '" + deck.string() + "' --stats -o '" + (dir / "out.csv").string() + "'", dir);
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.err.find("note: method"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("method event:"), std::string::npos) << r.err;
}

// smooth locates switch changes as roots of IDA (the guards after the diodes' crossings), to
// IDA's tolerance: the ramped RC's instant exactly (its control is the source alone), every row
// within 1e-5 V of the closed form (local error control at --rtol 1e-6 on 5 V, 5e-6 per step;
// 4.7e-6 measured); the relaxation oscillator's instants within 1e-6 relative (2.5e-7 measured).
TEST(EventSwitches, SmoothLocatesSwitchesAsRootsOfIda) {
  const fs::path ramp = write_deck("event_switch_deck_", "smooth_ramp", kRampedRc);
  const Csv csv = run_csv(ramp, "smooth", "--probe 'v(out)'");
  const std::vector<double> t = column(csv, "time"), v = column(csv, "v(out)");
  const double t_on = 0.5e-3 / 0.9;
  EXPECT_NEAR(t[row_at(t, t_on)], t_on, kTimeRel * t_on);
  for (size_t k = 0; k < t.size(); ++k) ASSERT_NEAR(v[k], ramped_rc(t[k]), 1e-5) << t[k];

  const fs::path relax = write_deck("event_switch_deck_", "smooth_relax", R"(relaxation oscillator
VDD dd 0 DC 5
R1 dd c 10k
C1 c 0 1n
S1 c 0 c 0 swr
.model swr SW(VT=2.5 VH=1 RON=100 ROFF=1e12)
.tran 0.1u 40u UIC
.end
)");
  const Csv osc = run_csv(relax, "smooth", "--probe 'v(c)'");
  const std::vector<double> to = column(osc, "time"), vo = column(osc, "v(c)");
  const double C = 1e-9, R = 1e4, roff = 1e12, ron = 100;
  const double rth = R * roff / (R + roff), vth = 5 * roff / (R + roff);
  const double rd = R * ron / (R + ron), vd = 5 * ron / (R + ron);
  const double t1 = rth * C * std::log(vth / (vth - 3.5));
  const double td = rd * C * std::log((3.5 - vd) / (1.5 - vd));
  const double tr = rth * C * std::log((vth - 1.5) / (vth - 3.5));
  for (int k = 0; k < 4; ++k) {
    SCOPED_TRACE(k);
    const double on = t1 + k * (td + tr), off = on + td;
    EXPECT_NEAR(to[row_at(to, on)], on, 1e-6 * on);
    EXPECT_NEAR(to[row_at(to, off)], off, 1e-6 * off);
    EXPECT_NEAR(vo[row_at(to, on)], 3.5, 1e-6);
  }
}

// smooth on a switched circuit starts at the smoothed circuit's own operating point, as it does
// without switches: circuits/switch_boost.cir at t = 0 (switch open, the diode carrying VIN into
// the load) has v(out) = RL i with VIN - RL i = N Vt ln(1 + i / IS) + RS i, 4.7376 V (ngspice's
// operating point too). Before, a switched circuit started at the ideal diode's operating point
// (4.998 V) and relaxed from there.
TEST(EventSwitches, SmoothStartsSwitchedCircuitsAtTheirOwnOperatingPoint) {
  const Csv csv = run_csv(circuit("switch_boost"), "smooth", "--probe 'v(out)'");
  ASSERT_FALSE(csv.rows.empty());
  const double vin = 5, rl = 50, is = 1e-5, nvt = 1.1 * (1.38064852e-23 * 300.15 / 1.6021766208e-19), rs = 0.02;
  double i = 0.09;
  for (int k = 0; k < 50; ++k) {  // Newton on f(i) = VIN - RL i - N Vt ln(1 + i/IS) - RS i
    const double f = vin - rl * i - nvt * std::log1p(i / is) - rs * i, df = -rl - nvt / (is + i) - rs;
    i -= f / df;
  }
  EXPECT_NEAR(csv.rows[0][0], 0.0, 0.0);
  EXPECT_NEAR(csv.rows[0][1], rl * i, 1e-6);
}

// smooth's guards are IDA's roots: a circuit without states (no IDA run) is refused with the
// reason and the methods that handle it (a usage error, the netlist is fine).
TEST(EventSwitches, SmoothRefusesSwitchesWithoutStates) {
  const fs::path deck = write_deck("event_switch_deck_", "smooth_no_states", R"(switch on a resistive load
VDD dd 0 DC 5
VC c 0 PWL(0 0 1m 1 2m 0)
S1 dd out c 0 sw1
R1 out 0 1k
.model sw1 SW(VT=0.5 VH=0.205 RON=1 ROFF=1e12)
.tran 10u 2m
.end
)");
  const Result r = run_lcspice("run '" + deck.string() + "' --method smooth -o -", deck.parent_path());
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_NE(r.err.find("error: method smooth: switch s1: the smooth method locates switch changes only in a "
                       "circuit with states (capacitors or inductors); use --method event, euler, theta, "
                       "radau3 or radau5"),
            std::string::npos)
      << r.err;
}

}  // namespace
}  // namespace lcs
