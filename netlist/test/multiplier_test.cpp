// ngspice's `m` multiplier (m copies in parallel) on element cards and subcircuit instances, the
// EXP/SFFM/AM and SINE source cards, and negative couplings, as the reader stores them.
#include <gtest/gtest.h>

#include "netlist/test/parse_helpers.h"

namespace lcs {
namespace {

using test::element;
using test::parse;

TEST(ParseMultiplier, ElementCardsScaleToTheirParallelEquivalent) {
  Netlist n = parse(
      "t\nV1 a 0 1\nR1 a 0 1k m=2\nC1 a 0 1u M=3 IC=2\nL1 a b 1m ic=1m m=4\nR2 b 0 1\n"
      "D1 a 0 dm\nD2 a 0 dm 2\nD3 a 0 dm 2 m=3\nD4 a 0 dm area=0.5 M=4\n.model dm D\n"
      "I1 0 a SIN(0 1 1k) m=2\nQ1 a a 0 qm m=2\n.model qm NPN\n");
  EXPECT_DOUBLE_EQ(element(n, "r1").value, 500);     // R/m
  EXPECT_DOUBLE_EQ(element(n, "c1").value, 3e-6);    // C*m
  EXPECT_EQ(element(n, "c1").ic, 2.0);               // a voltage: the same on every copy
  EXPECT_DOUBLE_EQ(element(n, "l1").value, 0.25e-3); // L/m
  EXPECT_EQ(element(n, "l1").ic, 1e-3);
  EXPECT_EQ(element(n, "d1").value, 1.0);            // a diode's value: area times m
  EXPECT_EQ(element(n, "d2").value, 2.0);
  EXPECT_EQ(element(n, "d3").value, 6.0);
  EXPECT_EQ(element(n, "d4").value, 2.0);
  EXPECT_EQ(element(n, "i1").waveform.params[1], 2.0);  // VA*m
  EXPECT_EQ(element(n, "q1").value, 2.0);
}

// ngspice manual, "Paralleling devices with multiplier m": an X line's m multiplies the m of
// every R, C, L, D, Q, I inside, recursively through nested instances. (The ngspice 39 library
// on this machine does not multiply: it overrides an inner m by the outer one.)
TEST(ParseMultiplier, SubcircuitInstancesMultiplyRecursively) {
  Netlist n = parse(
      "t\n.subckt inner a b\nR1 a b 1k m=2\nC1 a b 1u\nV1 a c 1\nR2 c b 10\n.ends\n"
      ".subckt outer a b\nX1 a b inner m=5\nL1 a b 1m\nK1 L1 L2 -0.5\nL2 a b 1m\n.ends\n"
      "X1 p 0 outer m=3\nX2 q 0 inner\nR9 p q 1\n");
  EXPECT_DOUBLE_EQ(element(n, "x1.x1.r1").value, 1e3 / 30);  // 2 * 5 * 3
  EXPECT_DOUBLE_EQ(element(n, "x1.x1.c1").value, 15e-6);
  EXPECT_DOUBLE_EQ(element(n, "x1.x1.r2").value, 10.0 / 15);
  EXPECT_EQ(element(n, "x1.x1.v1").waveform.dc, 1.0);  // a voltage source is the same in every copy
  EXPECT_DOUBLE_EQ(element(n, "x1.l1").value, 1e-3 / 3);
  EXPECT_EQ(element(n, "x1.k1").value, -0.5);          // k is a ratio: unchanged
  EXPECT_DOUBLE_EQ(element(n, "x2.r1").value, 500);    // another instance keeps its own m
}

// ngspice 39 measured: `X1 1 0 s m=2` with `.subckt s a b params: m=1`, `r1 a b {1k*m}` draws
// 0.5 mA from 1 V: the declared parameter, and no multiplier.
TEST(ParseMultiplier, ASubcircuitThatDeclaresMTakesItAsAParameter) {
  Netlist n = parse("t\n.subckt s a b params: m=1\nR1 a b {1k*m}\n.ends\nX1 p 0 s m=2\nR2 p 0 1\n");
  EXPECT_DOUBLE_EQ(element(n, "x1.r1").value, 2e3);
}

TEST(ParseSources, ExpSffmAmAndSineCards) {
  Netlist n = parse(
      "t\nV1 a 0 EXP(1 3 0.2m 0.1m 0.6m 0.3m)\nV2 b 0 sffm 0.1 2 200 0.01 10k\n"
      "I1 c 0 AM(0.5 2 1.8 1k 100k 1m 0 0)\nV_V2 10 0 dc 0.0 sine(0.0 0.3 440.0 0 0)\n"
      "R1 a 0 1\nR2 b 0 1\nR3 c 0 1\nR4 10 0 1\n.tran 1u 2m\n");
  const Waveform& e = element(n, "v1").waveform;
  EXPECT_EQ(e.kind, Waveform::Kind::Exp);
  EXPECT_EQ(e.params, (std::vector<double>{1, 3, 0.2e-3, 0.1e-3, 0.6e-3, 0.3e-3}));
  const Waveform& f = element(n, "v2").waveform;
  EXPECT_EQ(f.kind, Waveform::Kind::Sffm);
  EXPECT_EQ(f.params, (std::vector<double>{0.1, 2, 200, 0.01, 10e3, 0, 0, 0}));
  EXPECT_EQ(element(n, "i1").waveform.kind, Waveform::Kind::Am);
  const Waveform& s = element(n, "v_v2").waveform;
  EXPECT_EQ(s.kind, Waveform::Kind::Sin);
  EXPECT_EQ(s.params, (std::vector<double>{0, 0.3, 440, 0, 0, 0}));
}

// ngspice's PWL delay: value(t) = pwl(t - TD).
TEST(ParseSources, PwlDelayShiftsEveryTimePoint) {
  Netlist n = parse("t\nV1 a 0 PWL(0 0 1m 1) td=2m\nR1 a 0 1\n");
  const std::vector<double>& p = element(n, "v1").waveform.params;
  ASSERT_EQ(p.size(), 4u);
  EXPECT_DOUBLE_EQ(p[0], 2e-3);
  EXPECT_DOUBLE_EQ(p[2], 3e-3);
  EXPECT_EQ(p[3], 1.0);
}

// ngspice's PWL repeat, r= a time point (before TD= shifts it, in either order on the card).
TEST(ParseSources, PwlRepeatNamesATimePoint) {
  for (const char* options : {"r=1m td=2m", "td=2m r=1m"}) {
    Netlist n = parse(std::string("t\nV1 a 0 PWL(0 0 1m 1 3m 0) ") + options + "\nR1 a 0 1\n");
    const Waveform& w = element(n, "v1").waveform;
    EXPECT_DOUBLE_EQ(w.params[0], 2e-3) << options;
    ASSERT_TRUE(w.repeat_from.has_value()) << options;
    EXPECT_DOUBLE_EQ(*w.repeat_from, 3e-3) << options;
    EXPECT_DOUBLE_EQ(w.value(5e-3 + 1e-3), 0.5) << options;  // one period (2 ms) after 4 ms
  }
  // A repeat point below 0 after the shift; r= within rounding of a point repeats from that point;
  // r=-1 (below -0.5: ngspice's "no repeat").
  Netlist shifted = parse("t\nV1 a 0 PWL(0 0 1m 1 2m 0) td=-0.5m r=0\nR1 a 0 1\n");
  EXPECT_DOUBLE_EQ(*element(shifted, "v1").waveform.repeat_from, -0.5e-3);
  EXPECT_DOUBLE_EQ(element(shifted, "v1").waveform.value(2.5e-3), 1.0);  // 3 ms of the list again
  Netlist near = parse("t\nV1 a 0 PWL(0 0 1m 1 2m 0 3m 1) r=1.0000000000001m\nR1 a 0 1\n");
  EXPECT_EQ(*element(near, "v1").waveform.repeat_from, 1e-3);
  Netlist none = parse("t\nV1 a 0 PWL(0 0 1m 1 2m 0) r=-1\nR1 a 0 1\n");
  EXPECT_FALSE(element(none, "v1").waveform.repeat_from.has_value());
  EXPECT_EQ(test::diag("t\nV1 a 0 PWL(0 0 1m 1) r=0.5m\nR1 a 0 1\n"),
            "t.cir:2:24: error: pwl repeat time r=0.5m of 'v1' must be one of its time points before the last\n"
            "V1 a 0 PWL(0 0 1m 1) r=0.5m\n                       ^~~~");
  EXPECT_EQ(test::diag("t\nV1 a 0 PWL(0 0 1m 1) r=1m\nR1 a 0 1\n"),
            "t.cir:2:24: error: pwl repeat time r=1m of 'v1' must be one of its time points before the last\n"
            "V1 a 0 PWL(0 0 1m 1) r=1m\n                       ^~");
}

TEST(ParseSources, SffmModulationIndexAboveFcOverFsIsLimitedWithAWarning) {
  Netlist n = parse("t\nV2 10 0 SFFM 0.1 2 200 45 10k 1m 0 0\nR2 10 0 1\n.tran 1u 2m\n");
  EXPECT_DOUBLE_EQ(element(n, "v2").waveform.params[3], 0.02);
  ASSERT_EQ(n.warnings.size(), 1u);
  EXPECT_EQ(n.warnings[0].substr(0, n.warnings[0].find('\n')),
            "t.cir:2:24: warning: sffm modulation index 45 of 'v2' is limited to FC/FS (as ngspice does)");
}

TEST(ParseElements, NegativeAndZeroCouplings) {
  Netlist n = parse("t\nL1 a 0 1\nL2 b 0 1\nL3 c 0 1\nK1 L1 L2 -1\nK2 L2 L3 0\nR1 a b 1\nR2 c 0 1\n");
  EXPECT_EQ(element(n, "k1").value, -1.0);
  EXPECT_EQ(element(n, "k2").value, 0.0);
}

}  // namespace
}  // namespace lcs

namespace lcs {
namespace {

// m copies of a G or F source draw m times the current; E, H and switches are not scaled.
TEST(ParseMultiplier, ControlledCurrentSourcesScaleInsideAnInstance) {
  Netlist n = parse(
      "t\n.subckt s a b\nG1 a b a 0 2m\nF1 a b vs 3\nE1 c 0 a 0 4\nH1 d 0 vs 5\nVs a e 0\nR1 e b 1k\n"
      "R2 c 0 1\nR3 d 0 1\n.ends\nX1 p 0 s m=3\nR9 p 0 1\n");
  EXPECT_DOUBLE_EQ(element(n, "x1.g1").value, 6e-3);
  EXPECT_DOUBLE_EQ(element(n, "x1.f1").value, 9.0);
  EXPECT_DOUBLE_EQ(element(n, "x1.e1").value, 4.0);
  EXPECT_DOUBLE_EQ(element(n, "x1.h1").value, 5.0);
}

}  // namespace
}  // namespace lcs
