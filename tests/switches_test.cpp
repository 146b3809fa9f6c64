// Ideal switches S and W (SPEC §2): switching times where the control crosses VT + VH (on) and
// VT - VH (off), the RC closed form after the switch closes, hysteresis, current control, the
// state at t = 0, and the refusals.
#include <cmath>
#include <fstream>

#include <gtest/gtest.h>

#include "netlist/netlist.h"
#include "solver/model/switch_family.h"
#include "tests/cli_support.h"

namespace lcs {
namespace {

using namespace cli_testing;

// v(c) ramps 0 -> 0.9 V over 1 ms; the switch (VT 0.4 V, VH 0.1 V) closes where v(c) reaches
// 0.5 V, t_on = 0.5/0.9 ms (not a multiple of the step), and charges C1 = 1 uF through RON = 1 k
// from 5 V: v(out) = 5 (1 - exp(-(t - t_on)/1 ms)) after it, ~0 before (from rest, UIC: ROFF =
// 1e12 leaks 5 V t / (ROFF C) = 2.8 nV by t_on; the operating point would charge C1 through ROFF).
const char* const kRampedRc = R"(RC charged through a voltage-controlled switch
VDD dd 0 DC 5
VC c 0 PWL(0 0 1m 0.9)
S1 dd out c 0 sw1
C1 out 0 1u
.model sw1 SW(VT=0.4 VH=0.1 RON=1k ROFF=1e12)
.tran 1u 3m UIC
.end
)";

TEST(Switches, RcChargedThroughARampedSwitch) {
  const fs::path deck = write_deck("switch_deck_", "ramped_rc", kRampedRc);
  const double t_on = 0.5e-3 / 0.9;
  // radau5: the RC exponential to its fifth-order error; euler: to its first-order global error
  // (h/2 tau) (t/tau) e^(-t/tau) 5 V <= 0.93 mV at h = 1 us, tau = 1 ms.
  for (auto [method, tol] : {std::pair{"radau5", 1e-7}, std::pair{"euler", 1e-3}, std::pair{"theta", 1e-6},
                             std::pair{"radau3", 1e-7}}) {
    SCOPED_TRACE(method);
    const Csv csv = run_csv(deck, method, "--probe 'v(out),v(c)'");
    const std::vector<double> t = column(csv, "time"), v = column(csv, "v(out)");
    // A row at the switching time itself, exact for a linear control.
    const size_t k_on = row_at(t, t_on);
    EXPECT_NEAR(t[k_on], t_on, 1e-12);
    for (size_t k = 0; k < t.size(); ++k) {
      const double expected = t[k] < t_on ? 0.0 : 5 * (1 - std::exp(-(t[k] - t_on) / 1e-3));
      ASSERT_NEAR(v[k], expected, tol) << t[k];
    }
  }
}

// A switch on a PULSE with zero-width edges (TR = TF = 0, the common idiom) chops an RC: on at
// 5 us + k 50 us, off 20 us later. On, C1 charges towards 10 V 1000/2001 through 1001 || 1000 ohm
// (tau 5.0025 us); off, it discharges through RL (tau 10 us). The grid times k h lie an ulp on
// either side of the edges (10 * 0.5 us is 4.9999999999999996e-6, the edge 5e-6): the fixed-step
// methods switched half a step late (0.24 V off the closed form for all of them), and the smooth
// method stopped (IDACalcIC: "tout1 too close to t0", its segment starting an ulp before the edge).
TEST(Switches, ZeroWidthPulseEdgesSwitchAtTheEdges) {
  const fs::path deck = write_deck("switch_deck_", "zero_width_edges", R"(chopped RC
VIN in 0 DC 10
VCTL ctl 0 PULSE(0 5 5u 0 0 20u 50u)
S1 in x ctl 0 SMOD
R1 x out 1k
C1 out 0 10n
RL out 0 1k
.model SMOD SW(VT=2.5 VH=0 RON=1 ROFF=1e12)
.tran 0.5u 200u
.end
)");
  const double v_on = 10 * 1000.0 / 2001, tau_on = 1001 * 1000.0 / 2001 * 10e-9, tau_off = 10e-6;
  auto exact = [&](double t) {
    double v = 0, from = 0;
    bool on = false;
    for (int k = 0; k < 4; ++k)
      for (double edge : {5e-6 + k * 50e-6, 25e-6 + k * 50e-6}) {
        if (edge > t) break;
        v = on ? v_on + (v - v_on) * std::exp(-(edge - from) / tau_on) : v * std::exp(-(edge - from) / tau_off);
        on = !on, from = edge;
      }
    return on ? v_on + (v - v_on) * std::exp(-(t - from) / tau_on) : v * std::exp(-(t - from) / tau_off);
  };
  // event and radau5: exact to ROFF's leak (10 nV); smooth: IDA's tolerance; the fixed-step
  // methods to their order at h / tau_on = 0.1 (euler's first-order error (h / 2 tau) e^-1 5 V
  // = 0.09 V; theta's second order).
  for (auto [method, tol] : {std::pair{"event", 1e-7}, std::pair{"smooth", 1e-5}, std::pair{"radau5", 1e-7},
                             std::pair{"radau3", 1e-4}, std::pair{"theta", 3e-3}, std::pair{"euler", 0.1}}) {
    SCOPED_TRACE(method);
    const Csv csv = run_csv(deck, method, "--probe 'v(out)'");
    const std::vector<double> t = column(csv, "time"), v = column(csv, "v(out)");
    ASSERT_EQ(t.size(), 401u);  // the grid, no extra rows: every edge is on it
    for (size_t k = 0; k < t.size(); ++k) ASSERT_NEAR(v[k], exact(t[k]), tol) << t[k];
    // An edge at TSTOP itself (the switch opens at 25 us): none of the breakpoints before TSTOP;
    // the last step interpolated the control and switched at 24.75 us (radau5 4.78 V for 4.906 V).
    const Csv short_run = run_csv(deck, method, "--probe 'v(out)' --tstop 25u");
    const std::vector<double> ts = column(short_run, "time"), vs = column(short_run, "v(out)");
    ASSERT_EQ(ts.size(), 51u);
    EXPECT_NEAR(vs.back(), exact(25e-6), tol);
  }
}

// Two sources' edges 1e-18 s apart, both within rounding of one grid time: the step's start reads
// the controls after both jumps (after the first only, S2 switched half a step late: radau5 5e-4
// off event, where the two agree to 1e-8).
TEST(Switches, EdgesWithinRoundingOfEachOtherAreBothTakenAtTheGridTime) {
  const fs::path deck = write_deck("switch_deck_", "close_edges", R"(close edges
VIN in 0 DC 10
VCTL ctl 0 PULSE(0 5 5u 0 0 20u 50u)
VCT2 ct2 0 PULSE(0 5 5.000000000001u 0 0 7u 50u)
S1 in x ctl 0 SMOD
S2 in y ct2 0 SMOD2
S3 y x ctl 0 SMOD3
R1 x out 1k
R2 y out 2k
C1 out 0 10n
RL out 0 1k
.model SMOD SW(VT=2.5 VH=0 RON=1 ROFF=1e12)
.model SMOD2 SW(VT=1 VH=0.5 RON=1 ROFF=1e12)
.model SMOD3 SW(VT=4 VH=0.5 RON=10 ROFF=1e12)
.tran 0.5u 60u
.end
)");
  const Csv exact = run_csv(deck, "event", "--probe 'v(out)'"), radau5 = run_csv(deck, "radau5", "--probe 'v(out)'");
  const std::vector<double> te = column(exact, "time"), ve = column(exact, "v(out)");
  const std::vector<double> t = column(radau5, "time"), v = column(radau5, "v(out)");
  ASSERT_EQ(t.size(), 121u);
  for (size_t k = 0; k < t.size(); ++k) ASSERT_NEAR(v[k], ve[row_at(te, t[k])], 1e-7) << t[k];
}

// A flyback converter: the switch opens (ROFF = 1 Meg) against the primary's 1 uH of leakage
// (k = 0.99), a mode whose fast rate ROFF/L_leak is 1e12/s, stiff at any step. The trapezoidal
// rule's R(h lambda) is near -1 there: the leakage current rang, i(l1) flipping sign at 6198 of
// the 10200 rows down to -10.3 A, and v(out) reached 58.2 V at 1 ms (event: 19.95 V). The steps
// after a switching into a stiff configuration are now implicit Euler's.
TEST(Switches, ThetaDoesNotRingAfterAFlybacksSwitchOpens) {
  const fs::path deck = write_deck("switch_deck_", "flyback", R"(flyback
VIN in 0 DC 12
L1 in sw 100u
L2 0 s 400u
K1 L1 L2 0.99
S1 sw 0 ctl 0 SMOD
VCTL ctl 0 PULSE(0 5 0 10n 10n 4u 10u)
D1 s out DS
C1 out 0 47u
RL out 0 100
.model SMOD SW(VT=2.5 VH=0.1 RON=0.05 ROFF=1Meg)
.model DS D(VON=0.7 RON=0.05)
.tran 0.1u 1m
.print tran v(out) i(l1)
.end
)");
  const Csv theta = run_csv(deck, "theta"), event = run_csv(deck, "event");
  const std::vector<double> t = column(theta, "time"), v = column(theta, "v(out)"), i = column(theta, "i(l1)");
  const std::vector<double> te = column(event, "time"), ve = column(event, "v(out)");
  // The primary's current only charges and discharges the core: never negative.
  for (size_t k = 0; k < i.size(); ++k) ASSERT_GT(i[k], -1e-3) << t[k];
  // The output within theta's (first-order, at the switchings) error of the exact one.
  for (double at : {0.25e-3, 0.5e-3, 1e-3}) EXPECT_NEAR(v[row_at(t, at)], ve[row_at(te, at)], 0.01 * ve[row_at(te, at)]) << at;
}

// A triangle 0 -> 1 -> 0 V (1 ms up, 1 ms down) into a switch with VT = 0.5 V, VH = 0.205 V and
// a 1 k load: on at 0.705 V (t = 0.705 ms) on the way up, off at 0.295 V (t = 1.705 ms) on the
// way down, not at 0.705 V (t = 1.295 ms). On: v(out) = 5 * 1000/1001. (Neither time is a
// multiple of the 10 us step.)
// A grid time within rounding of TSTOP is TSTOP: 500000 steps of 1e-7 s end at
// 0.049999999999999996 s, and the switched fixed-step loop took one more step of 4e-18 s and
// wrote a second row that prints as t = 0.05 (SPEC 3: times strictly increase).
TEST(Switches, TheLastRowIsWrittenOnce) {
  const fs::path deck = write_deck("switches_", "last_row",
                                   "switch on a pulse\nVIN in 0 DC 10\nVG g 0 PULSE(0 5 0 10n 10n 4u 10u)\n"
                                   "S1 in o g 0 swm\nR1 o 0 100\nC1 o 0 1u\n"
                                   ".model swm SW(VT=2.5 VH=0.5 RON=1 ROFF=1e9)\n.tran 1u 50m\n.end\n");
  const Csv csv = run_csv(deck, "euler", "--step 100n");
  const auto t = column(csv, "time");
  ASSERT_GT(t.size(), 2u);
  EXPECT_DOUBLE_EQ(t.back(), 0.05);
  for (size_t k = 1; k < csv.raw.size(); ++k)  // as printed
    ASSERT_LT(std::stod(csv.raw[k - 1][0]), std::stod(csv.raw[k][0])) << "row " << k;
}

TEST(Switches, HysteresisOpensAtVtMinusVh) {
  const fs::path deck = write_deck("switch_deck_", "hysteresis", R"(switch hysteresis
VDD dd 0 DC 5
VC c 0 PWL(0 0 1m 1 2m 0)
S1 dd out c 0 sw1
R1 out 0 1k
.model sw1 SW(VT=0.5 VH=0.205 RON=1 ROFF=1e12)
.tran 10u 2m
.end
)");
  for (const char* method : {"euler", "radau5"}) {
    SCOPED_TRACE(method);
    const Csv csv = run_csv(deck, method, "--probe 'v(out)'");
    const std::vector<double> t = column(csv, "time"), v = column(csv, "v(out)");
    EXPECT_NEAR(t[row_at(t, 0.705e-3)], 0.705e-3, 1e-12);
    EXPECT_NEAR(t[row_at(t, 1.705e-3)], 1.705e-3, 1e-12);
    for (size_t k = 0; k < t.size(); ++k) {
      const bool on = t[k] >= 0.705e-3 - 1e-12 && t[k] < 1.705e-3 - 1e-12;
      EXPECT_NEAR(v[k], on ? 5 * 1000.0 / 1001 : 5 * 1000 / (1e12 + 1000), 1e-9) << t[k];
    }
  }
}

// W1 is controlled by the current of VSENSE, i = v(in)/1k ramping 0 -> 1 mA over 1 ms; with
// IT = 0.5 mA and IH = 0.105 mA it closes at 0.605 mA, t = 0.605 ms.
TEST(Switches, CurrentControlledSwitch) {
  const fs::path deck = write_deck("switch_deck_", "wswitch", R"(current-controlled switch
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
  const Csv csv = run_csv(deck, "radau5", "--probe 'v(out),i(vsense)'");
  const std::vector<double> t = column(csv, "time"), v = column(csv, "v(out)");
  EXPECT_NEAR(t[row_at(t, 0.605e-3)], 0.605e-3, 1e-12);
  for (size_t k = 0; k < t.size(); ++k)
    EXPECT_NEAR(v[k], t[k] >= 0.605e-3 - 1e-12 ? 5 * 1000.0 / 1001 : 0.0, 1e-8) << t[k];
}

// The state at t = 0: an S whose control is its own output inverted (E1: v(c) = 5 - v(out)) has
// no consistent state (off: v(c) = 5 V asks for on; on: v(c) = 5 mV asks for off); ON on the card
// makes it definite. The op prints the on state's output.
TEST(Switches, StateAtTimeZeroIsConsistentOrRefused) {
  const std::string inverted = R"(switch that opens itself
VDD dd 0 DC 5
S1 dd out c 0 sw1 STATE
R1 out 0 1k
E1 c 0 dd out 1
.model sw1 SW(VT=2.5 RON=1 ROFF=1e12)
.tran 10u 1m
.end
)";
  std::string free_text = inverted, on_text = inverted;
  free_text.replace(free_text.find(" STATE"), 6, "");
  on_text.replace(on_text.find("STATE"), 5, "ON");
  const fs::path free_deck = write_deck("switch_deck_", "inconsistent", free_text), on_deck = write_deck("switch_deck_", "on", on_text);
  const Result r = run_lcspice("op '" + free_deck.string() + "'", free_deck.parent_path());
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_NE(r.err.find("no consistent state of the switches at t = 0"), std::string::npos) << r.err;
  const Result on = run_lcspice("op '" + on_deck.string() + "'", on_deck.parent_path());
  EXPECT_EQ(on.code, 0) << on.err;
  EXPECT_NE(on.out.find("4.99500499"), std::string::npos) << on.out;  // 5 * 1000/1001
  EXPECT_NE(on.out.find("(switch on)"), std::string::npos) << on.out;
}

// A latch: S1 controlled by its own output holds whichever state it starts in.
TEST(Switches, LatchKeepsItsCardState) {
  const std::string latch = R"(self-holding switch
VDD dd 0 DC 5
S1 dd out out 0 sw1 STATE
R1 out 0 1k
.model sw1 SW(VT=1 RON=1 ROFF=1e12)
.tran 10u 100u
.end
)";
  for (const char* state : {"ON", "OFF"}) {
    std::string text = latch;
    text.replace(text.find("STATE"), 5, state);
    const fs::path deck = write_deck("switch_deck_", std::string("latch_") + state, text);
    const Csv csv = run_csv(deck, "euler", "--probe 'v(out)'");
    const double expected = std::string(state) == "ON" ? 5 * 1000.0 / 1001 : 5 * 1000 / (1e12 + 1000);
    for (double v : column(csv, "v(out)")) EXPECT_NEAR(v, expected, 1e-9);
  }
}

