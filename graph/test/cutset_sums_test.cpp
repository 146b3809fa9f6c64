#include "graph/cutset_sums.h"

#include <random>

#include <gtest/gtest.h>

#include "solver/devices/device_registry.h"
#include "tests/support/netlist_builder.h"
#include "tests/support/random_graph_circuit.h"

namespace lcs {
namespace {

using testing::NetlistBuilder;
using testing::random_graph_circuit;


// The cutset of a tree branch by its definition: the links whose fundamental loops pass through
// it, with the sign the loop gives it.
std::vector<LoopTerm> cutset_from_loops(const CircuitGraph& g, const SpanningTree& t, int f) {
  std::vector<LoopTerm> cutset;
  for (int l : t.links) {
    const std::vector<LoopTerm> loop = fundamental_loop(g, t, l);
    for (size_t k = 1; k < loop.size(); ++k)
      if (loop[k].branch == f) cutset.push_back({l, loop[k].sign});
  }
  return cutset;
}

TEST(FundamentalCutset, IsTheLinksWhoseLoopsPassThroughTheBranchWithTheirSigns) {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 300; ++trial) {
    const CircuitGraph g = graph_of_devices(make_devices(random_graph_circuit(rng, 2 + trial % 17, trial % 23), {}));
    const SpanningTree t = build_normal_tree(g);
    for (int f : t.tree) {
      const std::vector<LoopTerm> expected = cutset_from_loops(g, t, f), got = fundamental_cutset(g, t, f);
      ASSERT_EQ(got.size(), expected.size()) << "trial " << trial << ", branch " << g.branches[f].name;
      for (size_t k = 0; k < got.size(); ++k) {
        EXPECT_EQ(got[k].branch, expected[k].branch);
        EXPECT_EQ(got[k].sign, expected[k].sign);
      }
    }
  }
}

TEST(CutsetSums, EqualTheWeightsSummedOverEachCutset) {
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> weight(-3, 7);
  for (int trial = 0; trial < 300; ++trial) {
    const CircuitGraph g = graph_of_devices(make_devices(random_graph_circuit(rng, 2 + trial % 29, trial % 31), {}));
    const SpanningTree t = build_normal_tree(g);
    std::vector<double> w(g.branches.size());
    for (double& x : w) x = weight(rng);
    const std::vector<double> sums = CutsetSums(g, t).sums(w);
    ASSERT_EQ(sums.size(), g.branches.size());
    for (int b = 0; b < static_cast<int>(g.branches.size()); ++b) {
      double expected = 0;
      if (t.in_tree[b])
        for (const LoopTerm& l : cutset_from_loops(g, t, b)) expected += w[l.branch];
      EXPECT_EQ(sums[b], expected) << "trial " << trial << ", branch " << g.branches[b].name;
    }
  }
}

// A chain (a multiplier's tree is one): every link from the far end to ground crosses every
// tree branch, and the sums see depth, not just neighbours.
TEST(CutsetSums, CountTheLinksAcrossEveryBranchOfAChain) {
  NetlistBuilder b;
  const int n = 40;
  for (int k = 1; k <= n; ++k) b.c("c" + std::to_string(k), std::to_string(k - 1), std::to_string(k), 1e-6);
  for (int k = 1; k <= n; ++k) b.r("r" + std::to_string(k), std::to_string(k), "0", 1e3);
  const CircuitGraph g = graph_of_devices(make_devices(b.build(), {}));
  const SpanningTree t = build_normal_tree(g);
  const std::vector<double> sums = CutsetSums(g, t).sums(std::vector<double>(g.branches.size(), 1.0));
  // The branch from node k-1 to node k carries the resistors of nodes k ... n.
  for (int k = 1; k <= n; ++k) EXPECT_EQ(sums[k - 1], n - k + 1) << "c" << k;
}

}  // namespace
}  // namespace lcs
