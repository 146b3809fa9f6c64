// The line through a junction's curve (junction_fit.h): closed forms for the pure logarithm.
#include <gtest/gtest.h>

#include <cmath>

#include "solver/devices/diode.h"
#include "solver/devices/junction_fit.h"
#include "solver/integrators/diode_refit.h"

namespace lcs {
namespace {

// v = Vt ln(i / IBV) + BV (a breakdown curve, RS = 0) over [1, 9] mA: the chord's slope is
// Vt ln 9 / 8 mA; the curve's slope Vt / i equals it at i* = 8 mA / ln 9; the chord lies below
// by d = Vt (ln(i*/1 mA) - ln 9 (i* - 1 mA) / 8 mA), and the minimax line is the chord raised by
// d / 2, its worst error d / 2.
TEST(JunctionFit, MinimaxLineOfALogarithmIsTheChordRaisedByHalfItsGap) {
  const double vt = kThermalVoltage;
  const JunctionCurve c = breakdown_curve(5.0, 1e-3, 1.0, 0.0);
  const double istar = 8e-3 / std::log(9.0);
  const double d = vt * (std::log(istar / 1e-3) - std::log(9.0) * (istar - 1e-3) / 8e-3);
  const LineFit chord = chord_fit(c, 1e-3, 9e-3);
  EXPECT_NEAR(chord.law.ron, vt * std::log(9.0) / 8e-3, 1e-12);
  EXPECT_NEAR(chord.law.von, 5.0 - chord.law.ron * 1e-3, 1e-12);
  EXPECT_NEAR(chord.max_error, d, 1e-12);
  const LineFit best = minimax_fit(c, 1e-3, 9e-3);
  EXPECT_NEAR(best.law.ron, chord.law.ron, 1e-12);
  EXPECT_NEAR(best.law.von, chord.law.von + d / 2, 1e-12);
  EXPECT_NEAR(best.max_error, d / 2, 1e-12);
  EXPECT_NEAR(best.error_fraction, d / 2 / 5.0, 1e-12);  // v(i1) = BV at i1 = IBV
  // The error is d / 2 at both ends and -d / 2 at i*.
  for (double i : {1e-3, 9e-3})
    EXPECT_NEAR(best.law.von + best.law.ron * i - c.voltage(i), d / 2, 1e-12);
  EXPECT_NEAR(best.law.von + best.law.ron * istar - c.voltage(istar), -d / 2, 1e-12);
}

// One current: the tangent there (exact at that current).
TEST(JunctionFit, OneCurrentGivesTheTangent) {
  const JunctionCurve c = forward_curve(1e-14, 1.0, 2.0);
  const LineFit t = minimax_fit(c, 5e-6, 5e-6);
  EXPECT_NEAR(t.law.ron, kThermalVoltage / (1e-14 + 5e-6) + 2.0, 1e-9);
  EXPECT_NEAR(t.law.von + t.law.ron * 5e-6, c.voltage(5e-6), 1e-12);
  EXPECT_EQ(t.max_error, 0.0);
}

// A circuit range makes the card's law the minimax line over it; VON/RON on the card win.
TEST(JunctionFit, ResolvedLawOverACircuitRange) {
  DiodeModel card;
  const ResolvedDiodeLaw r = resolve_diode_law(card, 10e-3, CurrentRange{1e-6, 5e-6});
  const LineFit f = minimax_fit(forward_curve(1e-14, 1.0, 0.0), 1e-6, 5e-6);
  EXPECT_TRUE(r.fitted);
  EXPECT_TRUE(r.circuit_fit);
  EXPECT_EQ(r.law.von, f.law.von);
  EXPECT_EQ(r.law.ron, f.law.ron);
  EXPECT_EQ(r.fit_i1, 1e-6);
  card.von = 0.7;
  EXPECT_FALSE(resolve_diode_law(card, 10e-3, CurrentRange{1e-6, 5e-6}).fitted);
  card.bv = 5.1;
  const ResolvedDiodeLaw z = resolve_breakdown_law(card, 10e-3);
  EXPECT_EQ(z.law.von, 5.1);
  EXPECT_EQ(z.law.ron, 0.0);  // RON (absent: 0); Rrev would take its place
  card.rrev = 3.0;
  EXPECT_EQ(resolve_breakdown_law(card, 10e-3).law.ron, 3.0);
}

// NBV (ngspice's breakdown emission coefficient) is the breakdown curve's: a card with N = 1 and
// NBV = 2 fits the line of BV + 2 Vt ln(i / IBV) + RS i, not of N Vt (was ignored with a
// warning: a 1N4733 card's Zener voltage 8 mV off ngspice's on the same card).
TEST(JunctionFit, BreakdownFitUsesNbv) {
  DiodeModel card;
  card.is = 1e-14;
  card.n = 1.0;
  card.rs = 0.5;
  card.bv = 5.1;
  card.ibv = 1e-3;
  card.nbv = 2.0;
  const CurrentRange range{2e-3, 20e-3};
  const ResolvedDiodeLaw z = resolve_breakdown_law(card, 10e-3, range);
  const LineFit expected = minimax_fit(breakdown_curve(5.1, 1e-3, 2.0, 0.5), 2e-3, 20e-3);
  EXPECT_TRUE(z.fitted);
  EXPECT_EQ(z.law.von, expected.law.von);
  EXPECT_EQ(z.law.ron, expected.law.ron);
  // The chord's slope over [2, 20] mA: 2 Vt ln 10 / 18 mA + RS.
  EXPECT_NEAR(z.law.ron, 2 * kThermalVoltage * std::log(10.0) / 18e-3 + 0.5, 1e-9);
  card.nbv.reset();
  EXPECT_NEAR(resolve_breakdown_law(card, 10e-3, range).law.ron, kThermalVoltage * std::log(10.0) / 18e-3 + 0.5, 1e-9);
}

// The range of a diode's conducting samples: its off phases (0 A) left out, [10 % quantile, max].
TEST(JunctionFit, ConductingRangeLeavesTheOffPhasesOut) {
  std::vector<double> samples(50, 0.0);
  for (int k = 1; k <= 10; ++k) samples.push_back(k * 1e-6);
  const CurrentRange r = conducting_range(samples, 0.1);
  EXPECT_DOUBLE_EQ(r.hi, 10e-6);
  EXPECT_EQ(r.lo, 1e-6);  // index floor(0.1 * 9) = 0 of the ten conducting samples
  EXPECT_TRUE(conducting_range(std::vector<double>(5, 0.0), 0.1).empty());
}

}  // namespace
}  // namespace lcs