// ngspice's manual example (p. 92): v1 a triangle 0 -> 2 -> 0 V over 4 ms, v2 0.9 -> 2 -> 0.4 V,
// the current of vm3 0 -> 2 -> 0 mA; VT = 1 V, VH = 0.2 V (CSW: 1 mA, 0.2 mA), 10 k loads from 2 V.
// s1 (v1): on at 1.2 ms, off at 3.2 ms; s2 (v2, OFF): on at 0.3/0.55 ms, off at 3.5 ms; s3 (v2,
// ON, starting inside the window): on until 3.5 ms; w1: on at 1.2 ms, off at 3.2 ms. The deck
// is read from the shared corpus, its `.probe` card left out (another part of the dialect).
// radau5 (crossings interpolated over a step) and event (located as events) alike.
TEST(Switches, NgspiceManualExampleSwitchesWhereTheControlsCross) {
  const fs::path source = "/work/shared/realworld/ngspice/examples/probe/switches-manual-p92.cir";
  if (!fs::exists(source)) GTEST_SKIP() << source << " is not on this machine";
  std::istringstream in(read_file(source));
  std::string text, line;
  while (std::getline(in, line))
    if (line.rfind(".probe", 0) != 0) text += line + "\n";
  const fs::path deck = write_deck("switch_deck_", "manual_p92", text);
  for (const char* method : {"radau5", "event"}) {
    SCOPED_TRACE(method);
    const Csv csv = run_csv(deck, method, "--probe 'v(10),v(20),v(30),v(40)'");
    const std::vector<double> t = column(csv, "time");
    struct Window { const char* probe; double on, off; double on_value; };
    const Window windows[] = {{"v(10)", 1.2e-3, 3.2e-3, 2 * 1 / 10001.0},
                              {"v(20)", 0.3e-3 / 0.55, 3.5e-3, 2 * 1 / 10001.0},
                              {"v(30)", 0.0, 3.5e-3, 2 * 1 / 10001.0},
                              {"v(40)", 1.2e-3, 3.2e-3, 2 * 1000 / 11000.0}};
    for (const Window& w : windows) {
      SCOPED_TRACE(w.probe);
      const std::vector<double> v = column(csv, w.probe);
      if (w.on > 0) {
        EXPECT_NEAR(t[row_at(t, w.on)], w.on, 1e-12);
      }
      EXPECT_NEAR(t[row_at(t, w.off)], w.off, 1e-12);
      for (size_t k = 0; k < t.size(); ++k) {
        // These switching times are multiples of the 2 us step: the grid row k h and the switching
        // row differ by rounding only, and either state is right there.
        if (std::abs(t[k] - w.on) < 1e-12 || std::abs(t[k] - w.off) < 1e-12) continue;
        const bool on = t[k] > w.on && t[k] < w.off;
        // Off: ROFF = 10 k against the 10 k load; on: RON = 1 ohm (1 k for w1).
        ASSERT_NEAR(v[k], on ? w.on_value : 1.0, 1e-9) << t[k];
      }
    }
  }
}

}  // namespace
}  // namespace lcs

