// Diodes fitted to the circuit's own currents, breakdown (Zener) pairs, --diode auto and LTspice's
// ideal-diode card (issue 13; README "Diode law"). The decks are written here: each is the
// smallest circuit that shows one thing.
#include <algorithm>
#include <cmath>
#include <fstream>

#include "tests/cli_support.h"

namespace lcs {
namespace {

using namespace cli_testing;

fs::path write_deck(const fs::path& dir, const std::string& name, const std::string& text) {
  const fs::path p = dir / name;
  std::ofstream(p) << text;
  return p;
}

double max_of(const std::vector<double>& v) { return *std::max_element(v.begin(), v.end()); }
double min_of(const std::vector<double>& v) { return *std::min_element(v.begin(), v.end()); }

// Largest |a - b| over the rows both runs share a time with (event rows add switching instants).
double max_difference(const Csv& a, const Csv& b, const std::string& probe) {
  const std::vector<double> ta = column(a, "time"), tb = column(b, "time");
  const std::vector<double> va = column(a, probe), vb = column(b, probe);
  double worst = 0;
  size_t j = 0;
  for (size_t k = 0; k < ta.size(); ++k) {
    while (j < tb.size() && tb[j] < ta[k] - 1e-12) ++j;
    if (j < tb.size() && std::abs(tb[j] - ta[k]) <= 1e-12) worst = std::max(worst, std::abs(va[k] - vb[j]));
  }
  return worst;
}

const char* const kDetector =
    "half-wave rectifier at microamperes: 1 V sine, 100k load, a card with only IS and N\n"
    "V1 in 0 SIN(0 1 1k)\n"
    "D1 in out dsig\n"
    "R1 out 0 100k\n"
    ".model dsig D(IS=1e-14 N=1)\n"
    ".tran 2u 3m\n"
    ".print tran v(out) i(d1)\n"
    ".end\n";

}  // namespace
}  // namespace lcs
