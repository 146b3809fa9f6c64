// `lcspice run --method theta --euler-at-switching` checks its stiff steps whose mode changes
// against implicit Euler's (solver/integrators/euler_at_switching.h); by default every step is
// theta's own.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/cli_support.h"

namespace lcs::cli_testing {
namespace {

// circuits/stability/diode_charged_rc_large_step.cir: 1 uF charged from 10 V through a diode
// (VON 0.7) and 1 kOhm (tau = 1 ms) at h = 100 tau. The trapezoidal rule's first step ends at
// (h / 2 tau) 9.3 V = 465 V with the diode off, and the diode holds it; implicit Euler's ends at
// 9.3 (h/tau) / (1 + h/tau) = 9.2079 V conducting, and the run reaches 9.3 V.
std::vector<double> v_out(const std::string& flags, std::string* err = nullptr) {
  const fs::path dir = scratch_dir("euler_at_switching_cli");
  const std::string csv = (dir / "out.csv").string();
  const Result r = run_lcspice("run '" + source_path("circuits/stability/diode_charged_rc_large_step.cir").string() +
                                   "' " + flags + " --stats -o '" + csv + "'",
                               dir);
  EXPECT_EQ(r.code, 0) << r.err;
  if (err) *err = r.err;
  return column(parse_csv(read_file(csv)), "v(out)");
}

TEST(EulerAtSwitchingCli, TheFlagCuresTheHeldOvershootOfTheDefault) {
  std::string err;
  const std::vector<double> checked = v_out("--method theta --euler-at-switching", &err);
  ASSERT_EQ(checked.size(), 11u);
  EXPECT_NEAR(checked[1], 9.3 * 100 / 101, 1e-9);
  EXPECT_NEAR(checked.back(), 9.3, 1e-9);
  EXPECT_NE(err.find("steps taken by implicit Euler at stiff mode changes (and the steps after): "), std::string::npos)
      << err;

  const std::vector<double> own = v_out("--method theta", &err);
  ASSERT_EQ(own.size(), 11u);
  EXPECT_NEAR(own[1], 465.0, 1e-4);
  EXPECT_NEAR(own.back(), 465.0, 1e-4);
  EXPECT_EQ(err.find("implicit Euler at stiff mode changes"), std::string::npos) << err;
}

TEST(EulerAtSwitchingCli, FlagIsIgnoredWithAWarningByOtherMethods) {
  std::string err;
  const std::vector<double> v = v_out("--method euler --euler-at-switching", &err);
  EXPECT_NEAR(v.back(), 9.3, 1e-9);
  EXPECT_NE(err.find("warning: --euler-at-switching is used only by --method theta; method euler ignores it"),
            std::string::npos)
      << err;
}

}  // namespace
}  // namespace lcs::cli_testing
