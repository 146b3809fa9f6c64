// Cards of LTspice-written decks (and ngspice's .global): `.lib FILE` as an include, the datasheet
// fields of vendor diode cards, `.backanno`, `.global`, and the clear refusal of `.step`
// (`.func` is read: user_function_test.cpp).
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "netlist/netlist.h"
#include "netlist/test/parse_helpers.h"

namespace lcs {
namespace {

const std::string kData = LCSPICE_TEST_DATA;

TEST(LtspiceDialect, LibWithoutSectionIncludesTheWholeFile) {
  Netlist n = parse_netlist_file(kData + "/lt_lib_top.cir");
  ASSERT_EQ(n.diode_models.count("1n4148"), 1u);
  ASSERT_EQ(n.diode_models.count("1n5819"), 1u);
  const DiodeModel& d = n.diode_models.at("1n4148");
  EXPECT_EQ(d.is, 2.52e-9);
  EXPECT_EQ(d.n, 1.752);
  EXPECT_EQ(d.loc.file, kData + "/lib/standard_like.dio");
  EXPECT_EQ(d.loc.line, 2);
}

TEST(LtspiceDialect, LibOfAMissingFileNamesTheFile) {
  try {
    parse_netlist_file(kData + "/lt_lib_missing.cir");
    FAIL() << "no error";
  } catch (const NetlistError& e) {
    EXPECT_EQ(e.formatted(), kData + "/lt_lib_missing.cir:4:6: error: cannot open library file 'standard.dio'; the "
                                     "deck needs it: diode model '1n4148' is not defined (" +
                                     kData + "/lt_lib_missing.cir:3:8)\n.lib standard.dio\n     ^~~~~~~~~~~~");
  }
}

// LTspice writes its install's library path into a deck (`.lib C:\...\standard.dio`) also when the
// deck defines the models it uses: the deck runs, with a warning at the path.
TEST(LtspiceDialect, LibOfAMissingFileIsAWarningWhenTheDeckDefinesWhatItUses) {
  Netlist n = test::parse("t\nV1 a 0 1\nD1 a 0 D\nR1 a 0 1k\n.model D D\n"
                          ".lib C:\\Users\\me\\Documents\\LTspiceXVII\\lib\\cmp\\standard.dio\n.tran 1u 1m\n");
  EXPECT_EQ(n.elements.size(), 3u);
  ASSERT_EQ(n.warnings.size(), 1u);
  EXPECT_EQ(n.warnings[0], "t.cir:6:6: warning: cannot open library file "
                           "'C:\\Users\\me\\Documents\\LTspiceXVII\\lib\\cmp\\standard.dio': lcspice goes on "
                           "with the models and subcircuits the deck defines itself (LTspice and PSpice write their own libraries' "
                           "paths into every deck)");
  // A subcircuit it lacks: the library's error, at the .lib line.
  EXPECT_EQ(test::diag("t\nX1 a 0 opamp\nR1 a 0 1k\n.lib lt.lib\n"),
            "t.cir:4:6: error: cannot open library file 'lt.lib'; the deck needs it: subcircuit 'opamp' is not defined "
            "(t.cir:2:8)\n.lib lt.lib\n     ^~~~~~");
  // Several that could not be opened: all named, at the first.
  EXPECT_EQ(test::diag("t\n.lib standard.dio\n.lib standard.bjt\nQ1 c b 0 2N3904\nR1 c 0 1k\n"),
            "t.cir:2:6: error: cannot open library file 'standard.dio'; nor library file 'standard.bjt' (t.cir:3); "
            "the deck needs one of them: transistor model '2n3904' is not defined (t.cir:4:10)\n.lib standard.dio\n"
            "     ^~~~~~~~~~~~");
  // ngspice's `.lib FILE SECTION` of a missing file is still an error at once.
  EXPECT_EQ(test::diag("t\nR1 a 0 1k\n.lib models.lib fast\n"),
            "t.cir:3:6: error: cannot open library file 'models.lib'\n.lib models.lib fast\n     ^~~~~~~~~~");
}

// LTspice IV writes its install path unquoted, with spaces: before, "expected '.lib FILE SECTION'"
// (three words or more) or "cannot open library file 'C:\Program'" (two).
TEST(LtspiceDialect, LibPathWithSpacesIsOneFileName) {
  Netlist n = test::parse("t\nV1 a 0 1\nD1 a 0 D\nR1 a 0 1k\n.model D D\n"
                          ".lib C:\\Program Files (x86)\\LTC\\LTspiceIV\\lib\\cmp\\standard.dio\n.tran 1u 1m\n");
  EXPECT_EQ(n.elements.size(), 3u);
  ASSERT_EQ(n.warnings.size(), 1u);
  EXPECT_EQ(n.warnings[0], "t.cir:6:6: warning: cannot open library file "
                           "'C:\\Program Files (x86)\\LTC\\LTspiceIV\\lib\\cmp\\standard.dio': lcspice goes on "
                           "with the models and subcircuits the deck defines itself (LTspice and PSpice write their own "
                           "libraries' paths into every deck)");
  n = test::parse("t\nR1 a 0 1k\nV1 a 0 1\n.lib C:\\Program Files\\LTC\\LTspiceXVII\\lib\\cmp\\standard.bjt\n");
  ASSERT_EQ(n.warnings.size(), 1u);
  EXPECT_NE(n.warnings[0].find("cannot open library file 'C:\\Program Files\\LTC\\LTspiceXVII\\lib\\cmp\\standard.bjt'"),
            std::string::npos)
      << n.warnings[0];
  // FILE SECTION stays ngspice's form (a section name has no extension).
  EXPECT_EQ(test::diag("t\nR1 a 0 1k\n.lib my models/models.lib fast\n"),
            "t.cir:3:1: error: expected '.lib FILE SECTION' or '.lib SECTION'\n.lib my models/models.lib fast\n^~~~");
}

TEST(LtspiceDialect, SectionDefinitionsAreStillSkipped) {  // `.lib NAME` ... `.endl` (ngspice)
  Netlist n = test::parse("t\nR1 a 0 1\nV1 a 0 1\n.lib fast\nR9 a 0 5\n.endl\n");
  EXPECT_EQ(n.find_element("r9"), nullptr);
  EXPECT_EQ(n.elements.size(), 2u);
}

TEST(LtspiceDialect, VendorDiodeFieldsAreDocumentationAndListed) {
  Netlist n = test::parse(
      "t\nV1 a 0 1\nD1 a 0 1N4148\n"
      ".model 1N4148 D(Is=2.52n Rs=.568 N=1.752 Cjo=4p M=.4 tt=20n Iave=200m Vpk=75 mfg=OnSemi type=silicon)\n");
  const DiodeModel& d = n.diode_models.at("1n4148");
  EXPECT_EQ(d.is, 2.52e-9);
  EXPECT_EQ(d.rs, 0.568);
  ASSERT_EQ(n.warnings.size(), 1u);
  EXPECT_EQ(n.warnings[0], "t.cir:4:42: warning: diode model '1n4148': parameters cjo, m, tt, iave, vpk, mfg, type "
                           "ignored by lcspice");
  // A word where a number belongs is still an error for the parameters the model reads.
  EXPECT_EQ(test::diag("t\nD1 a 0 dx\n.model dx D(Is=big)\n"),
            "t.cir:3:16: error: invalid number 'big'\n.model dx D(Is=big)\n               ^~~");
}

// LTspice's PWL increment: "+T" is T after the previous time point, cumulatively; a value written
// "+5" is a value, and absolute times may follow increments.
TEST(LtspiceDialect, PwlTimesWrittenWithAPlusAreIncrements) {
  Netlist n = test::parse("t\nV1 a 0 PWL 0,0 10m,0 +1u,+5 +10m,5 +1u,0 30m,1\nR1 a 0 1\n");
  const Waveform& w = test::element(n, "v1").waveform;
  EXPECT_EQ(w.params, (std::vector<double>{0, 0, 10e-3, 0, 10e-3 + 1e-6, 5, 10e-3 + 1e-6 + 10e-3, 5,
                                           10e-3 + 1e-6 + 10e-3 + 1e-6, 0, 30e-3, 1}));
  ASSERT_EQ(n.warnings.size(), 1u);
  EXPECT_EQ(n.warnings[0], "t.cir:2:8: warning: pwl times of 'v1' written '+T' are read as T after the previous "
                           "time point (LTspice; ngspice reads them as absolute times)");
  // "+{expression}" (LTspice's increment of a parameter expression), in a list with or without
  // parentheses.
  for (const char* list : {"PWL 0 0 +{tr} 1 +{2*tr} 1 +1m 0", "PWL(0,0 +{tr},1 +{2*tr},1 +1m,0)"}) {
    Netlist p = test::parse(std::string("t\n.param tr=1m\nV1 a 0 ") + list + "\nR1 a 0 1\n");
    EXPECT_EQ(test::element(p, "v1").waveform.params, (std::vector<double>{0, 0, 1e-3, 1, 3e-3, 1, 4e-3, 0})) << list;
  }
  // Without a '+' a decreasing time is still the error it was.
  EXPECT_EQ(test::diag("t\nV1 a 0 PWL(0 0 1m 1 +1m 2 0.5m 3)\nR1 a 0 1\n"),
            "t.cir:2:27: error: pwl times must not decrease\nV1 a 0 PWL(0 0 1m 1 +1m 2 0.5m 3)\n"
            "                          ^~~~");
}

// LTspice's PWL REPEAT: times count from each repetition's start, a repetition lasts until the
// last point. FOR N is written out (then the last value holds); FOREVER is ngspice's r= from the
// first point, with the ramp back to the first point appended when that point is after 0.
// `PWL file=NAME` (LTspice, PSpice; PSpice also `PWL FILE NAME`): the pairs from a text file
// beside the deck (blanks, commas or semicolons between numbers, SPICE suffixes, '*', '#' and ';'
// comment lines); TD= and R= apply as to written points. Before: "'pwl' needs at least 2
// parameters". Errors name the file (and its line).
TEST(LtspiceDialect, PwlPointsReadFromAFile) {
  Netlist n = parse_netlist_file(kData + "/pwl_file.cir");
  const std::vector<double> points{0, 0, 1e-3, 5, 2e-3, 5, 3e-3, 0};
  EXPECT_EQ(test::element(n, "v1").waveform.params, points);
  const std::vector<double> delayed{1e-3, 0, 2e-3, 5, 3e-3, 5, 4e-3, 0};
  EXPECT_EQ(test::element(n, "i1").waveform.params, delayed);
  auto error_of = [](const std::string& card) {
    const std::string deck = kData + "/pwl_error.cir";
    std::ofstream(deck) << "t\n" << card << "\nR1 a 0 1\n.tran 1m 4m\n.end\n";
    std::string message;
    try {
      parse_netlist_file(deck);
    } catch (const NetlistError& e) {
      message = e.message();
    }
    std::remove(deck.c_str());
    return message;
  };
  EXPECT_EQ(error_of("V1 a 0 PWL file=pwl/nosuch.txt"), "cannot open PWL file '" + kData + "/pwl/nosuch.txt'");
  EXPECT_EQ(error_of("V1 a 0 PWL file=pwl/bad_number.txt"),
            "PWL file '" + kData + "/pwl/bad_number.txt' line 2: invalid number 'x'");
  EXPECT_EQ(error_of("V1 a 0 PWL FILE pwl/odd.txt"),
            "PWL file '" + kData + "/pwl/odd.txt' needs time-value pairs (3 numbers)");
  EXPECT_EQ(error_of("V1 a 0 PWL file=pwl/decreasing.txt"),
            "PWL file '" + kData + "/pwl/decreasing.txt' line 3: times must not decrease");
  EXPECT_EQ(error_of("V1 a 0 PWL file="), "missing file name after 'file='");
}

TEST(LtspiceDialect, PwlRepeatForAndForever) {
  Netlist n = test::parse(
      "t\nV1 a 0 PWL REPEAT FOR 3 (0 0 1m 5 2m 0) ENDREPEAT\nV2 b 0 PWL REPEAT FOREVER 0,0 +1m,5 +1m,0 ENDREPEAT\n"
      "V3 c 0 PWL REPEAT FOREVER (1m 0 2m 5 3m 0) ENDREPEAT\nR1 a 0 1\nR2 b 0 1\nR3 c 0 1\n");
  const Waveform& a = test::element(n, "v1").waveform;
  EXPECT_EQ(a.params, (std::vector<double>{0, 0, 1e-3, 5, 2e-3, 0, 3e-3, 5, 4e-3, 0, 5e-3, 5, 6e-3, 0}));
  EXPECT_FALSE(a.repeat_from.has_value());
  EXPECT_EQ(a.value(100), 0.0);
  const Waveform& b = test::element(n, "v2").waveform;
  EXPECT_EQ(b.params, (std::vector<double>{0, 0, 1e-3, 5, 2e-3, 0}));
  ASSERT_TRUE(b.repeat_from.has_value());
  EXPECT_EQ(*b.repeat_from, 0.0);
  EXPECT_NEAR(b.value(10.5e-3), 2.5, 1e-9);  // 0.5 ms into the sixth repetition
  const Waveform& c = test::element(n, "v3").waveform;
  EXPECT_EQ(c.params, (std::vector<double>{1e-3, 0, 2e-3, 5, 3e-3, 0, 4e-3, 0}));
  EXPECT_EQ(*c.repeat_from, 1e-3);
  EXPECT_NEAR(c.value(0.5e-3), 0.0, 1e-12);   // before the first point: its value
  EXPECT_NEAR(c.value(4.5e-3), 2.5, 1e-9);    // the second repetition's rise, 1.5 ms into it
  EXPECT_NEAR(c.value(300.5e-3 + 1e-3), 2.5, 1e-9);  // the 101st
  EXPECT_EQ(test::diag("t\nV1 a 0 PWL REPEAT FOR 2.5 (0 0 1m 1) ENDREPEAT\n"),
            "t.cir:2:23: error: REPEAT FOR count must be a whole number of at least 1\n"
            "V1 a 0 PWL REPEAT FOR 2.5 (0 0 1m 1) ENDREPEAT\n                      ^~~");
  EXPECT_EQ(test::diag("t\nV1 a 0 PWL REPEAT FOR 3 (0 0 1m 1)\n"),
            "t.cir:2:35: error: expected 'ENDREPEAT' (LTspice's PWL REPEAT)\nV1 a 0 PWL REPEAT FOR 3 (0 0 1m 1)\n"
            "                                  ^");
  EXPECT_EQ(test::diag("t\nV1 a 0 PWL(0 0 1m 1) REPEAT FOREVER (0 0 1m 1) ENDREPEAT\n"),
            "t.cir:2:22: error: LTspice's REPEAT is read as the whole PWL only ('PWL REPEAT FOR N (...) ENDREPEAT' or "
            "'PWL REPEAT FOREVER (...) ENDREPEAT'), not after other points\n"
            "V1 a 0 PWL(0 0 1m 1) REPEAT FOREVER (0 0 1m 1) ENDREPEAT\n                     ^~~~~~");
}

TEST(LtspiceDialect, BackannoIsAcceptedSilently) {
  Netlist n = test::parse("t\nR1 a 0 1\nV1 a 0 1\n.backanno\n");
  EXPECT_TRUE(n.warnings.empty());
  EXPECT_EQ(n.elements.size(), 2u);
}

TEST(NgspiceGlobal, GlobalNodesAreSharedByEverySubcircuitInstance) {
  Netlist n = test::parse(
      "t\n.subckt load a\nR1 a vdd 1k\nR2 a gnd2 2k\n.ends\n"
      "X1 n1 load\nX2 n2 load\nVdd vdd 0 5\nR9 gnd2 0 1\n.global vdd\n");
  EXPECT_EQ(test::element(n, "x1.r1").nodes[1], "vdd");
  EXPECT_EQ(test::element(n, "x2.r1").nodes[1], "vdd");
  EXPECT_EQ(test::element(n, "x1.r2").nodes[1], "x1.gnd2");  // not global: local to the instance
  // A port of the same name is the port.
  n = test::parse("t\n.subckt load vdd\nR1 vdd 0 1k\n.ends\nX1 n1 load\nV1 vdd 0 1\n.global vdd\n");
  EXPECT_EQ(test::element(n, "x1.r1").nodes[0], "n1");
  EXPECT_EQ(test::diag("t\nR1 a 0 1\n.global\n"), "t.cir:3:8: error: missing node names after '.global'\n.global\n       ^");
}

// Parasitics an element does not take (instance_parasitics_test.cpp reads the ones it does).
TEST(LtspiceDialect, ParasiticsAnElementDoesNotTakeAreRefusedWithTheRemedy) {
  EXPECT_EQ(test::diag("t\nL1 in 0 1m Lser=1n\n"),
            "t.cir:2:12: error: unknown parameter 'Lser' for 'l1' (LTspice's series parasitic: lcspice reads Rser on "
            "L, C and V and Lser on C; write this one as its own element in series)\nL1 in 0 1m Lser=1n\n"
            "           ^~~~");
  EXPECT_EQ(test::diag("t\nR1 a 0 1k Cpar=1p\n"),
            "t.cir:2:11: error: unknown parameter 'Cpar' for 'r1' (LTspice's parallel parasitic: lcspice reads Rpar on "
            "L and C and Cpar on L, C and V; write this one as its own element in parallel)\nR1 a 0 1k Cpar=1p\n"
            "          ^~~~");
  EXPECT_EQ(test::diag("t\nV1 in 0 5 foo=1\n"),
            "t.cir:2:11: error: unknown parameter 'foo' for 'v1'\nV1 in 0 5 foo=1\n          ^~~");
}

// LTspice's .tran flags: `startup` ramps the supplies up from 0 V over 20 us; read as UIC (a
// start from rest), with a warning saying so. `steady` and `nodiscard` change nothing here.
TEST(LtspiceDialect, TranFlagsStartupSteadyNodiscard) {
  const Netlist n = test::parse("t\nV1 a 0 5\nR1 a b 1k\nC1 b 0 1u\n.tran 0 1m 0 startup steady nodiscard\n");
  ASSERT_TRUE(n.tran.has_value());
  EXPECT_TRUE(n.tran->uic);
  EXPECT_DOUBLE_EQ(n.tran->tstop, 1e-3);
  ASSERT_EQ(n.warnings.size(), 4u);
  EXPECT_EQ(n.warnings[0], "t.cir:5:14: warning: 'startup' (LTspice: the supplies ramped up from 0 V over the first "
                           "20 us) is read as UIC: the run starts from rest with the sources at their values");
  EXPECT_EQ(n.warnings[1], "t.cir:5:22: warning: 'steady' (LTspice) is ignored: lcspice runs to TSTOP and writes rows "
                           "from TSTART");
  EXPECT_EQ(n.warnings[2], "t.cir:5:29: warning: 'nodiscard' (LTspice) is ignored: lcspice runs to TSTOP and writes "
                           "rows from TSTART");
}

TEST(LtspiceDialect, SweepsAreRefusedByName) {
  EXPECT_EQ(test::diag("t\nR1 a 0 {r}\n.param r=1k\n.step param r 1k 10k 1k\n"),
            "t.cir:4:1: error: '.step' (parameter sweeps, LTspice/PSpice) is not supported: lcspice runs one "
            "transient per deck; give each value its own deck or .param\n.step param r 1k 10k 1k\n^~~~~");
  // LTspice writes the directives last, and the stepped parameter is defined by .step alone:
  // before, "undefined parameter 'r'" at R1.
  EXPECT_EQ(test::diag("t\nV1 a 0 1\nR1 a 0 {r}\n.step param r 1k 10k 1k\n.tran 1m 20m\n"),
            "t.cir:4:1: error: '.step' (parameter sweeps, LTspice/PSpice) is not supported: lcspice runs one "
            "transient per deck; give each value its own deck or .param\n.step param r 1k 10k 1k\n^~~~~");
}

// LTspice's K with more than two inductors couples every pair by the one k: K1 plus K1#2, K1#3.
TEST(LtspiceDialect, CouplingOfThreeInductorsIsEveryPair) {
  const Netlist n = test::parse("t\nV1 a 0 1\nLP a 0 100m\nLS1 b c 25m\nLS2 c d 25m\nR1 b d 1\nR2 c 0 1\n"
                                "K1 LP LS1 LS2 0.999\n");
  const std::vector<std::pair<std::string, std::vector<std::string>>> expected = {
      {"k1", {"lp", "ls1"}}, {"k1#2", {"lp", "ls2"}}, {"k1#3", {"ls1", "ls2"}}};
  for (const auto& [name, coupled] : expected) {
    const Element& k = test::element(n, name);
    EXPECT_EQ(k.kind, ElementKind::Coupling) << name;
    EXPECT_EQ(k.coupled, coupled) << name;
    EXPECT_EQ(k.value, 0.999) << name;
  }
  EXPECT_TRUE(n.warnings.empty());
  EXPECT_EQ(test::diag("t\nL1 a 0 1\nL2 b 0 1\nR1 a b 1\nK1 L1 L2 L1 1\n"),
            "t.cir:5:10: error: 'k1' couples 'l1' twice\nK1 L1 L2 L1 1\n         ^~");
  EXPECT_EQ(test::diag("t\nL1 a 0 1\nL2 b 0 1\nR1 a b 1\nK1 L1 L2 L3 1\n"),
            "t.cir:5:10: error: coupled inductor 'l3' is not defined\nK1 L1 L2 L3 1\n         ^~");
  EXPECT_EQ(test::diag("t\nL1 a 0 1\nL2 b 0 1\nR1 a b 1\nK1 L1 L2\n"),
            "t.cir:5:9: error: missing coupling coefficient for 'k1'\nK1 L1 L2\n        ^");
  // A coefficient after one inductor: the second inductor is what is missing.
  EXPECT_EQ(test::diag("t\nL1 a 0 1\nK1 L1 0.5\n"),
            "t.cir:3:7: error: missing inductor name for 'k1' (K takes two or more inductors and k)\nK1 L1 0.5\n"
            "      ^~~");
}

}  // namespace
}  // namespace lcs
