#include "solver/model/line_dc_loops.h"

#include <algorithm>
#include <map>
#include <queue>
#include <set>

namespace lcs {

namespace {

// Edges that fix a voltage difference at DC: voltage sources, and a through line's two
// conductors (p1+ to p2+, p1- to p2-: the loop of a through connection carries no voltage).
struct Edge {
  std::string a, b;
  int element;
};

// The elements on a path from `from` to `to` over `edges` (BFS), empty when none.
std::vector<int> path(const std::vector<Edge>& edges, const std::string& from, const std::string& to) {
  std::map<std::string, std::vector<int>> at;
  for (int e = 0; e < static_cast<int>(edges.size()); ++e) {
    at[edges[e].a].push_back(e);
    at[edges[e].b].push_back(e);
  }
  std::map<std::string, int> via;  // node -> edge that reached it
  std::queue<std::string> q;
  q.push(from);
  via[from] = -1;
  while (!q.empty()) {
    const std::string n = q.front();
    q.pop();
    if (n == to) break;
    for (int e : at[n]) {
      const std::string& m = edges[e].a == n ? edges[e].b : edges[e].a;
      if (via.count(m)) continue;
      via[m] = e;
      q.push(m);
    }
  }
  std::vector<int> out;
  if (!via.count(to)) return out;
  for (std::string n = to; via[n] >= 0;) {
    const Edge& e = edges[via[n]];
    out.push_back(e.element);
    n = e.a == n ? e.b : e.a;
  }
  return out;
}

bool through_at_dc(const Netlist& netlist, const Element& e) {
  if (e.kind == ElementKind::Line) return true;
  if (e.kind != ElementKind::LossyLine) return false;
  const auto it = netlist.line_models.find(e.model);
  return it != netlist.line_models.end() && it->second.r == 0;
}

}  // namespace

void check_line_dc_loops(const Netlist& netlist) {
  std::vector<Edge> edges;
  for (int k = 0; k < static_cast<int>(netlist.elements.size()); ++k)
    if (netlist.elements[k].kind == ElementKind::VoltageSource)
      edges.push_back({netlist.elements[k].nodes[0], netlist.elements[k].nodes[1], k});
  for (int k = 0; k < static_cast<int>(netlist.elements.size()); ++k) {
    const Element& e = netlist.elements[k];
    if (!through_at_dc(netlist, e)) continue;
    if (e.nodes[0] == e.nodes[2] && e.nodes[1] == e.nodes[3])
      throw TopologyError("the two ports of line " + e.name + " are on the same nodes: at DC it is a through "
                          "connection looped onto itself, and the current circulating in it is not determined "
                          "(start from rest with UIC)",
                          {k});
    for (int c = 0; c < 2; ++c) {
      const std::string& a = e.nodes[c], &b = e.nodes[2 + c];
      if (a != b) {
        std::vector<int> loop = path(edges, a, b);
        if (!loop.empty()) {
          loop.insert(loop.begin(), k);
          std::vector<std::string> names;
          for (int el : loop)
            if (std::find(names.begin(), names.end(), netlist.elements[el].name) == names.end())
              names.push_back(netlist.elements[el].name);
          std::set<int> unique(loop.begin(), loop.end());
          throw TopologyError("at DC the line " + e.name + " is a through connection and closes a loop with no "
                              "resistance: " + join_names(names) + " (no operating point, or a current it "
                              "cannot determine; put resistance in the loop, or start from rest with UIC)",
                              std::vector<int>(unique.begin(), unique.end()));
        }
      }
      edges.push_back({a, b, k});
    }
  }
}

}  // namespace lcs
