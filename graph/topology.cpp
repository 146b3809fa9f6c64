#include "graph/topology.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <limits>
#include <queue>

#include "graph/components.h"

namespace lcs {

std::string join_names(const std::vector<std::string>& names) {
  std::string out;
  for (size_t k = 0; k < names.size(); ++k) {
    if (k > 0) out += k + 1 == names.size() ? " and " : ", ";
    out += names[k];
  }
  return out;
}

std::string TopologyError::formatted(const Netlist& netlist) const {
  SourceLocation file_only;
  file_only.file = netlist.file;
  std::string out = format_diagnostic(file_only, "error", message_);
  for (int e : elements_) {
    if (e < 0 || e >= static_cast<int>(netlist.elements.size())) continue;
    const Element& el = netlist.elements[e];
    out += "\n" + format_diagnostic(el.loc, "note", std::string(element_kind_name(el.kind)) + " " +
                                                        el.name + " is here");
  }
  return out;
}

namespace {

std::vector<std::string> names_of(const Netlist& netlist, const std::vector<int>& elements) {
  std::vector<std::string> names;
  for (int e : elements) names.push_back(netlist.elements[e].name);
  return names;
}

}  // namespace

void check_connected(const Netlist& netlist, const CircuitGraph& graph) {
  NodePartition all = components(graph, [](const Branch&) { return true; });
  if (all.count <= 1) return;
  std::vector<std::string> nodes;
  std::vector<int> elements;
  for (int n = 1; n < static_cast<int>(graph.nodes.size()); ++n)
    if (!all.same(n, 0)) nodes.push_back("'" + graph.nodes[n] + "'");
  for (const Branch& b : graph.branches)
    if (!all.same(b.from, 0)) elements.push_back(b.element);
  std::string what = nodes.size() == 1 ? "node " + nodes[0] + " has" : "nodes " + join_names(nodes) + " have";
  throw TopologyError(what + " no path to ground (floating: " +
                          join_names(names_of(netlist, elements)) + ")",
                      elements);
}

void check_source_loops_and_cutsets(const Netlist& netlist, const CircuitGraph& graph,
                                    const SpanningTree& tree) {
  // A V link: by the cycle property its fundamental loop holds only voltage sources.
  for (size_t j = 0; j < tree.links.size(); ++j) {
    const Branch& link = graph.branches[tree.links[j]];
    if (link.cls != BranchClass::VoltageSource) continue;
    std::vector<int> elements;
    for (const LoopTerm& t : fundamental_loop(graph, tree, tree.links[j])) elements.push_back(graph.branches[t.branch].element);
    throw TopologyError("voltage sources form a loop: " + join_names(names_of(netlist, elements)) +
                            " (KVL cannot hold for arbitrary source values)",
                        elements);
  }
  // An I tree branch: its fundamental cutset holds only current sources.
  for (size_t i = 0; i < tree.tree.size(); ++i) {
    const Branch& tb = graph.branches[tree.tree[i]];
    if (tb.cls != BranchClass::CurrentSource) continue;
    std::vector<int> elements{tb.element};
    for (const LoopTerm& l : fundamental_cutset(graph, tree, tree.tree[i])) elements.push_back(graph.branches[l.branch].element);
    throw TopologyError("current sources form a cutset: " + join_names(names_of(netlist, elements)) +
                            " (KCL cannot hold for arbitrary source values)",
                        elements);
  }
}

void check_ideal_diode_loops(const Netlist& netlist, const CircuitGraph& graph,
                             const std::vector<IdealDiodeLaw>& law, double t0, double t1) {
  const int n_nodes = static_cast<int>(graph.nodes.size());
  auto ideal = [&](int b) {
    return graph.branches[b].cls == BranchClass::Diode && law[b].ron == 0.0;
  };
  // Arcs along which current can flow with no impedance: ideal diodes anode -> cathode (cost:
  // their threshold VON), voltage sources both ways (cost 0).
  struct Arc { int branch, next; double cost; };
  std::vector<std::vector<Arc>> arcs(n_nodes);
  for (int b = 0; b < static_cast<int>(graph.branches.size()); ++b) {
    const Branch& br = graph.branches[b];
    if (ideal(b)) {
      arcs[br.from].push_back({b, br.to, law[b].von});
    } else if (br.cls == BranchClass::VoltageSource) {
      arcs[br.from].push_back({b, br.to, 0.0});
      arcs[br.to].push_back({b, br.from, 0.0});
    }
  }
  for (int d = 0; d < static_cast<int>(graph.branches.size()); ++d) {
    if (!ideal(d)) continue;
    const Branch& diode = graph.branches[d];
    // Cheapest path (least total VON) from the cathode back to the anode, without d itself.
    std::vector<double> dist(n_nodes, std::numeric_limits<double>::infinity());
    std::vector<int> via(n_nodes, -1), prev(n_nodes, -1);
    using Item = std::pair<double, int>;
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
    dist[diode.to] = 0;
    queue.push({0.0, diode.to});
    while (!queue.empty()) {
      auto [du, u] = queue.top();
      queue.pop();
      if (du > dist[u]) continue;
      for (const Arc& a : arcs[u]) {
        if (a.branch == d || du + a.cost >= dist[a.next]) continue;
        dist[a.next] = du + a.cost;
        via[a.next] = a.branch;
        prev[a.next] = u;
        queue.push({dist[a.next], a.next});
      }
    }
    if (via[diode.from] < 0) continue;

    std::vector<int> elements{diode.element};
    std::vector<std::string> sources;
    // Largest forward push of the sources around the loop, against the loop's thresholds.
    double push_max = 0.0;
    for (int v = diode.from; v != diode.to; v = prev[v]) {
      const Branch& br = graph.branches[via[v]];
      elements.push_back(br.element);
      if (br.cls != BranchClass::VoltageSource) continue;
      sources.push_back(br.name);
      // Stepping prev[v] -> v over a source raises the potential by +u when v is its n+.
      // A controlled source (E, H) can take any value: the loop is taken as able to conduct.
      const Element& source = netlist.elements[br.element];
      constexpr double kAny = std::numeric_limits<double>::infinity();
      auto [lo, hi] = source.kind == ElementKind::VoltageSource ? source.waveform.range(t0, t1)
                                                                : std::pair<double, double>{-kAny, kAny};
      push_max += br.from == v ? hi : -lo;
    }
    const double thresholds = law[d].von + dist[diode.from];
    if (push_max < thresholds) continue;  // the loop stays blocked: no loop current can flow
    const std::string loop = join_names(names_of(netlist, elements));
    if (elements.size() > sources.size() + 1) {
      throw TopologyError(
          "ideal diodes form a loop with no impedance that can conduct: " + loop +
              " (assumption 5.40, Figure 5.4: the loop current is undefined; give a diode "
              "RON > 0 or add a resistance to the loop)",
          elements);
    }
    throw TopologyError("diode " + diode.name + " is forward-biased directly by voltage source" +
                            (sources.size() > 1 ? "s " : " ") + join_names(sources) +
                            " with no impedance in the loop (" + loop +
                            "): an ideal diode has no solution there (Figure 5.5); give it "
                            "RON > 0 or add a series resistance",
                        elements);
  }
  check_balanced_ideal_diode_loops(netlist, graph, law);
}

// Ideal (RON = 0) diodes in parallel, same direction, same VON: while they conduct they are at
// the same threshold, so any split of their total current satisfies every law and the currents
// are not unique (assumption 5.40 fails as it does for a conducting loop). With different VONs
// the lower one takes it all, which is unique. Larger balanced loops (a diode parallel to two in
// series) are not searched: the rest of the circuit usually allows balance only at instants
// (a bridge at a zero crossing), and telling those apart needs the whole LCS.
void check_balanced_ideal_diode_loops(const Netlist& netlist, const CircuitGraph& graph,
                                      const std::vector<IdealDiodeLaw>& law) {
  std::map<std::pair<int, int>, std::vector<int>> between;  // (anode, cathode) -> RON = 0 diodes
  for (int b = 0; b < static_cast<int>(graph.branches.size()); ++b) {
    const Branch& br = graph.branches[b];
    if (br.cls == BranchClass::Diode && law[b].ron == 0.0 && br.from != br.to)
      between[{br.from, br.to}].push_back(b);
  }
  for (const auto& [ends, diodes] : between) {
    for (size_t i = 0; i < diodes.size(); ++i) {
      std::vector<int> elements{graph.branches[diodes[i]].element};
      const double von = law[diodes[i]].von;
      for (size_t j = i + 1; j < diodes.size(); ++j)
        if (std::abs(law[diodes[j]].von - von) <= 1e-12 * std::max(std::abs(von), 1e-300))
          elements.push_back(graph.branches[diodes[j]].element);
      if (elements.size() < 2) continue;
      std::sort(elements.begin(), elements.end());
      throw TopologyError("ideal diodes " + join_names(names_of(netlist, elements)) +
                              " are in parallel with the same VON and RON = 0: when they conduct, "
                              "the current divides between them in no defined ratio (assumption "
                              "5.40); give them RON > 0, or use one diode",
                          elements);
    }
  }
}

}  // namespace lcs
