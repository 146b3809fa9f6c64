// Element cards, sources, models, parameters and control cards, asserted on parsed values.
#include <cmath>

#include <gtest/gtest.h>

#include "netlist/netlist.h"
#include "netlist/test/parse_helpers.h"

namespace lcs {
namespace {

using test::element;
using test::parse;
using test::diag;

TEST(ParseElements, PassiveElements) {
  Netlist n = parse(
      "passives\n"
      "R1 in out 4.7k\n"
      "L1 out 0 10mH IC=2m\n"
      "C1 out GND 10uF ic = -1.5\n"
      "C2 a b 1p\n"
      "Lx a 0 1u\n");
  ASSERT_EQ(n.elements.size(), 5u);
  const Element& r = n.elements[0];
  EXPECT_EQ(r.kind, ElementKind::Resistor);
  EXPECT_EQ(r.name, "r1");
  EXPECT_EQ(r.nodes, (std::vector<std::string>{"in", "out"}));
  EXPECT_EQ(r.value, 4700.0);
  EXPECT_FALSE(r.ic.has_value());
  const Element& l = n.elements[1];
  EXPECT_EQ(l.kind, ElementKind::Inductor);
  EXPECT_EQ(l.value, 10e-3);
  ASSERT_TRUE(l.ic.has_value());
  EXPECT_EQ(*l.ic, 2e-3);
  const Element& c = n.elements[2];
  EXPECT_EQ(c.kind, ElementKind::Capacitor);
  EXPECT_EQ(c.nodes, (std::vector<std::string>{"out", "0"}));
  EXPECT_EQ(c.value, 1e-5);
  EXPECT_EQ(*c.ic, -1.5);
  EXPECT_FALSE(n.elements[3].ic.has_value());
  EXPECT_EQ(n.elements[4].name, "lx");
  EXPECT_EQ(n.elements[0].loc.line, 2);
  EXPECT_EQ(n.elements[4].loc.line, 6);
  EXPECT_TRUE(n.warnings.empty());
}

TEST(ParseElements, Coupling) {
  Netlist n = parse("t\nL1 a 0 1m\nK12 L1 L2 0.99\nL2 b 0 4m\nL3 c 0 1m\nK3 l3 l1 1\n");
  const Element& k = element(n, "k12");
  EXPECT_EQ(k.kind, ElementKind::Coupling);
  EXPECT_TRUE(k.nodes.empty());
  EXPECT_EQ(k.coupled, (std::vector<std::string>{"l1", "l2"}));
  EXPECT_EQ(k.value, 0.99);
  EXPECT_EQ(element(n, "k3").value, 1.0);
  EXPECT_EQ(element(n, "k3").coupled, (std::vector<std::string>{"l3", "l1"}));
}

TEST(ParseElements, GroundAliases) {
  Netlist n = parse("t\nR1 a 0 1\nR2 a gnd 1\nR3 GND a 1\n");
  EXPECT_EQ(n.elements[0].nodes[1], "0");
  EXPECT_EQ(n.elements[1].nodes[1], "0");
  EXPECT_EQ(n.elements[2].nodes[0], "0");
}

TEST(ParseElements, Diode) {
  Netlist n = parse("t\nD1 a k DMOD\n.model dmod D\n");
  const Element& d = element(n, "d1");
  EXPECT_EQ(d.kind, ElementKind::Diode);
  EXPECT_EQ(d.nodes, (std::vector<std::string>{"a", "k"}));
  EXPECT_EQ(d.model, "dmod");
  ASSERT_EQ(n.diode_models.count("dmod"), 1u);
}

TEST(ParseSources, AllWaveformForms) {
  Netlist n = parse(
      "t\n"
      "V1 a 0 5\n"
      "V2 b 0 DC 3.3V\n"
      "V3 c 0 SIN(0 10 50)\n"
      "V4 d 0 sin (1 2 1k 1m 10 90)\n"
      "V5 e 0 PULSE(0 5 1u 2u 3u 4u 10u)\n"
      "V6 f 0 pulse 0 5\n"
      "I1 g 0 PWL(0 0 1m 1 2m 1)\n"
      "I2 h 0 DC 1 SIN(0, 1, 60)\n"
      "V7 i 0 0 AC 1 0\n"
      "I3 j 0 {2*3}\n");
  const Element& v1 = element(n, "v1");
  EXPECT_EQ(v1.kind, ElementKind::VoltageSource);
  EXPECT_EQ(v1.waveform.kind, Waveform::Kind::Dc);
  EXPECT_EQ(v1.waveform.dc, 5);
  EXPECT_EQ(element(n, "v2").waveform.dc, 3.3);
  const Waveform& s = element(n, "v3").waveform;
  EXPECT_EQ(s.kind, Waveform::Kind::Sin);
  EXPECT_TRUE(s.resolved);
  // No .tran: FREQ given, TD THETA PHASE default to 0
  EXPECT_EQ(s.params, (std::vector<double>{0, 10, 50, 0, 0, 0}));
  EXPECT_EQ(element(n, "v4").waveform.params, (std::vector<double>{1, 2, 1e3, 1e-3, 10, 90}));
  EXPECT_EQ(element(n, "v5").waveform.kind, Waveform::Kind::Pulse);
  EXPECT_EQ(element(n, "v5").waveform.params, (std::vector<double>{0, 5, 1e-6, 2e-6, 3e-6, 4e-6, 1e-5}));
  // Without .tran the PULSE defaults are zero (zero-length edges are jumps)
  EXPECT_EQ(element(n, "v6").waveform.params, (std::vector<double>{0, 5, 0, 0, 0, 0, 0}));
  const Element& i1 = element(n, "i1");
  EXPECT_EQ(i1.kind, ElementKind::CurrentSource);
  EXPECT_EQ(i1.waveform.kind, Waveform::Kind::Pwl);
  EXPECT_EQ(i1.waveform.params, (std::vector<double>{0, 0, 1e-3, 1, 2e-3, 1}));
  const Waveform& i2 = element(n, "i2").waveform;
  EXPECT_EQ(i2.kind, Waveform::Kind::Sin);
  EXPECT_EQ(i2.dc, 1);
  EXPECT_EQ(i2.params[2], 60);
  EXPECT_EQ(element(n, "v7").waveform.dc, 0);
  EXPECT_EQ(element(n, "i3").waveform.dc, 6);
  ASSERT_EQ(n.warnings.size(), 1u);
  EXPECT_EQ(n.warnings[0], "t.cir:10:10: warning: AC specification of 'v7' is ignored");
}

TEST(ParseSources, DefaultsComeFromTran) {
  Netlist n = parse("t\nV1 a 0 PULSE(0 5 1m)\nV2 b 0 SIN(0 1)\n.tran 1u 10m\n");
  EXPECT_EQ(element(n, "v1").waveform.params, (std::vector<double>{0, 5, 1e-3, 1e-6, 1e-6, 1e-2, 1e-2}));
  EXPECT_EQ(element(n, "v2").waveform.params, (std::vector<double>{0, 1, 100, 0, 0, 0}));
}

// ngspice reads `DC=5` as `DC 5` (a one-shot's supply written that way was refused).
TEST(ParseSources, DcWithAnEqualsSign) {
  Netlist n = parse("t\nV1 a 0 DC=5\nI1 b 0 dc = 2m SIN(0 1 1k)\nR1 a b 1\n.tran 1u 1m\n");
  EXPECT_EQ(element(n, "v1").waveform.kind, Waveform::Kind::Dc);
  EXPECT_EQ(element(n, "v1").waveform.dc, 5);
  EXPECT_EQ(element(n, "i1").waveform.kind, Waveform::Kind::Sin);
  EXPECT_EQ(element(n, "i1").waveform.dc, 2e-3);
  EXPECT_TRUE(n.warnings.empty());
  Netlist ac = parse("t\nV1 a 0 DC=2 AC=1\nR1 a 0 1\n");
  EXPECT_EQ(element(ac, "v1").waveform.dc, 2);
  ASSERT_EQ(ac.warnings.size(), 1u);
  EXPECT_EQ(ac.warnings[0], "t.cir:2:13: warning: AC specification of 'v1' is ignored");
  try {
    parse("t\nV1 a 0 DC=\n");
    ADD_FAILURE() << "DC= with no value accepted";
  } catch (const NetlistError& e) {
    EXPECT_EQ(e.formatted().rfind("t.cir:2:11: error: missing value after 'DC'", 0), 0u) << e.formatted();
  }
}

// LTspice writes its part database's ratings and part numbers into the cards it exports; they
// change nothing in its simulation. Skipped with one warning per card; what is not one stays an
// error (a resistor has no Ipk).
TEST(ParseElements, LtspicePartAttributesAreSkippedWithAWarning) {
  Netlist n = parse(
      "t\n"
      "L1 in out 10u Ipk=2 Rser=0.05 mfg=\"Coilcraft\" pn=\"MSS1260-103\" type=\"ferrite\"\n"
      "C1 out 0 100u V=50 Irms=2 Rser=0.01\n"
      "R1 out 0 10 tol=1 pwr=0.25\n"
      "V1 in 0 5\n");
  EXPECT_EQ(element(n, "l1").value, 10e-6);
  EXPECT_EQ(element(n, "l1#rser").value, 0.05);
  EXPECT_EQ(element(n, "c1").value, 100e-6);
  EXPECT_EQ(element(n, "r1").value, 10);
  ASSERT_EQ(n.warnings.size(), 3u);
  EXPECT_EQ(n.warnings[0], "t.cir:2:1: warning: 'l1': LTspice part attributes Ipk, mfg, pn, type ignored (ratings and "
                           "part data: they do not change the simulation)");
  EXPECT_EQ(n.warnings[1], "t.cir:3:1: warning: 'c1': LTspice part attributes V, Irms ignored (ratings and part data: "
                           "they do not change the simulation)");
  EXPECT_EQ(n.warnings[2], "t.cir:4:1: warning: 'r1': LTspice part attributes tol, pwr ignored (ratings and part "
                           "data: they do not change the simulation)");
  try {
    parse("t\nR1 a 0 1k Ipk=2\n");
    ADD_FAILURE() << "Ipk on a resistor accepted";
  } catch (const NetlistError& e) {
    EXPECT_EQ(e.formatted().rfind("t.cir:2:11: error: unknown parameter 'Ipk' for 'r1'", 0), 0u) << e.formatted();
  }
}

TEST(ParseSources, NoValueIsDcZeroWithAWarning) {
  Netlist n = parse("t\nVsense a b\nR1 a b 1\n");
  EXPECT_EQ(element(n, "vsense").waveform.kind, Waveform::Kind::Dc);
  EXPECT_EQ(element(n, "vsense").waveform.dc, 0);
  ASSERT_EQ(n.warnings.size(), 1u);
  EXPECT_EQ(n.warnings[0], "t.cir:2:1: warning: 'vsense' has no value, DC 0 assumed");
}

TEST(ParseModels, DiodeParameters) {
  Netlist n = parse(
      "t\n"
      "D1 a 0 dideal\n"
      "D2 a 0 DSMOOTH\n"
      ".model dideal D(VON=0.7 RON=0.1)\n"
      ".model dsmooth d is=1e-12, n=1.8\n"
      "+ rs=0.5 cjo=2p TT=5n cjo=3p\n");
  const DiodeModel& a = n.diode_models.at("dideal");
  EXPECT_EQ(a.name, "dideal");
  EXPECT_EQ(*a.von, 0.7);
  EXPECT_EQ(*a.ron, 0.1);
  EXPECT_FALSE(a.has_is || a.has_n || a.has_rs);
  EXPECT_EQ(a.is, 1e-14);
  EXPECT_EQ(a.n, 1.0);
  EXPECT_EQ(a.rs, 0.0);
  EXPECT_TRUE(a.ignored.empty());
  EXPECT_EQ(a.loc.line, 4);
  EXPECT_EQ(a.loc.column, 8);
  const DiodeModel& b = n.diode_models.at("dsmooth");
  EXPECT_FALSE(b.von.has_value());
  EXPECT_FALSE(b.ron.has_value());
  EXPECT_TRUE(b.has_is && b.has_n && b.has_rs);
  EXPECT_EQ(b.is, 1e-12);
  EXPECT_EQ(b.n, 1.8);
  EXPECT_EQ(b.rs, 0.5);
  EXPECT_EQ(b.ignored, (std::vector<std::string>{"cjo", "tt"}));
  ASSERT_EQ(n.warnings.size(), 1u);
  EXPECT_EQ(n.warnings[0], "t.cir:6:10: warning: diode model 'dsmooth': parameters cjo, tt ignored by lcspice");
  EXPECT_EQ(element(n, "d2").model, "dsmooth");
}

// CJO is read either way; it is listed as ignored (SPEC §2) unless `.options diodecap` is given,
// before or after the card, and a bad value is an error.
TEST(ParseModels, DiodeCapacitanceIsListedAsIgnoredUnlessOptionsDiodecap) {
  Netlist n = parse("t\nD1 a 0 dc\n.model dc D(IS=1e-14 CJO=2p TT=5n)\n");
  EXPECT_EQ(n.diode_models.at("dc").cjo, 2e-12);
  EXPECT_EQ(n.diode_models.at("dc").ignored, (std::vector<std::string>{"cjo", "tt"}));
  for (const char* option : {".options diodecap\n", ".options diodecap=1\n"}) {
    n = parse(std::string("t\nD1 a 0 dc\n.model dc D(IS=1e-14 CJ0=2p TT=5n)\n") + option);
    EXPECT_EQ(n.diode_models.at("dc").cjo, 2e-12) << option;
    EXPECT_EQ(n.diode_models.at("dc").ignored, (std::vector<std::string>{"tt"})) << option;
    ASSERT_EQ(n.warnings.size(), 1u);
    EXPECT_EQ(n.warnings[0], "t.cir:3:29: warning: diode model 'dc': parameter tt ignored by lcspice");
  }
  n = parse("t\n.options diodecap=0\nD1 a 0 dc\n.model dc D(IS=1e-14 CJ=2p)\n");
  EXPECT_EQ(n.diode_models.at("dc").ignored, (std::vector<std::string>{"cj"}));
  EXPECT_EQ(diag("t\nD1 a 0 dc\n.model dc D(CJO=-1p)\n"),
            "t.cir:3:17: error: diode parameter 'cjo' must not be negative\n.model dc D(CJO=-1p)\n                ^~~");
}

// A nonzero temperature coefficient with .options temp=/tnom= (another temperature than the
// nominal one, which lcspice runs at) is warned about once; with the nominal one it is silent.
TEST(ParseElements, TemperatureCoefficientsWithAnotherTemperatureAreWarnedAbout) {
  Netlist n = parse("t\nV1 a 0 1\nR1 a 0 1k TC=0,0\nR2 a 0 1k TC=0.01\nR3 a 0 1k tc2=1e-6\n.options tnom=20 temp=60\n");
  ASSERT_EQ(n.warnings.size(), 1u);
  EXPECT_EQ(n.warnings[0], "t.cir:4:11: warning: 'r2': temperature coefficients are not modelled: lcspice runs at "
                           "the nominal temperature (.options temp= is ignored)");
  EXPECT_TRUE(parse("t\nV1 a 0 1\nR2 a 0 1k TC=0.01\n").warnings.empty());
  EXPECT_EQ(diag("t\nR1 a 0 1k TC=0.001,\n"),
            "t.cir:2:20: error: missing second value for 'tc'\nR1 a 0 1k TC=0.001,\n                   ^");
}

TEST(ParseModels, ManyIgnoredNgspiceParameters) {
  Netlist n = parse("t\n.model D1N4148 D(Is=2.52n Rs=.568 N=1.752 Cjo=4p M=.4 tt=20n bv=100 ibv=100u level=1)\n");
  const DiodeModel& d = n.diode_models.at("d1n4148");
  EXPECT_EQ(d.is, 2.52e-9);
  EXPECT_EQ(d.rs, 0.568);
  EXPECT_EQ(d.n, 1.752);
  EXPECT_EQ(d.ignored, (std::vector<std::string>{"cjo", "m", "tt", "level"}));
  ASSERT_TRUE(d.bv);  // breakdown is modelled (a second, reverse pair: issue 13)
  EXPECT_EQ(*d.bv, 100.0);
  EXPECT_EQ(d.ibv, 100e-6);
  ASSERT_EQ(n.warnings.size(), 1u);
  EXPECT_EQ(n.warnings[0],
            "t.cir:2:43: warning: diode model 'd1n4148': parameters cjo, m, tt, level ignored by lcspice");
}

// LTspice's ideal diode: Vfwd is VON, Vrev BV, Rrev its resistance; Roff is reported as not
// modelled at its own column, the limits as ignored; a non-positive Vrev is an error.
TEST(ParseModels, LtspiceIdealDiodeParameters) {
  Netlist n = parse("t\n.model A D(Ron=1 Roff=1Meg Vfwd=1 Vrev=2 Rrev=3 Ilimit=1 epsilon=1)\n");
  const DiodeModel& d = n.diode_models.at("a");
  EXPECT_EQ(d.von, 1.0);
  EXPECT_EQ(d.ron, 1.0);
  EXPECT_EQ(d.bv, 2.0);
  EXPECT_EQ(d.rrev, 3.0);
  EXPECT_EQ(d.ignored, (std::vector<std::string>{"ilimit", "epsilon"}));
  ASSERT_EQ(n.warnings.size(), 2u);
  EXPECT_EQ(n.warnings[0], "t.cir:2:18: warning: diode model 'a': Roff (LTspice) is not modelled: the blocking diode is an open circuit");
  EXPECT_EQ(n.warnings[1], "t.cir:2:49: warning: diode model 'a': parameters ilimit, epsilon ignored by lcspice");
  try {
    parse("t\n.model A D(Vrev=0)\n");
    ADD_FAILURE() << "Vrev=0 accepted";
  } catch (const NetlistError& e) {
    EXPECT_EQ(e.formatted().rfind("t.cir:2:17: error: diode parameter 'vrev' must be positive", 0), 0u) << e.formatted();
  }
}

TEST(ParseModels, BjtAndLineModelsAreAcceptedAndNotStored) {
  Netlist n = parse(
      "t\n"
      ".model q2n NPN(BF=100 BR=1 IS=1e-15 VON=0.7)\n"
      ".model qp pnp bf=50\n"
      ".model line LTRA(R=0.1 L=1u G=0 C=1p LEN=10)\n"
      "R1 a 0 1\n");
  EXPECT_TRUE(n.diode_models.empty());
  EXPECT_TRUE(n.warnings.empty());
}

TEST(ParseParams, ExpressionsEverywhere) {
  Netlist n = parse(
      "params\n"
      ".param r0=1k c0 = {10u/2} f=50 vpk='2*5' td={1/f}\n"
      ".param half = r0/2 tau=r0*c0\n"
      "R1 a b {r0}\n"
      "R2 b 0 {half}\n"
      "C1 b 0 {c0} IC={-vpk/10}\n"
      "L1 a 0 {tau*1k} ic={1m}\n"
      "V1 a 0 SIN(0 {vpk} {f} {td})\n"
      "K1 L1 L2 {0.5*2}\n"
      "L2 b 0 1\n"
      "D1 b 0 dm\n"
      ".model dm D(von={0.1*7} ron={r0/1e4})\n"
      ".tran {1/f/100} {10/f}\n"
      ".ic v(b)={vpk/2}\n");
  EXPECT_EQ(element(n, "r1").value, 1000);
  EXPECT_EQ(element(n, "r2").value, 500);
  EXPECT_EQ(element(n, "c1").value, 5e-6);
  EXPECT_EQ(*element(n, "c1").ic, -1);
  EXPECT_DOUBLE_EQ(element(n, "l1").value, 5);
  EXPECT_EQ(*element(n, "l1").ic, 1e-3);
  EXPECT_EQ(element(n, "v1").waveform.params, (std::vector<double>{0, 10, 50, 0.02, 0, 0}));
  EXPECT_EQ(element(n, "k1").value, 1);
  EXPECT_DOUBLE_EQ(*n.diode_models.at("dm").von, 0.7);
  EXPECT_EQ(*n.diode_models.at("dm").ron, 0.1);
  ASSERT_TRUE(n.tran);
  EXPECT_DOUBLE_EQ(n.tran->tstep, 2e-4);
  EXPECT_EQ(n.tran->tstop, 0.2);
  ASSERT_EQ(n.node_ics.size(), 1u);
  EXPECT_EQ(n.node_ics[0].value, 5);
}

TEST(ParseParams, ForwardReferencesAndRedefinition) {
  Netlist n = parse("t\n.param a={b*2}\n.param b=3\nR1 x 0 {a}\n.param b=4\n");
  EXPECT_EQ(element(n, "r1").value, 8);  // the later definition of b replaces the earlier one
  EXPECT_EQ(element(parse("t\nR1 x 0 {late}\n.param late=7\n"), "r1").value, 7);
}

TEST(ParseControl, Tran) {
  Netlist n = parse("t\nR1 a 0 1\n.tran 1u 1m\n");
  ASSERT_TRUE(n.tran);
  EXPECT_EQ(n.tran->tstep, 1e-6);
  EXPECT_EQ(n.tran->tstop, 1e-3);
  EXPECT_EQ(n.tran->tstart, 0);
  EXPECT_EQ(n.tran->tmax, 0);
  EXPECT_FALSE(n.tran->uic);
  EXPECT_EQ(n.tran->loc.line, 3);
  n = parse("t\nR1 a 0 1\n.TRAN 10n 5u 1u 2n UIC\n");
  EXPECT_EQ(n.tran->tstep, 1e-8);
  EXPECT_EQ(n.tran->tstop, 5e-6);
  EXPECT_EQ(n.tran->tstart, 1e-6);
  EXPECT_EQ(n.tran->tmax, 2e-9);
  EXPECT_TRUE(n.tran->uic);
  n = parse("t\nR1 a 0 1\n.tran 1n 1u uic\n");
  EXPECT_TRUE(n.tran->uic);
  EXPECT_EQ(n.tran->tstart, 0);
  EXPECT_FALSE(parse("t\nR1 a 0 1\n").tran.has_value());
}

TEST(ParseControl, InitialConditions) {
  Netlist n = parse("t\nR1 a b 1\nR2 b 0 1\n.ic v(a)=1.5 V(B) = {2*2}\n.ic v(a)=3\n");
  ASSERT_EQ(n.node_ics.size(), 2u);
  EXPECT_EQ(n.node_ics[0].node, "a");
  EXPECT_EQ(n.node_ics[0].value, 3);  // the later .ic wins
  EXPECT_EQ(n.node_ics[1].node, "b");
  EXPECT_EQ(n.node_ics[1].value, 4);
  EXPECT_EQ(n.node_ics[1].loc.line, 4);
  EXPECT_EQ(n.node_ics[1].loc.column, 14);
  EXPECT_EQ(n.node_ics[1].loc.length, 4);
}

TEST(ParseControl, PrintAndSave) {
  Netlist n = parse(
      "t\nR1 a b 1\nD1 b 0 dm\n.model dm d\n"
      ".print tran V(A) v(a, b) I(D1)\n"
      ".save v(b) v(a) i(r1) v(gnd)\n"
      ".save all\n"
      ".plot tran v( b , a )\n");
  std::vector<std::string> names;
  for (const Probe& p : n.probes) names.push_back(p.name());
  EXPECT_EQ(names, (std::vector<std::string>{"v(a)", "v(a,b)", "i(d1)", "v(b)", "i(r1)", "v(0)", "v(b,a)"}));
  EXPECT_EQ(n.probes[1].kind, Probe::Kind::NodePairVoltage);
  EXPECT_EQ(n.probes[2].kind, Probe::Kind::ElementCurrent);
  EXPECT_EQ(n.probes[1].loc.line, 5);
  EXPECT_EQ(n.probes[1].loc.column, 18);
  EXPECT_EQ(n.probes[1].loc.length, 7);
  EXPECT_TRUE(parse("t\nR1 a 0 1\n.save all\n").probes.empty());
}

TEST(ParseControl, PrintOfAnotherAnalysisIsIgnored) {
  Netlist n = parse("t\nR1 a 0 1\n.print ac vm(a)\n");
  EXPECT_TRUE(n.probes.empty());
  ASSERT_EQ(n.warnings.size(), 1u);
  EXPECT_EQ(n.warnings[0], "t.cir:3:8: warning: '.print ac' is ignored (lcspice runs transient analyses)");
}

TEST(ParseControl, Options) {
  Netlist n = parse("t\nR1 a 0 1\n.options method=Euler reltol=1e-4 abstol={1p*2} noacct\n.option Temp=27\n");
  EXPECT_EQ(n.options.at("method"), "euler");
  EXPECT_EQ(n.options.at("reltol"), "1e-4");
  EXPECT_EQ(n.options.at("abstol"), "2e-12");
  EXPECT_EQ(n.options.at("noacct"), "");
  EXPECT_EQ(n.options.at("temp"), "27");
  EXPECT_EQ(n.option_locs.at("reltol").line, 3);
  EXPECT_EQ(n.option_locs.at("reltol").column, 23);
  EXPECT_EQ(n.option_locs.at("temp").line, 4);
}

TEST(ParseControl, AcceptedAndIgnoredCards) {
  Netlist n = parse(
      "t\nR1 a 0 1\n.op\n.ac dec 10 1 1meg\n.dc V1 0 1 0.1\n.noise v(a) v1 dec 10 1 1k\n.tf v(a) v1\n"
      ".meas tran x max v(a)\n.four 1k v(a)\n");
  // `.meas tran` is read (measure_card_test.cpp); the others are warned about.
  ASSERT_EQ(n.warnings.size(), 5u);
  EXPECT_EQ(n.warnings[0], "t.cir:4:1: warning: '.ac' is not supported and is ignored");
  EXPECT_EQ(n.warnings[4], "t.cir:9:1: warning: '.four' is not supported and is ignored");
  ASSERT_EQ(n.measures.size(), 1u);
  EXPECT_EQ(n.measures[0].name, "x");
}

TEST(ParseControl, TitleCard) {
  EXPECT_EQ(parse("first\n.title  The Real  Title\nR1 a 0 1\n").title, "The Real  Title");
}

TEST(ParseNetlist, FileAndEmptyInputs) {
  Netlist n = parse_netlist_string("only a title", "x.cir");
  EXPECT_EQ(n.file, "x.cir");
  EXPECT_EQ(n.title, "only a title");
  EXPECT_TRUE(n.elements.empty());
  EXPECT_TRUE(parse_netlist_string("", "empty.cir").elements.empty());
  EXPECT_THROW(parse_netlist_file("/nonexistent/dir/x.cir"), FileError);
  EXPECT_THROW(parse_netlist_file(LCSPICE_TEST_DATA), FileError);  // a directory
}

}  // namespace
}  // namespace lcs

