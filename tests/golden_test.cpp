// Golden waveforms: every circuit in tests/golden/manifest.tsv runs with implicit Euler at its
// .tran TSTEP and every probe is compared with tests/golden/<circuit>.csv, a reference computed
// at TSTEP/64 and checked against TSTEP/32 (tests/golden/generate.sh). Every probe has two
// stated tolerances in the manifest, relative to the probe's range over the run:
//   max  = max |y(t) - y_ref(t)| away from steep edges: samples within 2 steps of a reference
//          step that moves more than 5 % of the range are left out, because a first-order
//          method places a switching instant within O(h) and a shifted edge costs its full
//          height at one sample, however small h is;
//   mean = mean |y(t) - y_ref(t)| over every sample, edges included (first order across jumps).
#include <cmath>

#include <gtest/gtest.h>

#include "netlist/netlist.h"
#include "solver/integrators/transient.h"
#include "tests/cli_support.h"

namespace lcs {
namespace {

using namespace cli_testing;

struct ProbeTolerance {
  std::string probe;
  double max = 0, mean = 0;
};

struct GoldenCase {
  std::string circuit;
  std::vector<ProbeTolerance> probes;
};

std::vector<GoldenCase> manifest() {
  std::vector<GoldenCase> out;
  std::istringstream in(read_file(source_path("tests/golden/manifest.tsv")));
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    std::string circuit;
    ProbeTolerance t;
    fields >> circuit >> t.probe >> t.max >> t.mean;
    if (out.empty() || out.back().circuit != circuit) out.push_back({circuit, {}});
    out.back().probes.push_back(t);
  }
  return out;
}

void PrintTo(const GoldenCase& c, std::ostream* os) { *os << c.circuit; }

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
  ASSERT_EQ(c.probes.size(), sink.names.size()) << "every probe needs a stated tolerance";
  for (size_t p = 0; p < sink.names.size(); ++p) {
    ASSERT_EQ(ref.header[p + 1], sink.names[p]);
    ASSERT_EQ(c.probes[p].probe, sink.names[p]);
    double lo = INFINITY, hi = -INFINITY, worst = 0, worst_t = 0, sum = 0;
    for (size_t k = 0; k < ref.rows.size(); ++k) {
      ASSERT_NEAR(ref.rows[k][0], sink.times[k], 1e-9 * o.tstop);
      lo = std::min(lo, ref.rows[k][p + 1]);
      hi = std::max(hi, ref.rows[k][p + 1]);
    }
    const double range = hi - lo > 0 ? hi - lo : 1.0;
    std::vector<bool> near_edge(ref.rows.size(), false);
    for (size_t k = 1; k < ref.rows.size(); ++k)
      if (std::abs(ref.rows[k][p + 1] - ref.rows[k - 1][p + 1]) > 0.05 * range)
        for (size_t j = k >= 3 ? k - 3 : 0; j <= k + 2 && j < ref.rows.size(); ++j) near_edge[j] = true;
    for (size_t k = 0; k < ref.rows.size(); ++k) {
      const double e = std::abs(sink.rows[k](p) - ref.rows[k][p + 1]);
      sum += e;
      if (!near_edge[k] && e > worst) worst = e, worst_t = sink.times[k];
    }
    const double max_rel = worst / range, mean_rel = sum / ref.rows.size() / range;
    EXPECT_LE(max_rel, c.probes[p].max) << c.circuit << " " << sink.names[p]
                                        << ": max error away from edges " << worst << " at t = "
                                        << worst_t << ", range " << range;
    EXPECT_LE(mean_rel, c.probes[p].mean) << c.circuit << " " << sink.names[p];
    std::printf("golden\t%s\t%s\t%.3e\t%.3e\n", c.circuit.c_str(), sink.names[p].c_str(),
                max_rel, mean_rel);
  }
}

INSTANTIATE_TEST_SUITE_P(Circuits, GoldenWaveform, ::testing::ValuesIn(manifest()),
                         [](const ::testing::TestParamInfo<GoldenCase>& info) {
                           return info.param.circuit;
                         });

}  // namespace
}  // namespace lcs
