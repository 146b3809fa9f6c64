// Smaller pieces of the ngspice (and LTspice) dialect: .probe, .print/.save entries lcspice does
// not write, a diode without a model, LTRA flags, elements with both terminals on one node.
#include <gtest/gtest.h>

#include "netlist/netlist.h"
#include "netlist/test/parse_helpers.h"

namespace lcs {
namespace {

std::string names(const std::vector<Probe>& probes) { return test::probe_names(probes); }

TEST(NgspiceDialect, ProbeCardIsLikeSave) {
  Netlist n = test::parse("t\nR1 a 0 1\nV1 a 0 1\n.probe alli\n");
  EXPECT_TRUE(n.probes.empty());  // alli, like all: the default probes
  EXPECT_TRUE(n.warnings.empty());
  n = test::parse("t\nR1 a 0 1\nV1 a 0 1\n.probe v(a) i(r1)\n.save allv\n");
  EXPECT_EQ(names(n.probes), "v(a) i(r1) ");
}

TEST(NgspiceDialect, PrintEntriesThatAreNotProbesAreSkippedWithAWarningEach) {
  Netlist n = test::parse(
      "t\nR1 1 0 1\nV1 1 0 1\nD1 1 0 dm\n.model dm d\n"
      ".print tran v(1) v(1)*i(r1) FORMAT=NOQUOTE i(v1)\n"
      ".save @d1[id] p(r1) v(1, 0) all\n");
  EXPECT_EQ(names(n.probes), "v(1) i(v1) v(1,0) ");
  ASSERT_EQ(n.warnings.size(), 4u);
  EXPECT_EQ(n.warnings[0], "t.cir:6:18: warning: '.print' entry 'v(1)*i(r1)' is ignored: expressions are not "
                           "written by lcspice (only v(), i() probes)");
  EXPECT_EQ(n.warnings[1], "t.cir:6:29: warning: '.print': FORMAT= is ignored (lcspice writes CSV)");
  EXPECT_EQ(n.warnings[2], "t.cir:7:7: warning: '.save' entry '@d1[id]' is ignored: device parameters are not "
                           "probes lcspice writes");
  EXPECT_EQ(n.warnings[3], "t.cir:7:15: warning: '.save' entry 'p(r1)' is ignored: power probes are not written by lcspice");
  // Xyce writes an expression in braces.
  n = test::parse("t\nR1 3 0 1\nV1 3 0 1\n.PRINT TRAN I(V1) V(3) {V(3)/I(V1)}\n");
  EXPECT_EQ(names(n.probes), "i(v1) v(3) ");
  ASSERT_EQ(n.warnings.size(), 1u);
  EXPECT_EQ(n.warnings[0], "t.cir:4:24: warning: '.print' entry '{V(3)/I(V1)}' is ignored: expressions are not "
                           "written by lcspice (only v(), i() probes)");
  // A probe that is neither is still an error.
  EXPECT_EQ(test::diag("t\nR1 a 0 1\n.save q(a)\n"),
            "t.cir:3:7: error: invalid probe 'q(a)': expected v(node), v(node1,node2), i(element), ic/ib/ie(transistor) "
            "or i2(line)\n.save q(a)\n      ^~~~");
}

// ngspice 40 reordered AM's parameters; five values or fewer fit the earlier AM(VA VO MF FC TD)
// too, and lcspice (like its validate witness, which gets lcspice's reading) would silently give
// a constant where the deck meant a 100 kHz carrier. A warning says which reading is used.
TEST(NgspiceDialect, AmWithFiveValuesOrFewerSaysWhichOrderIsRead) {
  Netlist n = test::parse("t\nV1 in 0 AM(1 0.5 1k 100k 0)\nR1 in 0 1k\n");
  ASSERT_EQ(n.warnings.size(), 1u);
  EXPECT_EQ(n.warnings[0], "t.cir:2:9: warning: AM of 'v1' is read in ngspice 40's order, AM(VO VMO VMA FM FC TD "
                           "PHASEM PHASEC): carrier FC = 0 Hz, modulation FM = 100000 Hz; ngspice 39 and earlier "
                           "read AM(VA VO MF FC TD), a carrier of 100000 Hz here (six values or more are read in "
                           "the 40+ order without this warning)");
  EXPECT_DOUBLE_EQ(test::element(n, "v1").waveform.value(3e-6), 1.0);  // VO + VMO sin(0): the 40+ reading
  n = test::parse("t\nV1 in 0 AM(0.5 2 1.8 1k 100k 1m 0 0)\nR1 in 0 1k\n");
  EXPECT_TRUE(n.warnings.empty());
}

// R, C and L take their value as a keyword too (ngspice: r=, resistance=; c=, capacitance=;
// l=, inductance=; LTspice writes R=): before, "invalid number 'r'".
TEST(NgspiceDialect, ValueGivenAsAKeyword) {
  Netlist n = test::parse("t\n.param rv=2k\nV1 a 0 1\nR1 a b r=1k\nC1 b 0 c=1u\nL1 b c L=1m m=2\n"
                          "R2 c 0 resistance={rv}\nC2 c 0 CAPACITANCE=2n ic=1\nL2 c 0 inductance=3m\nR3 c 0 R=5\n");
  EXPECT_DOUBLE_EQ(test::element(n, "r1").value, 1e3);
  EXPECT_DOUBLE_EQ(test::element(n, "c1").value, 1e-6);
  EXPECT_DOUBLE_EQ(test::element(n, "l1").value, 0.5e-3);  // two in parallel
  EXPECT_DOUBLE_EQ(test::element(n, "r2").value, 2e3);
  EXPECT_DOUBLE_EQ(test::element(n, "c2").value, 2e-9);
  ASSERT_TRUE(test::element(n, "c2").ic.has_value());
  EXPECT_DOUBLE_EQ(*test::element(n, "c2").ic, 1.0);
  EXPECT_DOUBLE_EQ(test::element(n, "l2").value, 3e-3);
  EXPECT_DOUBLE_EQ(test::element(n, "r3").value, 5.0);
  EXPECT_TRUE(n.warnings.empty());
  // Another element's keyword is not a value, and a keyword without one is located.
  EXPECT_EQ(test::diag("t\nR1 a 0 c=1u\n"), "t.cir:2:8: error: invalid number 'c'\nR1 a 0 c=1u\n       ^");
  EXPECT_EQ(test::diag("t\nR1 a 0 r=\n"), "t.cir:2:10: error: missing value for 'r1'\nR1 a 0 r=\n         ^");
  EXPECT_EQ(test::diag("t\nR1 a 0 r=-5\n"), "t.cir:2:10: error: resistance of 'r1' must be positive\nR1 a 0 r=-5\n         ^~");
}

TEST(NgspiceDialect, DiodeWithoutModelIsLtspicesIdealDiode) {
  Netlist n = test::parse("t\nV1 a 0 1\nD1 a b\nR1 b 0 1k\nD2 b 0\n");
  ASSERT_EQ(n.elements.size(), 4u);
  const Element& d1 = test::element(n, "d1");
  const Element& d2 = test::element(n, "d2");
  EXPECT_EQ(d1.model, d2.model);
  const DiodeModel& m = n.diode_models.at(d1.model);
  ASSERT_TRUE(m.von && m.ron);
  EXPECT_EQ(*m.von, 0.0);
  EXPECT_EQ(*m.ron, 0.0);
  ASSERT_EQ(n.warnings.size(), 1u);
  EXPECT_EQ(n.warnings[0], "t.cir:3:1: warning: diode 'd1' has no model name (LTspice dialect): it and every other "
                           "such diode get the ideal diode, VON = 0, RON = 0");
}

TEST(NgspiceDialect, LtraFlagsWithoutValuesAreAcceptedAndListed) {
  Netlist n = test::parse(
      "t\n.model llfifth ltra nocontrol noprint rel=10 r=0 g=0 l=9.13e-9\n"
      "+c=3.65e-12 len=0.2 steplimit quadinterp truncdontcut\nO1 a 0 b 0 llfifth\nR1 a 0 50\nR2 b 0 50\n");
  const LineModel& m = n.line_models.at("llfifth");
  EXPECT_EQ(m.l, 9.13e-9);
  EXPECT_EQ(m.c, 3.65e-12);
  EXPECT_EQ(m.len, 0.2);
  EXPECT_EQ(m.ignored, (std::vector<std::string>{"nocontrol", "noprint", "rel", "steplimit", "quadinterp", "truncdontcut"}));
  ASSERT_EQ(n.warnings.size(), 1u);
  EXPECT_EQ(n.warnings[0], "t.cir:2:21: warning: line model 'llfifth': parameters nocontrol, noprint, rel, steplimit, "
                           "quadinterp, truncdontcut ignored by lcspice");
}

TEST(NgspiceDialect, ShortedResistorCapacitorDiodeAreLeftOutAndReadZero) {
  Netlist n = test::parse(
      "t\nV1 in 0 1\nR1 in 0 1k\nX1 0 clamp\n.subckt clamp k\nD1CLAMP 0 k dmod\nC1 k k 1p\n.ends\n"
      ".model dmod d\n.print tran v(in) i(x1.d1clamp) i(r1)\n");
  ASSERT_EQ(n.elements.size(), 2u);  // v1, r1
  ASSERT_EQ(n.warnings.size(), 2u);
  EXPECT_EQ(n.warnings[0], "t.cir:6:9: warning: 'x1.d1clamp' has both terminals on node '0': it carries no current "
                           "and is left out of the circuit");
  EXPECT_EQ(n.warnings[1], "t.cir:7:4: warning: 'x1.c1' has both terminals on node '0': it carries no current "
                           "and is left out of the circuit");
  EXPECT_EQ(names(n.probes), "v(in) i(x1.d1clamp) i(r1) ");
  EXPECT_EQ(n.probes[1].kind, Probe::Kind::NodePairVoltage);  // v(0,0): zero
  EXPECT_EQ(n.probes[1].a, "0");
  EXPECT_EQ(n.probes[1].b, "0");
  // An undefined model is still an error on a shorted diode.
  EXPECT_EQ(test::diag("t\nD1 a a nosuch\n"),
            "t.cir:2:8: error: diode model 'nosuch' is not defined\nD1 a a nosuch\n       ^~~~~~");
}

TEST(NgspiceDialect, ShortedInductorOrVoltageSourceStaysAnError) {
  EXPECT_EQ(test::diag("t\nL1 a a 1m\n"),
            "t.cir:2:6: error: l1 connects node 'a' to itself (the current of an inductor shorted by itself is "
            "not set by the circuit)\nL1 a a 1m\n     ^");
  EXPECT_EQ(test::diag("t\nV1 0 gnd 1\n"),
            "t.cir:2:6: error: v1 connects node '0' to itself (a voltage source cannot hold a voltage across a "
            "short)\nV1 0 gnd 1\n     ^~~");
}

}  // namespace
}  // namespace lcs

