// The generated circuit families of `bench --scale` (cli/scale_family.h): they parse and form a
// model, hold the cells they promise, every diode switches in the benchmark interval, and a small
// Cockcroft-Walton multiplier pumps up to its known no-load level.
#include <algorithm>
#include <map>

#include <gtest/gtest.h>

#include "cli/scale_family.h"
#include "netlist/netlist.h"
#include "solver/model/circuit_model.h"
#include "tests/cli_support.h"

namespace lcs::cli_testing {
namespace {

constexpr ScaleFamily kFamilies[] = {ScaleFamily::CockcroftWalton, ScaleFamily::Ladder, ScaleFamily::Rectifiers};

std::map<ElementKind, int> count_kinds(const Netlist& netlist) {
  std::map<ElementKind, int> count;
  for (const Element& e : netlist.elements) ++count[e.kind];
  return count;
}

// Lines of the text that are D cards.
int d_cards(const std::string& text) {
  std::istringstream in(text);
  std::string line;
  int n = 0;
  while (std::getline(in, line))
    if (!line.empty() && (line[0] == 'D' || line[0] == 'd')) ++n;
  return n;
}

fs::path write_netlist(ScaleFamily family, int n) {
  const fs::path dir = scratch_dir(std::string("scale_family_") + scale_family_name(family) + std::to_string(n));
  const fs::path path = dir / "circuit.cir";
  std::ofstream(path) << scale_family_netlist(family, n);
  return path;
}

TEST(ScaleFamily, NamesRoundTrip) {
  for (ScaleFamily f : kFamilies) EXPECT_EQ(find_scale_family(scale_family_name(f)), f);
  EXPECT_FALSE(find_scale_family("bridge").has_value());
}

TEST(ScaleFamily, NetlistsParseFormAModelAndHoldTheirCells) {
  for (ScaleFamily f : kFamilies)
    for (int n : {1, 3, 7}) {
      SCOPED_TRACE(std::string(scale_family_name(f)) + " N=" + std::to_string(n));
      const std::string text = scale_family_netlist(f, n);
      const Netlist netlist = parse_netlist_string(text, "family.cir");
      EXPECT_TRUE(netlist.warnings.empty());
      const std::map<ElementKind, int> count = count_kinds(netlist);
      const int diodes = scale_family_diodes(f, n);
      EXPECT_EQ(d_cards(text), diodes);
      EXPECT_EQ(count.at(ElementKind::Diode), diodes);
      switch (f) {
        case ScaleFamily::CockcroftWalton:
          EXPECT_EQ(diodes, 2 * n);
          EXPECT_EQ(count.at(ElementKind::Capacitor), 2 * n);
          EXPECT_EQ(count.at(ElementKind::Resistor), 1);
          EXPECT_EQ(count.at(ElementKind::VoltageSource), 1);
          break;
        case ScaleFamily::Ladder:
          EXPECT_EQ(diodes, n);
          EXPECT_EQ(count.at(ElementKind::Resistor), n);
          EXPECT_EQ(count.at(ElementKind::Capacitor), n);
          EXPECT_EQ(count.at(ElementKind::VoltageSource), 2);
          break;
        case ScaleFamily::Rectifiers:
          EXPECT_EQ(diodes, n);
          EXPECT_EQ(count.at(ElementKind::Resistor), 2 * n);
          EXPECT_EQ(count.at(ElementKind::Capacitor), n);
          EXPECT_EQ(count.at(ElementKind::VoltageSource), 1);
          break;
      }
      EXPECT_EQ(count.size(), 4u);  // those kinds only
      ASSERT_TRUE(netlist.tran.has_value());
      EXPECT_TRUE(netlist.tran->uic);
      EXPECT_NEAR(netlist.tran->tstop / netlist.tran->tstep, 1000, 1e-6);
      ModelOptions options;
      options.t1 = netlist.tran->tstop;
      const CircuitModel model = CircuitModel::build(netlist, options);
      EXPECT_EQ(model.netlist().elements.size(), netlist.elements.size());
      ASSERT_EQ(netlist.probes.size(), f == ScaleFamily::Rectifiers && n > 1 ? 2u : 1u);
      EXPECT_EQ(netlist.probes.back().a, scale_family_output_node(f, n));
    }
  EXPECT_THROW(scale_family_netlist(ScaleFamily::Ladder, 0), std::invalid_argument);
}

TEST(ScaleFamily, DefaultSizesRunFromTenToAThousandDiodes) {
  for (ScaleFamily f : kFamilies) {
    std::vector<int> diodes;
    for (int n : default_scale_sizes(f)) diodes.push_back(scale_family_diodes(f, n));
    EXPECT_EQ(diodes, (std::vector<int>{10, 20, 50, 100, 200, 500, 1000})) << scale_family_name(f);
  }
}

// The benchmark interval is meant to make every diode switch: each one's current is zero at some
// output time and well above zero at another (euler over the family's own five periods, N = 6).
TEST(ScaleFamily, EveryDiodeSwitchesInTheInterval) {
  for (ScaleFamily f : kFamilies) {
    SCOPED_TRACE(scale_family_name(f));
    const int n = 6, diodes = scale_family_diodes(f, n);
    std::string probes;
    for (int k = 1; k <= diodes; ++k) probes += (k > 1 ? "," : "") + std::string("i(d") + std::to_string(k) + ")";
    const Csv csv = run_csv(write_netlist(f, n), "euler", "--probe '" + probes + "'");
    for (int k = 1; k <= diodes; ++k) {
      const std::vector<double> i = column(csv, "i(d" + std::to_string(k) + ")");
      ASSERT_FALSE(i.empty());
      EXPECT_LT(*std::min_element(i.begin(), i.end()), 1e-9) << "d" << k << " never turns off";
      EXPECT_GT(*std::max_element(i.begin(), i.end()), 1e-6) << "d" << k << " never conducts";
    }
  }
}

// Three stages pump up to 2N (VP - VON) = 6 (100 - 0.7) = 595.8 V less the droop of the 1 Gohm
// load, (I / fC) (2N^3/3 + N^2/2 - N/6) = (0.596 uA / (50 Hz 10 uF)) 22 = 0.026 V. The approach is
// geometric (within 0.6 V after 100 periods, 0.02 V after 150); after 200 periods (euler, 200
// steps a period) the top is within 0.02 V of that level and never above 2N (VP - VON).
TEST(ScaleFamily, CockcroftWaltonPumpsUpToTwoNTimesThePeakLessTheDrops) {
  const Csv csv = run_csv(write_netlist(ScaleFamily::CockcroftWalton, 3), "euler", "--tstop 4 --probe 'v(b3)'");
  const std::vector<double> top = column(csv, "v(b3)");
  ASSERT_GT(top.size(), 100u);
  const double no_load = 6 * (100 - 0.7), droop = (no_load / 1e9) / (50 * 10e-6) * (2 * 27 / 3.0 + 9 / 2.0 - 3 / 6.0);
  EXPECT_NEAR(top.back(), no_load - droop, 0.02);
  EXPECT_LT(*std::max_element(top.begin(), top.end()), no_load);
}

}  // namespace
}  // namespace lcs::cli_testing
