// PSpice's VSWITCH and ISWITCH models (Xyce reads them too), end to end: read as ideal switches at
// the midpoint of VON and VOFF (ION and IOFF), closing as the control falls when VON < VOFF; the
// levels and instants against their closed forms, and agreement with ngspice through `validate`,
// whose deck writes a reversed switch as ngspice's SW on the negated control.
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/cli_support.h"

namespace lcs {
namespace {

using namespace cli_testing;

double parallel(double a, double b) { return a * b / (a + b); }

// Xyce's regression deck VSWITCH/Vswitch_A1.cir (a NOR gate of two switches and a 1k pull-up),
// its inputs as written: each output level is the pull-up against the switches' RON/ROFF.
TEST(PspiceSwitch, XyceNorGateLevels) {
  const auto deck = write_deck("pspice_switch_", "nor",
                               "NOR gate of voltage switches\nRL 2 1 1K\nS1 1 0 3 0 SW\nS2 1 0 4 0 SW\nVCC 2 0 5\n"
                               "V3 3 0 PWL(0 0 1U 0 1.01U 5 2U 5 2.01U 0 3U 0 3.01U 5)\nR3 3 0 1\n"
                               "V4 4 0 PWL (0 0 2U 0 2.01U 5)\nR4 4 0 1\n"
                               ".MODEL SW VSWITCH(RON=1 ROFF=1MEG VON=1 VOFF=0)\n.TRAN 0.02U 4U\n"
                               ".PRINT TRAN V(1) V(3) V(4)\n.END\n");
  const Csv csv = run_csv(deck, "");
  const std::vector<double> t = column(csv, "time"), v1 = column(csv, "v(1)");
  auto level = [](double r_down) { return 5 * r_down / (1e3 + r_down); };
  const double off = 1e6, on = 1;
  struct Expect {
    double t, v;
  } expected[] = {{0.5e-6, level(parallel(off, off))},
                  {1.5e-6, level(parallel(on, off))},
                  {2.5e-6, level(parallel(off, on))},
                  {3.5e-6, level(parallel(on, on))}};
  for (const Expect& e : expected) EXPECT_NEAR(v1[row_at(t, e.t)], e.v, 1e-12 * 5) << e.t;
  EXPECT_NEAR(level(parallel(off, off)), 4.99002, 1e-5);  // a logic 1, as the deck's comment says
}

// VON = 0 < VOFF = 5: the switch closes as v(c) falls through 2.5 V (t = 0.5 ms on the ramp
// 5 - 5 t/1ms) and opens as it rises through it again (t = 1.5 ms).
const char* const kReversedDeck =
    "reversed VSWITCH\nV1 in 0 5\nVc c 0 PWL(0 5 1m 0 2m 5)\nS1 in out c 0 SINV\nR1 out 0 1k\n"
    ".MODEL SINV VSWITCH(RON=1 ROFF=1E9 VON=0 VOFF=5)\n.TRAN 10u 2m\n.END\n";

// The control current i(vsense) = v(c)/1k = 2 mA t/1ms rising, closes past the midpoint of
// IOFF = 0.5 mA and ION = 1.5 mA (t = 0.5 ms) and opens below it on the way down (t = 1.5 ms).
const char* const kCurrentDeck =
    "ISWITCH\nV1 in 0 5\nVc c 0 PWL(0 0 1m 2 2m 0)\nRc c cs 1k\nVsense cs 0 0\nW1 in out Vsense IMOD\n"
    "R1 out 0 1k\n.MODEL IMOD ISWITCH(ION=1.5mA IOFF=0.5mA RON=1 ROFF=1E9)\n.TRAN 10u 2m\n.END\n";

void expect_closed_between(const Csv& csv, double t_on, double t_off) {
  const std::vector<double> t = column(csv, "time"), out = column(csv, "v(out)");
  const double closed = 5 * 1e3 / (1e3 + 1), open = 5 * 1e3 / (1e3 + 1e9);
  for (size_t k = 0; k < t.size(); ++k) {
    if (std::abs(t[k] - t_on) < 1e-9 || std::abs(t[k] - t_off) < 1e-9) continue;  // the instant itself
    const bool on = t[k] > t_on && t[k] < t_off;
    EXPECT_NEAR(out[k], on ? closed : open, 1e-9) << t[k];
  }
}

TEST(PspiceSwitch, ReversedVoltageSwitchClosesAsItsControlFalls) {
  const auto deck = write_deck("pspice_switch_", "reversed", kReversedDeck);
  const Result r = run_lcspice("run '" + deck.string() + "' -o '" + (deck.parent_path() / "out.csv").string() + "'",
                               deck.parent_path());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("reversed.cir:6:13: warning: switch model 'sinv': VSWITCH (PSpice): its smooth passage from "
                       "ROFF at VOFF = 5 V to RON at VON = 0 V is modelled as an ideal switch at their midpoint, on "
                       "below 2.5 V"),
            std::string::npos)
      << r.err;
  expect_closed_between(parse_csv(read_file(deck.parent_path() / "out.csv")), 0.5e-3, 1.5e-3);
  expect_closed_between(run_csv(deck, "euler"), 0.5e-3, 1.5e-3);
}

TEST(PspiceSwitch, CurrentSwitchAtTheMidpointOfIonAndIoff) {
  const auto deck = write_deck("pspice_switch_", "current", kCurrentDeck);
  expect_closed_between(run_csv(deck, ""), 0.5e-3, 1.5e-3);
}

// ngspice has no VSWITCH: validate writes SW(VT=-2.5) on the swapped control nodes, and for the
// current switch an H source of gain -1 when reversed (here not: CSW(IT=1m)).
TEST(PspiceSwitch, AgreesWithNgspice) {
  for (const char* text : {kReversedDeck, kCurrentDeck}) {
    const auto deck = write_deck("pspice_switch_validate_", text == kReversedDeck ? "reversed" : "current", text);
    const Result r = run_lcspice("validate '" + deck.string() + "' --tol 1e-3", deck.parent_path());
    EXPECT_EQ(r.code, 0) << r.out << r.err;
    EXPECT_NE(r.out.find("PASS: every probe within"), std::string::npos) << r.out;
  }
  const auto deck = write_deck("pspice_switch_validate_", "deck", kReversedDeck);
  const Result r = run_lcspice("validate '" + deck.string() + "' --print-deck", deck.parent_path());
  EXPECT_NE(r.out.find("s1 in out 0 c lcs_sw_s1\n"), std::string::npos) << r.out;  // nc+ nc- swapped
  EXPECT_NE(r.out.find(".model lcs_sw_s1 SW(VT=-2.5 VH=0 RON=1 ROFF=1000000000)"), std::string::npos) << r.out;
}

// A reversed current switch: on while the control current is below 1 mA (ION = 0 < IOFF = 2 mA),
// through ngspice's H source of gain -1 on the control.
TEST(PspiceSwitch, ReversedCurrentSwitchAgreesWithNgspice) {
  const auto deck = write_deck("pspice_switch_validate_", "reversed_current",
                               "reversed ISWITCH\nV1 in 0 5\nVc c 0 PWL(0 0 1m 2 2m 0)\nRc c cs 1k\nVsense cs 0 0\n"
                               "W1 in out Vsense IMOD\nR1 out 0 1k\n"
                               ".MODEL IMOD ISWITCH(ION=0 IOFF=2mA RON=1 ROFF=1E9)\n.TRAN 10u 2m\n.END\n");
  const Csv csv = run_csv(deck, "");
  const std::vector<double> t = column(csv, "time"), out = column(csv, "v(out)");
  EXPECT_NEAR(out[row_at(t, 0.2e-3)], 5 * 1e3 / (1e3 + 1), 1e-9);   // 0.4 mA: on
  EXPECT_NEAR(out[row_at(t, 1.0e-3)], 5 * 1e3 / (1e3 + 1e9), 1e-9);  // 2 mA: off
  EXPECT_NEAR(out[row_at(t, 1.8e-3)], 5 * 1e3 / (1e3 + 1), 1e-9);   // 0.4 mA: on again
  const Result r = run_lcspice("validate '" + deck.string() + "' --tol 1e-3", deck.parent_path());
  EXPECT_EQ(r.code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("PASS: every probe within"), std::string::npos) << r.out;
}

// With UIC ngspice's t = 0 row comes out of its first step's companion models: an inductor
// started at 0 A behind 1 MEG reads as L/h there, so the node between them is at 0.24 V in
// ngspice's row where the start has it at the supply, 24 V (the inductor carries no current, so
// the megohm drops nothing). The verdict starts at the first step, and says so.
TEST(ValidateUic, JudgedFromTheFirstStep) {
  const auto deck = write_deck("validate_uic_", "inductor",
                               "inductor behind a megohm\nV1 in 0 24\nR1 in sw 1meg\nL1 sw out 100u IC=0\nR2 out 0 5\n"
                               "C1 out 0 1u IC=0\nD1 0 sw dmod\n.model dmod d(von=0.7 ron=0.01)\n.tran 1u 100u UIC\n");
  const Csv csv = run_csv(deck, "");
  EXPECT_EQ(column(csv, "v(sw)")[0], 24.0);
  const Result r = run_lcspice("validate '" + deck.string() + "'", deck.parent_path());
  EXPECT_EQ(r.code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("  UIC: ngspice's t = 0 row is its first step's companion-model solve, not the start;\n"
                       "  judged from the first step on\n"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("PASS: every probe within"), std::string::npos) << r.out;
}

}  // namespace
}  // namespace lcs
