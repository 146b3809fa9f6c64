#include "ngspice/deck_translation.h"

#include <algorithm>

#include <gtest/gtest.h>

#include "solver/devices/diode.h"
#include "tests/support/netlist_builder.h"

namespace lcs {
namespace {

using testing::NetlistBuilder;

bool has_line(const TranslatedDeck& d, const std::string& line) {
  return std::find(d.lines.begin(), d.lines.end(), line) != d.lines.end();
}

TEST(DeckTranslation, IdealDiodeBecomesThresholdSourcePlusSharpShockley) {
  NetlistBuilder b;
  b.tran(1e-5, 1e-3, false);
  b.v("v1", "in", "0", NetlistBuilder::sin(0, 5, 1e3)).d("d1", "in", "out", 0.7, 0.2).r("r1", "out", "0", 100);
  CircuitModel m = CircuitModel::build(b.build(), {});
  TranslationOptions o;
  o.emission = 0.02;
  TranslatedDeck d = translate_to_ngspice(m, {{Probe::Kind::ElementCurrent, "d1", "", {}},
                                              {Probe::Kind::NodeVoltage, "out", "", {}}}, o);
  EXPECT_TRUE(has_line(d, "v_thr_d1 in lcs_d1_mid DC 0.7"));
  EXPECT_TRUE(has_line(d, "d1 lcs_d1_mid out lcs_m_d1"));
  EXPECT_TRUE(has_line(d, ".model lcs_m_d1 D(IS=1e-14 N=0.02 RS=0.2)"));
  EXPECT_TRUE(has_line(d, ".tran 1e-05 0.001 0 1e-05"));
  EXPECT_EQ(d.probes.at("i(d1)").plus, "v_thr_d1#branch");
  EXPECT_EQ(d.probes.at("v(out)").plus, "out");
  EXPECT_EQ(d.lines.back(), ".end");
}

TEST(DeckTranslation, FittedCardsKeepTheirShockleyParameters) {
  Netlist n = [] {
    NetlistBuilder b;
    b.tran(1e-5, 1e-3, true);
    b.v("v1", "in", "0", NetlistBuilder::dc(5)).d("d1", "in", "out").r("r1", "out", "0", 100);
    return b.build();
  }();
  DiodeModel& card = n.diode_models.begin()->second;
  card.von.reset();
  card.ron.reset();
  card.is = 2e-9;
  card.n = 1.8;
  card.rs = 0.5;
  CircuitModel m = CircuitModel::build(n, {});
  TranslatedDeck d = translate_to_ngspice(m, {}, {});
  EXPECT_TRUE(has_line(d, "v_thr_d1 in lcs_d1_mid DC 0"));
  EXPECT_TRUE(has_line(d, ".model lcs_m_d1 D(IS=2e-09 N=1.8 RS=0.5)"));
  EXPECT_TRUE(has_line(d, ".tran 1e-05 0.001 0 1e-05 uic"));
  EXPECT_TRUE(d.ideal_diodes.empty());
}

TEST(DeckTranslation, ReversedDiodeHookSubcircuitNamesAmmetersAndJumps) {
  NetlistBuilder b;
  b.tran(1e-6, 1e-3, false);
  b.v("v1", "in", "0", NetlistBuilder::pulse({0, 1, 1e-4, 0, 0, 2e-4, 5e-4}));
  b.d("x1.d1", "in", "x1.mid", 0.6).r("x1.r1", "x1.mid", "0", 50).l("l1", "in", "0", 1e-3);
  CircuitModel m = CircuitModel::build(b.build(), {});
  TranslationOptions o;
  o.reversed_diodes = {"x1.d1"};
  TranslatedDeck d = translate_to_ngspice(m, {{Probe::Kind::ElementCurrent, "x1.r1", "", {}}}, o);
  EXPECT_TRUE(has_line(d, "v_thr_x1.d1 x1.mid lcs_x1.d1_mid DC 0.6"));  // anode and cathode swapped
  EXPECT_TRUE(has_line(d, "d_x1.d1 lcs_x1.d1_mid in lcs_m_x1.d1"));
  EXPECT_TRUE(has_line(d, "v_amm_x1.r1 x1.mid lcs_x1.r1_amm DC 0"));
  EXPECT_TRUE(has_line(d, "r_x1.r1 lcs_x1.r1_amm 0 50"));
  // Jumps become 1 ns edges (1e-6 TSTOP) that end at the jump instants 1e-4 and 3e-4.
  EXPECT_TRUE(has_line(d, "v1 in 0 PULSE(0 1 9.9999e-05 1e-09 1e-09 0.000199999 0.0005)"))
      << d.lines[2];
}

TEST(SmoothEquivalent, IdealLawMapsToSeriesThresholdAndEmission) {
  DiodeModel card;
  ResolvedDiodeLaw law;
  law.law = {0.65, 0.3};
  SmoothDiodeLaw s = smooth_equivalent(card, law, 0.05, 1e-14);
  EXPECT_EQ(s.series_von, 0.65);
  EXPECT_EQ(s.n, 0.05);
  EXPECT_EQ(s.rs, 0.3);
  EXPECT_EQ(s.is, 1e-14);
}

}  // namespace
}  // namespace lcs
