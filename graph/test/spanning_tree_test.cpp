#include "graph/spanning_tree.h"

#include <random>

#include <gtest/gtest.h>

#include "graph/diode_classes.h"
#include "solver/devices/device_registry.h"
#include "tests/support/netlist_builder.h"
#include "tests/support/random_graph_circuit.h"

namespace lcs {
namespace {

using testing::NetlistBuilder;
using testing::random_graph_circuit;

// The graph of a netlist's devices (the graph stays two-terminal; devices say their branches).
CircuitGraph graph_of(const Netlist& netlist) { return graph_of_devices(make_devices(netlist, {})); }

TEST(SpanningTree, LoopsSatisfyKvlCutsetsSatisfyKclAndNodePathsGivePotentials) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> potential(-5, 5);
  for (int trial = 0; trial < 300; ++trial) {
    Netlist net = random_graph_circuit(rng, 2 + trial % 9, trial % 13);
    CircuitGraph g = graph_of(net);
    SpanningTree t = build_normal_tree(g);
    ASSERT_EQ(t.tree.size(), g.nodes.size() - 1);
    ASSERT_EQ(t.tree.size() + t.links.size(), g.branches.size());
    std::vector<double> phi(g.nodes.size());
    for (size_t n = 1; n < phi.size(); ++n) phi[n] = potential(rng);
    auto v = [&](int b) { return phi[g.branches[b].from] - phi[g.branches[b].to]; };
    for (size_t j = 0; j < t.links.size(); ++j) {
      double kvl = 0;
      for (const LoopTerm& term : fundamental_loop(g, t, t.links[j])) {
        kvl += term.sign * v(term.branch);
        // Cycle property of the minimum spanning tree: the loop of a link holds no branch of
        // a heavier class (the model builder relies on it).
        EXPECT_LE(static_cast<int>(g.branches[term.branch].cls),
                  static_cast<int>(g.branches[t.links[j]].cls));
      }
      EXPECT_NEAR(kvl, 0.0, 1e-12);
    }
    // KCL through the fundamental cutsets: link currents drawn at random, every tree current
    // i_f = sum of b_{f,l} i_l; then every node's currents sum to zero.
    std::vector<double> current(g.branches.size(), 0.0);
    for (int l : t.links) current[l] = potential(rng);
    for (int f : t.tree)
      for (const LoopTerm& l : fundamental_cutset(g, t, f)) current[f] += l.sign * current[l.branch];
    std::vector<double> leaving(g.nodes.size(), 0.0);
    for (size_t b = 0; b < g.branches.size(); ++b) {
      leaving[g.branches[b].from] += current[b];
      leaving[g.branches[b].to] -= current[b];
    }
    for (double sum : leaving) EXPECT_NEAR(sum, 0.0, 1e-12);
    for (size_t n = 0; n < g.nodes.size(); ++n) {
      double sum = 0;  // down the tree from ground: v(node) = v(parent) + sign * v_branch
      for (size_t c = n; c != 0; c = t.parent[c]) sum += t.to_parent[c].sign * v(t.to_parent[c].branch);
      EXPECT_NEAR(sum, phi[n], 1e-12);
    }
  }
}

TEST(SpanningTree, NormalTreePrefersSourcesThenCapacitors) {
  // A capacitor and a resistor in parallel across a source; an inductor to a second node that
  // also has a diode to ground: the tree is v1 (a), then the diode (b) rather than the inductor.
  NetlistBuilder b;
  b.v("v1", "a", "0", NetlistBuilder::dc(1)).r("r1", "a", "0", 1).c("c1", "a", "0", 1e-6);
  b.l("l1", "a", "b", 1e-3).d("d1", "b", "0");
  CircuitGraph g = graph_of(b.build());
  SpanningTree t = build_normal_tree(g);
  std::vector<std::string> tree;
  for (int br : t.tree) tree.push_back(g.branches[br].name);
  EXPECT_EQ(tree, (std::vector<std::string>{"v1", "d1"}));
}

TEST(DiodeClasses, CapacitorResistorAndInductorDiodes) {
  NetlistBuilder b;
  b.v("v1", "a", "0", NetlistBuilder::dc(1));
  b.c("c1", "a", "x", 1e-6).d("dc", "x", "a");     // C-only path between x and a
  b.r("r1", "a", "y", 1).d("dr", "y", "a");        // resistor path
  b.l("l1", "a", "z", 1e-3).d("dl", "z", "a");     // only through the inductor
  b.d("dq", "a", "q").r("rq", "q", "w", 1).c("cq", "w", "q", 1e-6);  // q, w: only via dq
  std::vector<DiodeClass> classes = classify_diodes(graph_of(b.build()));
  ASSERT_EQ(classes.size(), 4u);
  EXPECT_EQ(classes[0].cls, 'C');
  EXPECT_EQ(classes[1].cls, 'R');
  EXPECT_EQ(classes[2].cls, 'L');
  EXPECT_EQ(classes[3].cls, 'L');
  EXPECT_FALSE(classes[0].joins_h_components);
  EXPECT_TRUE(classes[3].joins_h_components);
}

}  // namespace
}  // namespace lcs
