#include "solver/model/inductance_check.h"

#include <algorithm>
#include <cstdio>
#include <map>
#include <numeric>

#include <Eigen/Dense>

#include "graph/topology.h"

namespace lcs {

namespace {

int find_root(std::vector<int>& parent, int i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

}  // namespace

void check_inductance_matrices(const Netlist& netlist) {
  std::map<std::string, int> inductor;  // name -> element index
  std::vector<int> couplings;
  for (int i = 0; i < static_cast<int>(netlist.elements.size()); ++i) {
    const Element& e = netlist.elements[i];
    if (e.kind == ElementKind::Inductor) inductor[e.name] = i;
    if (e.kind == ElementKind::Coupling) couplings.push_back(i);
  }
  if (couplings.size() < 2) return;  // one coupling with |k| <= 1 is always possible
  std::vector<int> parent(netlist.elements.size());
  std::iota(parent.begin(), parent.end(), 0);
  auto ends = [&](int k) {
    const Element& e = netlist.elements[k];
    auto a = inductor.find(e.coupled.at(0)), b = inductor.find(e.coupled.at(1));
    return std::pair<int, int>{a == inductor.end() ? -1 : a->second, b == inductor.end() ? -1 : b->second};
  };
  for (int k : couplings) {
    auto [a, b] = ends(k);
    if (a >= 0 && b >= 0) parent[find_root(parent, a)] = find_root(parent, b);
  }
  std::map<int, std::vector<int>> groups;  // root -> inductors, in card order
  for (const auto& [name, i] : inductor) groups[find_root(parent, i)].push_back(i);
  for (auto& [root, members] : groups) {
    if (members.size() < 3) continue;
    std::sort(members.begin(), members.end());
    std::map<int, int> position;
    for (int j = 0; j < static_cast<int>(members.size()); ++j) position[members[j]] = j;
    Eigen::MatrixXd K = Eigen::MatrixXd::Identity(members.size(), members.size());
    std::vector<int> involved;
    for (int k : couplings) {
      auto [a, b] = ends(k);
      if (a < 0 || b < 0 || !position.count(a)) continue;
      K(position[a], position[b]) = K(position[b], position[a]) = netlist.elements[k].value;
      involved.push_back(k);
    }
    const double smallest = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(K, Eigen::EigenvaluesOnly).eigenvalues()(0);
    if (smallest >= -kIndefiniteTolerance) continue;
    std::string names;
    for (int k : involved) names += (names.empty() ? "" : ", ") + netlist.elements[k].name;
    std::string windings;
    for (int i : members) windings += (windings.empty() ? "" : ", ") + netlist.elements[i].name;
    char eig[32];
    std::snprintf(eig, sizeof eig, "%.3g", smallest);
    involved.insert(involved.end(), members.begin(), members.end());
    throw TopologyError("the couplings " + names + " give the inductors " + windings +
                            " an inductance matrix that is not positive semidefinite (smallest "
                            "eigenvalue of its coupling-coefficient matrix: " + eig +
                            "): some currents would store negative energy; no real windings "
                            "have these coefficients",
                        involved);
  }
}

}  // namespace lcs