namespace lcs {
namespace {

// `.tran 0 TSTOP` (LTspice/PSpice): lcspice picks TSTEP = (TSTOP - TSTART)/1000 and says so.
TEST(ParseControl, TranWithZeroStepPicksTheStep) {
  Netlist n = parse("t\nV1 a 0 SIN(0 1 1k)\nR1 a 0 1k\n.tran 0 2m 1m\n");
  ASSERT_TRUE(n.tran);
  EXPECT_DOUBLE_EQ(n.tran->tstep, 1e-6);
  EXPECT_TRUE(n.tran->step_picked);
  ASSERT_EQ(n.warnings.size(), 1u);
  EXPECT_EQ(n.warnings[0], "t.cir:4:1: warning: '.tran 0 TSTOP' (LTspice/PSpice): lcspice picks TSTEP = (TSTOP - "
                           "TSTART)/1000 = 1e-06 s, the print step and the fixed-step methods' default step");
  Netlist capped = parse("t\nR1 a 0 1k\n.tran 0 2 0 1m\n");  // TMAX bounds the picked step
  EXPECT_DOUBLE_EQ(capped.tran->tstep, 1e-3);
  ASSERT_EQ(capped.warnings.size(), 1u);
  EXPECT_EQ(capped.warnings[0], "t.cir:3:1: warning: '.tran 0 TSTOP' (LTspice/PSpice): lcspice picks TSTEP = TMAX = "
                                "0.001 s, the print step and the fixed-step methods' default step");
  Netlist plain = parse("t\nR1 a 0 1k\n.tran 0 2\n");
  EXPECT_EQ(plain.warnings[0], "t.cir:3:1: warning: '.tran 0 TSTOP' (LTspice/PSpice): lcspice picks TSTEP = TSTOP/1000 = "
                               "0.002 s, the print step and the fixed-step methods' default step");
  Netlist written = parse("t\nR1 a 0 1k\n.tran 1u 1m\n");
  EXPECT_FALSE(written.tran->step_picked);
  EXPECT_TRUE(written.warnings.empty());
}

// LTspice's `.tran TSTOP` (its simulation dialog with only the stop time): `.tran 0 TSTOP`, said so.
TEST(ParseControl, TranWithOnlyTheStopTimePicksTheStep) {
  Netlist n = parse("t\nV1 a 0 SIN(0 1 1k)\nR1 a 0 1k\n.tran 100m\n");
  ASSERT_TRUE(n.tran);
  EXPECT_DOUBLE_EQ(n.tran->tstop, 0.1);
  EXPECT_DOUBLE_EQ(n.tran->tstep, 1e-4);
  EXPECT_EQ(n.tran->tstart, 0.0);
  EXPECT_TRUE(n.tran->step_picked);
  EXPECT_TRUE(n.tran->stop_only);
  EXPECT_FALSE(n.tran->uic);
  ASSERT_EQ(n.warnings.size(), 1u);
  EXPECT_EQ(n.warnings[0], "t.cir:4:1: warning: '.tran TSTOP' (LTspice): lcspice picks TSTEP = TSTOP/1000 = "
                           "0.0001 s, the print step and the fixed-step methods' default step");
  Netlist uic = parse("t\nR1 a 0 1k\n.tran 5m uic\n");
  EXPECT_DOUBLE_EQ(uic.tran->tstop, 5e-3);
  EXPECT_TRUE(uic.tran->uic);
}

}  // namespace
}  // namespace lcs