namespace lcs {
namespace {

// Vendor libraries (TLC555.LIB) name a port GND; ngspice reads gnd as node 0 everywhere.
TEST(NgspiceDialect, GroundPortIsGroundInsideWithAWarning) {
  Netlist n = test::parse("t\n.subckt s a GND\nR1 a gnd 1k\n.ends\nX1 in 0 s\nV1 in 0 1\n");
  EXPECT_EQ(test::element(n, "x1.r1").nodes, (std::vector<std::string>{"in", "0"}));
  ASSERT_EQ(n.warnings.size(), 1u);
  EXPECT_EQ(n.warnings[0], "t.cir:2:13: warning: port 'gnd' of subcircuit 's' is ground: inside it is node '0', "
                           "whatever an instance connects there");
}

// A negative VH (LTspice: a smooth passage; ngspice: a reversed band) is the ideal switch at VT,
// with a warning at the value.
TEST(NgspiceDialect, NegativeSwitchHysteresisIsTheIdealSwitchAtVtWithAWarning) {
  const Netlist n = test::parse("t\nV1 c 0 1\nS1 a 0 c 0 m1\nR1 a 0 1\n.model m1 SW(VT=0.5 VH=-0.4 RON=0.1)\n");
  const SwitchModel& m = n.switch_models.at("m1");
  EXPECT_EQ(m.vt, 0.5);
  EXPECT_EQ(m.vh, 0.0);
  ASSERT_EQ(n.warnings.size(), 1u);
  EXPECT_EQ(n.warnings[0], "t.cir:5:24: warning: switch model 'm1': negative VH (LTspice: a smooth passage over VT -+ "
                           "|VH|; ngspice: a reversed band) is modelled as an ideal switch at VT, without hysteresis");
}

// PSpice's VSWITCH/ISWITCH: the ideal switch at the midpoint of VON and VOFF, reversed when
// VON < VOFF; PSpice's defaults (VON 1 V, VOFF 0, ION 1 mA, IOFF 0, RON 1, ROFF 1 MEG).
TEST(PspiceDialect, VswitchAndIswitchAreIdealSwitchesAtTheirMidpoint) {
  Netlist n = test::parse("t\nV1 c 0 1\nS1 a 0 c 0 sv\nR1 a 0 1\nW1 a 0 V1 si\n"
                          ".model sv VSWITCH(VON=0 VOFF=5 RON=0.1)\n.model si ISWITCH\n");
  const SwitchModel& v = n.switch_models.at("sv");
  EXPECT_FALSE(v.current_controlled);
  EXPECT_TRUE(v.reversed);
  EXPECT_EQ(v.vt, 2.5);
  EXPECT_EQ(v.vh, 0.0);
  EXPECT_EQ(v.ron, 0.1);
  EXPECT_EQ(v.roff, 1e6);
  const SwitchModel& i = n.switch_models.at("si");
  EXPECT_TRUE(i.current_controlled);
  EXPECT_FALSE(i.reversed);
  EXPECT_EQ(i.vt, 0.5e-3);
  EXPECT_EQ(i.ron, 1.0);
  ASSERT_EQ(n.warnings.size(), 2u);
  EXPECT_EQ(n.warnings[1], "t.cir:7:11: warning: switch model 'si': ISWITCH (PSpice): its smooth passage from ROFF at "
                           "IOFF = 0 A to RON at ION = 0.001 A is modelled as an ideal switch at their midpoint, on "
                           "above 0.0005 A");
  EXPECT_EQ(test::diag("t\nS1 a 0 c 0 m\n.model m VSWITCH(VON=1 VOFF=1)\n"),
            "t.cir:3:10: error: switch model 'm': VON and VOFF must differ\n.model m VSWITCH(VON=1 VOFF=1)\n"
            "         ^~~~~~~");
  EXPECT_EQ(test::diag("t\nS1 a 0 c 0 m\n.model m VSWITCH(VT=1)\n"),
            "t.cir:3:18: error: unknown VSWITCH model parameter 'VT' (PSpice's are VON, VOFF, RON and ROFF)\n"
            ".model m VSWITCH(VT=1)\n                 ^~");
  // An S switch takes a VSWITCH, not an ISWITCH.
  EXPECT_EQ(test::diag("t\nS1 a 0 c 0 m\n.model m ISWITCH\n"),
            "t.cir:2:12: error: model 'm' is not an SW model (it is ISWITCH); S switches take SW (or VSWITCH) models\n"
            "S1 a 0 c 0 m\n           ^");
}

// PSpice's `.TRAN/OP ... SKIPBP` is `.tran ... UIC`; temperature coefficients on R, L and C are
// read (checked) and change nothing at the nominal temperature; an instance TEMP= is warned about.
TEST(PspiceDialect, TranOpSkipbpAndTemperatureCoefficients) {
  Netlist n = test::parse("t\nV1 a 0 1\nR1 a b 1k TC=0.001,1e-6\nR2 b 0 {2k} tc1=1m tc2=0\nC1 b 0 1u TC=0.01\n"
                          "L1 a c 1m tc1=1e-4 IC=0\nR3 c 0 1\nR4 a 0 1k dtemp=10\n"
                          ".TRAN/OP 0.1ms 50ms 0 0.1ms SKIPBP\n");
  ASSERT_TRUE(n.tran.has_value());
  EXPECT_TRUE(n.tran->uic);
  EXPECT_EQ(n.tran->tstop, 50e-3);
  EXPECT_EQ(test::element(n, "r1").value, 1e3);
  EXPECT_EQ(test::element(n, "r2").value, 2e3);
  EXPECT_EQ(test::element(n, "c1").value, 1e-6);
  ASSERT_EQ(n.warnings.size(), 1u);
  EXPECT_EQ(n.warnings[0], "t.cir:8:11: warning: 'r4': dtemp= is ignored (no temperature model)");
  EXPECT_EQ(test::diag("t\nR1 a 0 1k TC=\n"), "t.cir:2:14: error: missing value for 'tc'\nR1 a 0 1k TC=\n             ^");
  EXPECT_EQ(test::diag("t\nR1 a 0 1k TC=x\n"),
            "t.cir:2:14: error: invalid number 'x'\nR1 a 0 1k TC=x\n             ^");
}

// PSpice's Zener cards (its libraries' 1N47xx) carry IBVL and NBVL, the low-level breakdown knee:
// read and listed with the other parameters lcspice does not use (was "unknown diode model
// parameter 'IBVL'"); BV, IBV and NBV are the breakdown lcspice models.
TEST(PspiceDialect, ZenerLowLevelBreakdownParametersAreReadAndListed) {
  Netlist n = test::parse("t\nV1 a 0 1\nD1 0 a dz\n.model dz D(IS=1.214E-16 RS=0.8 N=1 BV=5.1 IBV=0.049 NBV=1.2 "
                          "IBVL=1E-3 NBVL=2 TBV1=-1E-4 TIKF=0.005)\n");
  ASSERT_EQ(n.warnings.size(), 1u);
  EXPECT_EQ(n.warnings[0], "t.cir:4:62: warning: diode model 'dz': parameters ibvl, nbvl, tbv1, tikf ignored by lcspice");
  EXPECT_EQ(n.diode_models.at("dz").nbv, 1.2);  // NBV is modelled: the breakdown's emission
  EXPECT_EQ(test::diag("t\nD1 0 a dz\n.model dz D(BV=5 NBV=0)\n"),
            "t.cir:3:22: error: diode parameter 'nbv' must be positive\n.model dz D(BV=5 NBV=0)\n                     ^");
}

// PSpice's transistor cards: NK (ngspice's NKF) and the temperature coefficients TRB1 ... (also
// ngspice level 1's TBF1 ...) are read and listed (was "unknown transistor model parameter 'Nk'").
TEST(PspiceDialect, TransistorTemperatureCoefficientsAndNkAreReadAndListed) {
  Netlist n = test::parse("t\nV1 c 0 5\nV2 b 0 0.7\nQ1 c b 0 qx\n.model qx NPN(Is=1e-14 Bf=100 Nk=.5 Trb1=0 "
                          "Tre1=0 Tbf1=1e-3)\n");
  ASSERT_EQ(n.warnings.size(), 1u);
  EXPECT_EQ(n.warnings[0], "t.cir:5:31: warning: transistor model 'qx': parameters nk, trb1, tre1, tbf1 ignored by lcspice");
}

// Every deck PSpice exports carries `.PROBE64 V(alias(*)) I(alias(*)) W(alias(*)) D(alias(*))
// NOISE(alias(*))` (or `.PROBE`): every voltage and current, lcspice's default probes; power,
// digital and noise waveforms are named in one warning.
TEST(PspiceDialect, ProbeOfEveryAliasIsTheDefaultProbes) {
  Netlist n = test::parse("t\nR1 a 0 1\nV1 a 0 1\n.PROBE64 V(alias(*)) I(alias(*)) W(alias(*)) D(alias(*)) NOISE(alias(*))\n");
  EXPECT_TRUE(n.probes.empty());
  ASSERT_EQ(n.warnings.size(), 1u);
  EXPECT_EQ(n.warnings[0], "t.cir:4:1: warning: '.probe64': W(alias(*)), D(alias(*)), NOISE(alias(*)) (PSpice's power, "
                           "digital and noise waveforms) not written by lcspice");
  n = test::parse("t\nR1 a 0 1\nV1 a 0 1\n.probe V(*) I(*) v(a)\n");
  EXPECT_EQ(names(n.probes), "v(a) ");
  EXPECT_TRUE(n.warnings.empty());
  EXPECT_EQ(test::diag("t\nR1 a 0 1\nV1 a 0 1\n.probe V(alias(a))\n"),
            "t.cir:4:8: error: invalid probe 'V(alias(a))': expected v(node), v(node1,node2), i(element), "
            "ic/ib/ie(transistor) or i2(line)\n.probe V(alias(a))\n       ^~~~~~~~~~~");
}

}  // namespace
}  // namespace lcs
