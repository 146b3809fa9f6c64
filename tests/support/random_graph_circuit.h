// Random connected circuits of every branch class (V, C, R, D, L, I): a random tree of branches
// (each node joined to an earlier one), then `extra` branches between random nodes. For the
// graph's tests: the loops, cutsets and maps of every kind of normal tree.
#pragma once

#include <random>
#include <string>

#include "tests/support/netlist_builder.h"

namespace lcs::testing {

inline Netlist random_graph_circuit(std::mt19937& rng, int nodes, int extra) {
  NetlistBuilder b;
  std::uniform_int_distribution<int> kind(0, 5), node(0, nodes - 1);
  auto name = [](int k) { return std::to_string(k); };
  auto add = [&](int id, int a, int c) {
    const std::string na = name(a), nc = name(c);
    switch (kind(rng)) {
      case 0: b.v("v" + name(id), na, nc, NetlistBuilder::dc(1)); break;
      case 1: b.c("c" + name(id), na, nc, 1e-6); break;
      case 2: b.r("r" + name(id), na, nc, 1e3); break;
      case 3: b.d("d" + name(id), na, nc, 0.5, 1); break;
      case 4: b.l("l" + name(id), na, nc, 1e-3); break;
      default: b.i("i" + name(id), na, nc, NetlistBuilder::dc(1)); break;
    }
  };
  int id = 0;
  for (int n = 1; n < nodes; ++n) {
    std::uniform_int_distribution<int> earlier(0, n - 1);
    add(id++, earlier(rng), n);
  }
  for (int k = 0; k < extra; ++k) {
    int a = node(rng), c = node(rng);
    if (a == c) c = (c + 1) % nodes;
    add(id++, a, c);
  }
  return b.build();
}

}  // namespace lcs::testing
