// .include: paths relative to the including file, locations inside included files, errors.
#include <gtest/gtest.h>

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

TEST(ParseInclude, RelativePathsNestedAndQuoted) {
  Netlist n = parse_netlist_file(kData + "/include_top.cir");
  EXPECT_EQ(n.file, kData + "/include_top.cir");
  EXPECT_EQ(n.title, "Top level that includes a model library and a subcircuit file");
  // lib/diodes.lib (bare name), which includes ../common.inc relative to lib/
  ASSERT_EQ(n.diode_models.count("dfast"), 1u);
  EXPECT_EQ(*n.diode_models.at("dfast").von, 0.6);
  EXPECT_EQ(n.diode_models.at("dfast").loc.file, kData + "/lib/diodes.lib");
  EXPECT_EQ(n.diode_models.at("dfast").loc.line, 2);
  // "lib/rc filter.inc" (quoted, with a space), parameter from common.inc
  const Element& r = test::element(n, "xf.r1");
  EXPECT_EQ(r.value, 2000);
  EXPECT_EQ(r.nodes, (std::vector<std::string>{"mid", "xf.mid"}));
  EXPECT_EQ(r.loc.file, kData + "/lib/rc filter.inc");
  EXPECT_EQ(r.loc.line, 2);
  EXPECT_EQ(r.loc.line_text, "R1 in mid {r}");
  EXPECT_EQ(test::element(n, "d1").loc.file, kData + "/include_top.cir");
  EXPECT_EQ(test::element(n, "d1").loc.line, 5);
}

TEST(ParseInclude, MissingFileIsAnErrorAtTheIncludeLine) {
  EXPECT_EQ(file_diag(kData + "/include_missing.cir"),
            kData + "/include_missing.cir:3:10: error: cannot open include file 'lib/no_such_file.lib'\n"
            ".include lib/no_such_file.lib\n"
            "         ^~~~~~~~~~~~~~~~~~~~");
}

TEST(ParseInclude, CycleIsAnError) {
  EXPECT_EQ(file_diag(kData + "/include_cycle_top.cir"),
            kData + "/lib/cycle_b.inc:2:10: error: include cycle: './cycle_a.inc' is already being included\n"
            ".include ./cycle_a.inc\n"
            "         ^~~~~~~~~~~~~");
}

TEST(ParseInclude, ErrorsInsideAnIncludedFileNameThatFile) {
  EXPECT_EQ(file_diag(kData + "/include_error.cir"),
            kData + "/lib/broken.inc:3:11: error: undefined parameter 'nosuch'\n"
            "R3 a 0 {2*nosuch}\n"
            "          ^~~~~~");
}

TEST(ParseInclude, EndInsideAnIncludedFileEndsOnlyThatFile) {
  Netlist n = parse_netlist_file(kData + "/include_end.cir");
  ASSERT_EQ(n.elements.size(), 2u);
  EXPECT_EQ(n.elements[0].name, "r1");
  EXPECT_EQ(n.elements[1].name, "r2");
}

TEST(ParseInclude, FromAStringRelativeToItsFileName) {
  Netlist n = parse_netlist_string("t\n.include common.inc\nR1 a 0 {rload}\n", kData + "/virtual.cir");
  EXPECT_EQ(n.elements[0].value, 2000);
  EXPECT_EQ(test::diag("t\n.include\n"),
            "t.cir:2:9: error: missing file name after '.include'\n"
            ".include\n"
            "        ^");
  EXPECT_EQ(test::diag("t\n.include \"a.inc\" extra\n"),
            "t.cir:2:18: error: unexpected extra token 'extra'\n"
            ".include \"a.inc\" extra\n"
            "                 ^~~~~");
}

TEST(ParseInclude, ADirectoryIsNotAFile) {
  EXPECT_EQ(test::diag("t\n.include lib\n", kData + "/x.cir"),
            kData + "/x.cir:2:10: error: cannot open include file 'lib'\n.include lib\n         ^~~");
}

}  // namespace
}  // namespace lcs
