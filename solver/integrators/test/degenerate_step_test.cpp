// Step LCPs that are degenerate but solvable (issue 9, defect 3): a node reached only through
// two diodes pointing into it. KCL makes both currents zero at every instant; the step LCP's q
// carries a rounding-level negative where KCL says 0, which left it infeasible as given and
// ended Lemke on a ray (exit 3) for euler, theta and radau3, and `op` too when the sources
// start at 0 (solver/model/structural_zeros.h restores the exact zero; solver/lcp/lemke.cpp
// retries a ray on q shifted by a rounding allowance).
#include <cmath>

#include <gtest/gtest.h>

#include "solver/integrators/method_registry.h"
#include "solver/integrators/transient.h"
#include "tests/support/netlist_builder.h"

namespace lcs {
namespace {

using testing::NetlistBuilder;

TEST(DegenerateStepLcp, ANodeFedOnlyThroughDiodesCarriesNoCurrentWithEveryIdealMethod) {
  NetlistBuilder b;
  b.tran(10e-6, 3e-3, false);
  b.v("v1", "a", "0", NetlistBuilder::sin(0, 5, 1e3)).v("v2", "b", "0", NetlistBuilder::sin(0, 3, 2e3));
  b.d("d1", "a", "x", 0.7, 9).d("d2", "b", "x", 0.7, 9);
  b.r("r1", "a", "c", 100).r("r2", "c", "0", 100).r("r3", "b", "c", 100);
  const Netlist netlist = b.build();
  ModelOptions mo;
  mo.t1 = 3e-3;
  const CircuitModel model = CircuitModel::build(netlist, mo);
  std::vector<Probe> probes;
  for (const char* p : {"i(d1)", "i(d2)", "v(c)"}) probes.push_back(parse_probe(p, {}));
  for (const MethodEntry& entry : method_registry()) {
    if (entry.smooth_model) continue;  // Shockley junctions leak IS: not zero
    TransientOptions o;
    o.method = entry.name;
    o.step = 10e-6;
    o.tstop = 3e-3;
    MemorySink sink;
    ASSERT_NO_THROW(run_transient(model, model.output_map(probes), o, sink)) << entry.name;
    ASSERT_GE(sink.times.size(), 301u) << entry.name;
    for (size_t k = 0; k < sink.times.size(); ++k) {
      const double t = sink.times[k];
      // Both diodes carry nothing, so v(c) is the resistive divider of the two sources.
      const double va = 5 * std::sin(2 * M_PI * 1e3 * t), vb = 3 * std::sin(2 * M_PI * 2e3 * t);
      ASSERT_EQ(sink.rows[k](0), 0.0) << entry.name << " t = " << t;
      ASSERT_EQ(sink.rows[k](1), 0.0) << entry.name << " t = " << t;
      ASSERT_NEAR(sink.rows[k](2), (va + vb) / 3, 1e-12) << entry.name << " t = " << t;
    }
  }
}

}  // namespace
}  // namespace lcs