namespace lcs {
namespace {

using namespace cli_testing;

// The family forms a configuration's model once, when first asked, and every configuration has
// the same states (the normal tree does not depend on resistances) but its own matrices.
TEST(Switches, FamilyFormsEachConfigurationOnceWithTheSameStates) {
  const Netlist netlist = parse_netlist_string(R"(three switches
VDD dd 0 DC 5
VC c 0 DC 1
S1 dd a c 0 sw1
S2 a b c 0 sw1
S3 b 0 c 0 sw1 ON
C1 a 0 1u
C2 b 0 1u
.model sw1 SW(VT=0.5 RON=1 ROFF=1e6)
.tran 1u 1m
.end
)",
                                               "family.cir");
  const CircuitModel base = CircuitModel::build(netlist, {});
  SwitchFamily family(base);
  ASSERT_EQ(family.switches().size(), 3u);
  EXPECT_EQ(family.config_of(base), (SwitchConfig{0, 0, 1}));
  EXPECT_EQ(&family.model({0, 0, 1}), &base);  // its own configuration: the base model itself
  EXPECT_EQ(family.formed(), 0);
  const CircuitModel& on = family.model({1, 1, 0});
  EXPECT_EQ(family.formed(), 1);
  EXPECT_EQ(&family.model({1, 1, 0}), &on);
  EXPECT_EQ(family.formed(), 1);
  ASSERT_EQ(on.states().size(), base.states().size());
  for (size_t k = 0; k < on.states().size(); ++k) EXPECT_EQ(on.states()[k].label, base.states()[k].label);
  EXPECT_GT((on.lcs().A - base.lcs().A).cwiseAbs().maxCoeff(), 1.0);
  // With v(c) = 1 V > VT every switch asks to be on; S3's ON is the card's, kept at t = 0.
  EXPECT_EQ(initial_configuration(family, family.config_of(base), false), (SwitchConfig{1, 1, 1}));
}

// `analyze` lists the switches with their thresholds and the state they start in, and the
// controlled sources with their laws.
TEST(Switches, AnalyzeListsSwitchesAndControlledSources) {
  const Result r = run_lcspice("analyze '" + circuit("switch_hysteresis").string() + "'", scratch_dir("analyze_sw"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("controlled sources and switches (switches: the configuration at t = 0):"), std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("switch s1: controlled by v(c,0), on above 1.2 V, off below 0.8 V (VT = 1, VH = 0.2), "
                       "RON = 1 ohm, ROFF = 10000 ohm, off (OFF on the card)"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("switch w1: controlled by i(vsense), on above 0.0012 A, off below 0.0008 A"), std::string::npos)
      << r.out;
  const Result c = run_lcspice("analyze '" + circuit("controlled_sources").string() + "'", scratch_dir("analyze_cs"));
  ASSERT_EQ(c.code, 0) << c.err;
  EXPECT_NE(c.out.find("voltage-controlled voltage source e1: v = 100000 * v(0,m)"), std::string::npos) << c.out;
  EXPECT_NE(c.out.find("current-controlled voltage source h1: v = 1000 ohm * i(vsense)"), std::string::npos) << c.out;
}

}  // namespace
}  // namespace lcs
