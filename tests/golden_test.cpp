// Golden waveforms: every circuit in tests/golden/manifest.tsv runs with implicit Euler at its
// .tran TSTEP and every probe is compared with tests/golden/<circuit>.csv, a reference computed
// at TSTEP/64 and checked against TSTEP/32 (tests/golden/generate.sh). The tolerance is on
//   max_t |y(t) - y_ref(t)| / range(y_ref)
// for every probe, stated per circuit in the manifest.
#include <cmath>

#include <gtest/gtest.h>

#include "netlist/netlist.h"
#include "solver/integrators/transient.h"
#include "tests/cli_support.h"

namespace lcs {
namespace {

using namespace cli_testing;

struct GoldenCase {
  std::string circuit;
  double tolerance = 0;
};

std::vector<GoldenCase> manifest() {
  std::vector<GoldenCase> out;
  std::istringstream in(read_file(source_path("tests/golden/manifest.tsv")));
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    GoldenCase c;
    fields >> c.circuit >> c.tolerance;
    out.push_back(c);
  }
  return out;
}

class GoldenWaveform : public ::testing::TestWithParam<GoldenCase> {};

TEST_P(GoldenWaveform, EveryProbeWithinTolerance) {
  const GoldenCase& c = GetParam();
  Netlist netlist = parse_netlist_file(source_path("circuits/" + c.circuit + ".cir").string());
  ModelOptions mo;
  mo.t1 = netlist.tran->tstop;
  CircuitModel model = CircuitModel::build(netlist, mo);
  TransientOptions o;
  o.method = "euler";
  o.step = netlist.tran->tstep;
  o.tstop = netlist.tran->tstop;
  o.uic = netlist.tran->uic;
  MemorySink sink;
  run_transient(model, model.output_map(netlist.probes.empty() ? model.default_probes() : netlist.probes), o, sink);

  Csv ref = parse_csv(read_file(source_path("tests/golden/" + c.circuit + ".csv")));
  ASSERT_EQ(ref.header.size(), sink.names.size() + 1);
  ASSERT_EQ(ref.rows.size(), sink.times.size());
  for (size_t p = 0; p < sink.names.size(); ++p) {
    ASSERT_EQ(ref.header[p + 1], sink.names[p]);
    double lo = INFINITY, hi = -INFINITY, worst = 0, worst_t = 0;
    for (size_t k = 0; k < ref.rows.size(); ++k) {
      ASSERT_NEAR(ref.rows[k][0], sink.times[k], 1e-9 * o.tstop);
      const double y_ref = ref.rows[k][p + 1];
      lo = std::min(lo, y_ref);
      hi = std::max(hi, y_ref);
      const double e = std::abs(sink.rows[k](p) - y_ref);
      if (e > worst) worst = e, worst_t = sink.times[k];
    }
    const double range = hi - lo > 0 ? hi - lo : 1.0;
    EXPECT_LE(worst / range, c.tolerance)
        << c.circuit << " " << sink.names[p] << ": max error " << worst << " at t = " << worst_t
        << " over range " << range;
    std::printf("  %-22s %-10s max|err|/range = %.3e (tolerance %.1e)\n", c.circuit.c_str(),
                sink.names[p].c_str(), worst / range, c.tolerance);
  }
}

INSTANTIATE_TEST_SUITE_P(Circuits, GoldenWaveform, ::testing::ValuesIn(manifest()),
                         [](const ::testing::TestParamInfo<GoldenCase>& info) {
                           return info.param.circuit;
                         });

}  // namespace
}  // namespace lcs
