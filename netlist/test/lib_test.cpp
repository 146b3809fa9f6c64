// `.lib FILE SECTION` and `.lib SECTION` ... `.endl` (ngspice's library sections).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "netlist/netlist.h"
#include "netlist/test/parse_helpers.h"

namespace lcs {
namespace {

const std::string kData = LCSPICE_TEST_DATA;

std::string file_diag(const std::string& path) {
  try {
    parse_netlist_file(path);
  } catch (const NetlistError& e) {
    return e.formatted();
  }
  return "<no error>";
}

TEST(ParseLib, ReadsOnlyTheSectionsAskedFor) {
  Netlist n = parse_netlist_file(kData + "/lib_top.cir");
  // Section 'diodes' (quoted file name): the model, located in the library.
  ASSERT_EQ(n.diode_models.count("dfast"), 1u);
  EXPECT_EQ(*n.diode_models.at("dfast").ron, 2.0);
  EXPECT_EQ(n.diode_models.at("dfast").loc.file, kData + "/lib/sections.lib");
  EXPECT_EQ(n.diode_models.at("dfast").loc.line, 4);
  // Section 'LOAD' (case-insensitive, bare file name) takes section 'res' of the same file,
  // found relative to the library, with its .param.
  const Element& r3 = test::element(n, "x1.x2.r3");
  EXPECT_EQ(r3.value, 2000.0);
  EXPECT_EQ(r3.loc.file, kData + "/lib/sections.lib");
  // Outside any section (R0) and the deck's own unused section (R9): not read.
  EXPECT_EQ(n.find_element("r0"), nullptr);
  EXPECT_EQ(n.find_element("r9"), nullptr);
  EXPECT_EQ(n.elements.size(), 3u);
}

TEST(ParseLib, MissingSectionIsAnErrorAtTheLibLineNamingIt) {
  EXPECT_EQ(file_diag(kData + "/lib_missing_section.cir"),
            kData + "/lib_missing_section.cir:2:25: error: library 'lib/sections.lib' has no section 'nosuch' "
                    "(its sections: diodes, load, res)\n"
                    ".lib \"lib/sections.lib\" nosuch\n"
                    "                        ^~~~~~");
}

TEST(ParseLib, MissingFileIsAnErrorAtTheLibLineBeforeLaterCards) {
  EXPECT_EQ(file_diag(kData + "/lib_missing_file.cir"),
            kData + "/lib_missing_file.cir:3:6: error: cannot open library file 'lib/no_such.lib'\n"
                    ".lib lib/no_such.lib res\n"
                    "     ^~~~~~~~~~~~~~~");
}

TEST(ParseLib, SectionWithoutEndlAndStrayEndl) {
  // With no `.endl` after it, `.lib foo` is LTspice's include of file foo (ltspice_dialect_test).
  EXPECT_EQ(test::diag("t\n.lib foo\nR1 a 0 1\n"),
            "t.cir:2:6: error: cannot open library file 'foo' ('.lib FILE' reads FILE, as LTspice does; a section "
            "'.lib foo' ends at '.endl')\n.lib foo\n     ^~~");
  EXPECT_EQ(test::diag("t\nR1 a 0 1\n.endl\n"), "t.cir:3:1: error: '.endl' without '.lib'\n.endl\n^~~~~");
}

// ngspice's own regression deck: X1 -> sub1 -> X2 of 'sub_in_lib' from ex1.lib section RES.
TEST(ParseLib, NgspiceRegressionDeckEx1a) {
  const std::string dir = std::string(LCSPICE_REALWORLD_DIR) + "/ngspice/tests/regression/lib-processing";
  if (!std::ifstream(dir + "/ex1a.cir")) GTEST_SKIP() << "real-world decks not found in " << dir;
  Netlist n = parse_netlist_file(dir + "/ex1a.cir");
  const Element& r3 = test::element(n, "x1.x2.r3");
  EXPECT_EQ(r3.value, 2000.0);
  EXPECT_EQ(r3.nodes, (std::vector<std::string>{"9", "0"}));
  EXPECT_EQ(r3.loc.file, (std::filesystem::path(dir) / "ex1.lib").lexically_normal().string());
}

}  // namespace
}  // namespace lcs
