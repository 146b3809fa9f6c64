#include "solver/model/primary_maps.h"

#include <random>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "solver/devices/device_registry.h"
#include "tests/support/random_graph_circuit.h"

namespace lcs {
namespace {

using Row = std::vector<std::pair<int, double>>;

Row row_of(const PrimaryMaps& maps, bool voltage, int b) {
  Row row;
  maps.visit_row(voltage, b, [&](int column, double value) { row.emplace_back(column, value); });
  return row;
}

// The rows read from the tree are the materialised maps' rows, entry for entry and in the same
// order (formation sums them into its equations either way: the same order gives the same
// rounding), and they hold KVL and KCL: v = Vmap p and i = Imap p satisfy both for any p.
TEST(PrimaryMaps, RowsReadFromTheTreeAreTheMaterialisedRows) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> value(-5, 5);
  for (int trial = 0; trial < 200; ++trial) {
    const CircuitGraph g = graph_of_devices(make_devices(testing::random_graph_circuit(rng, 2 + trial % 19, trial % 27), {}));
    const SpanningTree t = build_normal_tree(g);
    PrimaryMaps from_tree(g, t), formed(g, t);
    formed.materialise();
    ASSERT_FALSE(from_tree.materialised());
    const int nb = static_cast<int>(g.branches.size());
    for (int b = 0; b < nb; ++b)
      for (bool voltage : {true, false}) {
        const Row got = row_of(from_tree, voltage, b), expected = row_of(formed, voltage, b);
        ASSERT_EQ(got, expected) << "trial " << trial << ", " << (voltage ? "Vmap" : "Imap") << " row of "
                                 << g.branches[b].name;
      }
    std::vector<double> p(nb), v(nb, 0.0), i(nb, 0.0);
    for (double& x : p) x = value(rng);
    for (int b = 0; b < nb; ++b) {
      for (const auto& [column, coeff] : row_of(from_tree, true, b)) v[b] += coeff * p[column];
      for (const auto& [column, coeff] : row_of(from_tree, false, b)) i[b] += coeff * p[column];
    }
    std::vector<double> leaving(g.nodes.size(), 0.0);
    for (int b = 0; b < nb; ++b) {
      leaving[g.branches[b].from] += i[b];
      leaving[g.branches[b].to] -= i[b];
    }
    for (double sum : leaving) EXPECT_NEAR(sum, 0.0, 1e-12) << "KCL, trial " << trial;
    for (int l : t.links) {
      double around = 0;
      for (const LoopTerm& term : fundamental_loop(g, t, l)) around += term.sign * v[term.branch];
      EXPECT_NEAR(around, 0.0, 1e-12) << "KVL, trial " << trial;
    }
  }
}

}  // namespace
}  // namespace lcs
