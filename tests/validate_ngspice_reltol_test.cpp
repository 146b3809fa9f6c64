// Why bjt_boost and bjt_astable give ngspice reltol=1e-5 (circuits/validation.tsv, README
// "ngspice's maximum step is the output interval"): at validate's default TMAX (the output
// interval) they failed, and it was ngspice, at its default RELTOL = 1e-3, that was wrong right
// after a collector reached saturation (the B-C junction clamping a capacitor, an index-one
// clamp). Read here at ngspice's own time points (no interpolation), from the very deck validate
// hands it (--print-deck): its trapezoidal rule rings in the boost, its Gear-2 formula overshoots
// below VCESAT in the astable; at reltol=1e-5 neither happens.
#include <algorithm>
#include <cmath>
#include <sstream>

#include <gtest/gtest.h>

#include "ngspice/ngspice_session.h"
#include "tests/cli_support.h"

namespace lcs {
namespace {

using namespace cli_testing;

// ngspice's run of the deck `validate --print-deck CIRCUIT OPTIONS` prints.
NgspiceResult ngspice_run_of_validate_deck(const std::string& circuit, const std::string& options) {
  const fs::path dir = scratch_dir("validate_reltol_" + circuit);
  const Result r = run_lcspice("validate --print-deck '" + source_path("circuits/" + circuit + ".cir").string() +
                                   "' " + options, dir);
  EXPECT_EQ(r.code, 0) << r.err;
  NgspiceRun run;
  std::istringstream in(r.out);
  for (std::string line; std::getline(in, line);) run.deck.push_back(line);
  run.timeout_seconds = 60;
  return run_ngspice_transient(run);
}

// Saturated (v(sw) below 0.11 V at two successive points), the collector current minus the
// inductor's (the switch node is flat there, the diode off: they should agree) changes sign
// between the two points, by more than 0.05 A either side: the trapezoidal rule's ringing.
// Measured: 36 such alternations over the ten periods at RELTOL 1e-3 (ic 0.39, 0.63, 0.39,
// 0.63 A after the clamp at 20.027 us, where lcspice has 0.511 A), none at 1e-5.
int ringing_alternations(const NgspiceResult& r) {
  const std::vector<double>& sw = r.vectors.at("sw");
  const std::vector<double>& ic = r.vectors.at("v_ic_q1#branch");
  const std::vector<double>& il = r.vectors.at("v_amm_l1#branch");
  int n = 0;
  for (size_t k = 1; k < sw.size(); ++k) {
    const double before = ic[k - 1] - il[k - 1], after = ic[k] - il[k];
    const bool saturated = sw[k - 1] < 0.11 && sw[k] < 0.11;
    if (saturated && before * after < 0 && std::abs(before) > 0.05 && std::abs(after) > 0.05) ++n;
  }
  return n;
}

TEST(ValidateNgspiceReltol, TheBoostsTrapezoidalRingingAfterSaturationGoesAtReltol1e5) {
  EXPECT_GT(ringing_alternations(ngspice_run_of_validate_deck("bjt_boost", "")), 20);
  EXPECT_EQ(ringing_alternations(ngspice_run_of_validate_deck("bjt_boost", "--ngspice-option reltol=1e-5")), 0);
}

// The lowest collector voltage over the run: VCESAT = VONE - VONC = 0.2 V is the floor of the
// model (lcspice's rows never go below it). Measured: v(c1) 0.057 V and v(c2) 0.067 V for about
// 0.4 ns after a switching at RELTOL 1e-3 (Gear), 0.1976 and 0.1983 V at 1e-5.
TEST(ValidateNgspiceReltol, TheAstablesGearOvershootBelowVcesatGoesAtReltol1e5) {
  auto lowest = [](const NgspiceResult& r, const char* node) {
    const std::vector<double>& v = r.vectors.at(node);
    return *std::min_element(v.begin(), v.end());
  };
  const NgspiceResult loose = ngspice_run_of_validate_deck("bjt_astable", "--ngspice-option method=gear");
  EXPECT_LT(lowest(loose, "c1"), 0.1);
  EXPECT_LT(lowest(loose, "c2"), 0.1);
  const NgspiceResult tight =
      ngspice_run_of_validate_deck("bjt_astable", "--ngspice-option method=gear --ngspice-option reltol=1e-5");
  EXPECT_GT(lowest(tight, "c1"), 0.19);
  EXPECT_GT(lowest(tight, "c2"), 0.19);
}

}  // namespace
}  // namespace lcs
