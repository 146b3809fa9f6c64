// Every tests/bad_netlists/*.cir file fails to parse with exactly the diagnostic its
// `* expect-diag:` line announces, so the command-line test that runs them is known to be right.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "netlist/netlist.h"

namespace lcs {
namespace {

namespace fs = std::filesystem;

const std::string kDir = fs::path(LCSPICE_TEST_DATA "/../../../tests/bad_netlists").lexically_normal().string();

std::vector<std::string> bad_netlists() {
  std::vector<std::string> out;
  for (const auto& entry : fs::directory_iterator(kDir))
    if (entry.path().extension() == ".cir") out.push_back(entry.path().string());
  std::sort(out.begin(), out.end());
  return out;
}

// The text after `* key:` in the file's header comments.
std::string header_value(const std::string& path, const std::string& key) {
  std::ifstream in(path);
  std::string line;
  const std::string prefix = "* " + key + ": ";
  while (std::getline(in, line))
    if (line.rfind(prefix, 0) == 0) return line.substr(prefix.size());
  return "";
}

TEST(ParseBadNetlists, ThereAreEnoughOfThem) { EXPECT_GE(bad_netlists().size(), 16u); }

TEST(ParseBadNetlists, EachFailsWithItsExpectedDiagnostic) {
  for (const std::string& path : bad_netlists()) {
    SCOPED_TRACE(path);
    // Files marked with a later stage (topology, run, transient) parse cleanly by design;
    // the command-line suite checks them.
    if (!header_value(path, "stage").empty()) {
      EXPECT_NO_THROW(parse_netlist_file(path));
      continue;
    }
    EXPECT_EQ(header_value(path, "expect-exit"), "2");
    const std::string expected = header_value(path, "expect-diag");
    ASSERT_FALSE(expected.empty());
    try {
      parse_netlist_file(path);
      ADD_FAILURE() << "parsed without error";
    } catch (const NetlistError& e) {
      const std::string formatted = e.formatted();
      EXPECT_EQ(formatted.substr(0, formatted.find('\n')), path + ":" + expected);
      // The caret line is there too: the diagnostic is complete.
      EXPECT_EQ(std::count(formatted.begin(), formatted.end(), '\n'), 2);
    }
  }
}

TEST(ParseBadNetlists, NamesFollowTheConvention) {
  for (const std::string& path : bad_netlists()) {
    const std::string name = fs::path(path).filename().string();
    EXPECT_TRUE(name.size() > 7 && std::isdigit(static_cast<unsigned char>(name[0])) &&
                std::isdigit(static_cast<unsigned char>(name[1])) && name[2] == '-')
        << name;
  }
}

}  // namespace
}  // namespace lcs
