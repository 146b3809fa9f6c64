#include "solver/integrators/multistability.h"

#include <algorithm>
#include <cstdio>

#include "graph/topology.h"
#include "solver/model/numerical_failure.h"

namespace lcs {

std::string pair_owners(const LcsProblem& model, const std::vector<int>& pairs) {
  std::vector<std::string> owners;
  bool transistors = true;
  for (int i : pairs) {
    const std::string& name = model.pairs().at(i).name;
    const std::size_t colon = name.find(':');
    if (colon == std::string::npos) transistors = false;
    const std::string owner = name.substr(0, colon);
    if (std::find(owners.begin(), owners.end(), owner) == owners.end()) owners.push_back(owner);
  }
  return (owners.size() == 1 ? (transistors ? "transistor " : "element ")
                              : (transistors ? "transistors " : "elements ")) +
         join_names(owners);
}

void MultistabilityNotes::check(const LcpWarmSolver& lcp, const LcsProblem& model, double t, int blocks) {
  using M = LcpWarmSolver::Multiplicity;
  if (lcp.multiplicity() != M::SeveralKeptContinuous && lcp.multiplicity() != M::SeveralNoneContinuous &&
      lcp.multiplicity() != M::SeveralTookStable && lcp.multiplicity() != M::SeveralTookLemke)
    return;
  const int m = model.pair_count();
  std::vector<int> pairs;
  for (int i : lcp.differ())
    if (std::find(pairs.begin(), pairs.end(), i % m) == pairs.end()) pairs.push_back(i % m);
  std::sort(pairs.begin(), pairs.end());
  const std::string who = pair_owners(model, pairs);
  const std::string count = std::to_string(lcp.solutions()) + " solutions";
  if (lcp.multiplicity() == M::SeveralNoneContinuous)
    throw NumericalFailure(t, "the step's complementarity problem has " + count + " (" + who +
                                  " on in some, off in others), no previous state to continue "
                                  "and more than one is stable: the circuit's state is not "
                                  "determined (choose it with .ic or .nodeset values)");
  if (said_) return;
  said_ = true;
  char at[48];
  std::snprintf(at, sizeof at, "%.9g s", t);
  notes_.push_back(std::string("at t = ") + at + " the step's complementarity problem has " + count +
                   " (" + who + " on in some, off in others): the run keeps the one continuous "
                   "with the previous state, as the circuit's hysteresis does, and where that "
                   "state ends the one Lemke's method reaches (a regenerative switching)");
}

}  // namespace lcs
