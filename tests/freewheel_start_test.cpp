// A half-wave rectifier into an RL load with a freewheeling diode, started from rest (UIC): the
// inductor's current is the two diodes' (both off at t = 0), so the event method's switching
// LCP has rows of O(eta) there, and Lemke's path ended on a ray: "no next mode: the switching
// LCP has no solution" at t = 0 (the default run fell back to euler). With no operating point
// and no mode before the event, the first guess is now the mode with nothing conducting, and
// the search around it finds the one that continues the state. Found by a prober comparing the
// fixed-step methods with event.
#include <cmath>
#include <map>
#include <string>

#include <gtest/gtest.h>

#include "tests/cli_support.h"

namespace lcs::cli_testing {
namespace {

const char* const kFreewheel =
    "half wave inductive load with freewheel\nV1 a 0 SIN(0 10 1k)\nD1 a x dd\nD2 0 x dd\nL1 x y 10m\nR1 y 0 10\n"
    ".model dd D(VON=0.7 RON=0.05)\n.tran 1u 5m UIC\n.print tran i(l1) i(d1) i(d2) v(x)\n.end\n";

// Against radau5 at 0.1 us (every mode here is linear and radau5 fifth order inside it; the two
// agree to 4e-10 A on currents up to 0.32 A, measured); both diodes take turns.
TEST(FreewheelStart, EventStartsFromRestAndAgreesWithRadau) {
  const fs::path deck = write_deck("freewheel_", "hw_rl", kFreewheel);
  const Csv event = run_csv(deck, "event");
  const Csv radau = run_csv(deck, "radau5", "--step 1e-7");
  const std::vector<double> te = column(event, "time"), tr = column(radau, "time");
  std::map<long, size_t> radau_row;
  for (size_t k = 0; k < tr.size(); ++k) radau_row[std::lround(tr[k] * 1e7)] = k;
  int compared = 0, d1_on = 0, d2_on = 0;
  for (const char* probe : {"i(l1)", "i(d1)", "i(d2)"}) {
    const std::vector<double> ye = column(event, probe), yr = column(radau, probe);
    double worst = 0;
    for (size_t k = 0; k < te.size(); ++k) {
      const auto it = radau_row.find(std::lround(te[k] * 1e7));
      if (it == radau_row.end() || std::abs(tr[it->second] - te[k]) > 1e-12) continue;
      worst = std::max(worst, std::abs(ye[k] - yr[it->second]));
      ++compared;
      if (std::string(probe) == "i(d1)" && ye[k] > 1e-3) ++d1_on;
      if (std::string(probe) == "i(d2)" && ye[k] > 1e-3) ++d2_on;
    }
    EXPECT_LT(worst, 1e-6) << probe;
  }
  EXPECT_GT(compared, 3 * 4900);
  EXPECT_GT(d1_on, 1000);
  EXPECT_GT(d2_on, 1000);
}

}  // namespace
}  // namespace lcs::cli_testing
