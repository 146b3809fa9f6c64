// What schematic tools and other simulators write into the decks they export, found by running
// such decks as a new user would: KiCad's net names, Qucs-S's diode Temp=, Xyce's .PRINT options
// and wildcards, LTspice's `.meas ... PARAM expr`, an ohm symbol after a value.
#include <gtest/gtest.h>

#include "netlist/netlist.h"
#include "netlist/test/parse_helpers.h"

namespace lcs {
namespace {

std::string names(const std::vector<Probe>& probes) { return test::probe_names(probes); }

// KiCad names every net it was given no name for after a pin: `Net-(R1-Pad1)`, and leaves pins
// `unconnected-(U1-Pad3)`. They were "expected a node name, got '('".
TEST(ExportedDecks, KicadNetNamesAreNodeNames) {
  const Netlist n = test::parse(
      "kicad\nV1 Net-(R1-Pad1) 0 SIN(0 10 50)\nR1 Net-(R1-Pad1) Net-(D1-Pad1) 10\nD1 Net-(D1-Pad1) /out dm\n"
      "C1 /out GND 100u\nR3 unconnected-(U1-Pad3) 0 1k\n.model dm D(VON=0.7 RON=0.1)\n.tran 1m 40m\n"
      ".print tran v(Net-(D1-Pad1)) v(/out, Net-(R1-Pad1)) i(r1)\n.end\n");
  EXPECT_EQ(test::element(n, "v1").nodes, (std::vector<std::string>{"net-(r1-pad1)", "0"}));
  EXPECT_EQ(test::element(n, "r1").nodes, (std::vector<std::string>{"net-(r1-pad1)", "net-(d1-pad1)"}));
  EXPECT_EQ(test::element(n, "r3").nodes, (std::vector<std::string>{"unconnected-(u1-pad3)", "0"}));
  EXPECT_EQ(test::element(n, "v1").waveform.kind, Waveform::Kind::Sin);  // SIN( is not a name
  EXPECT_EQ(names(n.probes), "v(net-(d1-pad1)) v(/out,net-(r1-pad1)) i(r1) ");
  EXPECT_TRUE(n.warnings.empty());
  // Only a word ending in '-' takes the parentheses, and only when a name is inside.
  EXPECT_EQ(test::diag("t\nR1 a-( ) 0 1\n"), "t.cir:2:6: error: expected a node name, got '('\nR1 a-( ) 0 1\n     ^");
}

// Qucs-S writes `Temp=26.85` on every diode; ngspice also takes dtemp=, ic= and pj= there. They
// were "unknown parameter 'temp' for 'd1'"; now ignored with a warning each, as on R, L, C and Q.
TEST(ExportedDecks, DiodeInstanceTemperatureAndInitialConditionAreIgnoredWithAWarning) {
  const Netlist n = test::parse(
      "t\nV1 a 0 5\nR1 a b 1k\nD1 b 0 dm AREA=2 Temp=26.85 dtemp=1 ic=0.6 pj=1u\n.model dm D(is=1e-14)\n"
      ".tran 1u 2u\n.end\n");
  EXPECT_DOUBLE_EQ(test::element(n, "d1").value, 2.0);  // the area still counts
  ASSERT_EQ(n.warnings.size(), 4u);
  EXPECT_EQ(n.warnings[0], "t.cir:4:18: warning: 'd1': temp= is ignored (no temperature model)");
  EXPECT_EQ(n.warnings[1], "t.cir:4:29: warning: 'd1': dtemp= is ignored (no temperature model)");
  EXPECT_EQ(n.warnings[2], "t.cir:4:37: warning: 'd1': ic= is ignored (use .ic on the nodes)");
  EXPECT_EQ(n.warnings[3], "t.cir:4:44: warning: 'd1': pj= is ignored (no sidewall junction model)");
  // Their values are still read.
  EXPECT_EQ(test::diag("t\nD1 b 0 dm temp=hot\n.model dm D\n"),
            "t.cir:2:16: error: invalid number 'hot'\nD1 b 0 dm temp=hot\n               ^~~");
}

// Xyce: `.PRINT TRAN FORMAT=CSV FILE=out.csv V(*) I(*)`: FILE= was an invalid probe and V(*) an
// unknown node '*'. The options are ignored with a warning; V(*) I(*) ask for every voltage and
// current, lcspice's default probes (as PSpice's V(alias(*)) on .PROBE).
TEST(ExportedDecks, XycePrintOptionsAndWildcards) {
  const Netlist n = test::parse("t\nV1 a 0 1\nR1 a 0 1\n.tran 1u 2u\n.PRINT TRAN FORMAT=CSV FILE=out.csv WIDTH=12 V(*) I(*)\n");
  EXPECT_TRUE(n.probes.empty());
  ASSERT_EQ(n.warnings.size(), 3u);
  EXPECT_EQ(n.warnings[0], "t.cir:5:13: warning: '.print': FORMAT= is ignored (lcspice writes CSV)");
  EXPECT_EQ(n.warnings[1], "t.cir:5:24: warning: '.print': FILE= is ignored (lcspice writes to -o)");
  EXPECT_EQ(n.warnings[2], "t.cir:5:37: warning: '.print': WIDTH= is ignored");
  EXPECT_TRUE(n.every_probe);
  // With named entries beside it, or on another .print, V(*) still asks for every voltage and
  // current, and the named ones are kept (the run writes those the defaults lack, i(r1) here).
  for (const char* cards : {".PRINT TRAN I(R1) V(*)\n", ".PRINT TRAN V(*)\n.print tran i(r1)\n",
                            ".print tran i(r1)\n.PRINT TRAN V(*)\n"}) {
    const Netlist mixed = test::parse(std::string("t\nV1 a 0 1\nR1 a 0 1\n.tran 1u 2u\n") + cards);
    EXPECT_TRUE(mixed.every_probe) << cards;
    EXPECT_EQ(names(mixed.probes), "i(r1) ") << cards;
  }
  EXPECT_FALSE(test::parse("t\nV1 a 0 1\nR1 a 0 1\n.tran 1u 2u\n.print tran i(r1)\n").every_probe);
}

// LTspice's own help writes `.meas TRAN eff PARAM vout_avg**2/5/24` (no '='): it stopped the deck
// ("unknown measure kind 'PARAM'"), was then skipped; now read as ngspice's PARAM=.
TEST(ExportedDecks, LtspiceMeasureParamWithoutEqualsIsRead) {
  const Netlist n = test::parse("t\nV1 a 0 1\nR1 a 0 1\n.tran 1u 2u\n.meas TRAN vmax MAX v(a)\n.meas TRAN eff PARAM vmax**2/5\n");
  ASSERT_EQ(n.measures.size(), 2u);
  EXPECT_EQ(n.measures[1].name, "eff");
  EXPECT_EQ(n.measures[1].kind, Measure::Kind::Param);
  EXPECT_EQ(n.measures[1].expression.text, "vmax**2/5");
  EXPECT_DOUBLE_EQ(n.measures[1].expression.evaluate([](const std::string& name) -> std::optional<double> {
    return name == "vmax" ? std::optional<double>(3.0) : std::nullopt;
  }), 9.0 / 5);
  EXPECT_TRUE(n.warnings.empty());
}

// `1.5kΩ`: a value with its unit as the ohm symbol (U+03A9) or the ohm sign (U+2126).
TEST(ExportedDecks, OhmSymbolAfterAValueIsAUnit) {
  const Netlist n = test::parse("t\nV1 a 0 1\nR1 a 0 1.5k\xCE\xA9\nR2 a 0 2\xE2\x84\xA6\nR3 a 0 4.7Meg\xCE\xA9\n");
  EXPECT_DOUBLE_EQ(test::element(n, "r1").value, 1500.0);
  EXPECT_DOUBLE_EQ(test::element(n, "r2").value, 2.0);
  EXPECT_DOUBLE_EQ(test::element(n, "r3").value, 4.7e6);
}

// `4k7`, `2u2`, `1R5` (European schematics): LTspice reads 4k7 as 4.7k, ngspice as 4k. Neither is
// guessed; the error says how to write the value.
TEST(ExportedDecks, ASuffixInPlaceOfTheDecimalPointIsRefusedWithTheWayToWriteIt) {
  EXPECT_EQ(test::diag("t\nR1 a 0 4k7\n"), "t.cir:2:8: error: invalid number '4k7' (a suffix in place of the decimal "
                                            "point is not read: write 4.7k)\nR1 a 0 4k7\n       ^~~");
  EXPECT_EQ(test::diag("t\nC1 a 0 2u2\n"), "t.cir:2:8: error: invalid number '2u2' (a suffix in place of the decimal "
                                            "point is not read: write 2.2u)\nC1 a 0 2u2\n       ^~~");
  EXPECT_EQ(test::diag("t\nR1 a 0 1R5\n"), "t.cir:2:8: error: invalid number '1R5' (a suffix in place of the decimal "
                                            "point is not read: write 1.5)\nR1 a 0 1R5\n       ^~~");
  EXPECT_EQ(test::diag("t\nR1 a 0 1M5\n"), "t.cir:2:8: error: invalid number '1M5' (a suffix in place of the decimal "
                                            "point is not read: write 1.5Meg)\nR1 a 0 1M5\n       ^~~");
  EXPECT_EQ(test::diag("t\nC1 a 0 4m7\n"), "t.cir:2:8: error: invalid number '4m7' (a suffix in place of the decimal "
                                            "point is not read: write 4.7m)\nC1 a 0 4m7\n       ^~~");
  EXPECT_EQ(test::diag("t\nR1 a 0 4x7\n"), "t.cir:2:8: error: invalid number '4x7'\nR1 a 0 4x7\n       ^~~");
}

}  // namespace
}  // namespace lcs
