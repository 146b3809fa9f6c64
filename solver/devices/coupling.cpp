#include "solver/devices/coupling.h"

namespace lcs {

void Coupling::stamp(const StampContext& context, Stamps& stamps) const {
  int inductor[2] = {-1, -1};
  const CircuitGraph& g = context.graph;
  for (int b = 0; b < static_cast<int>(g.branches.size()); ++b)
    for (int k = 0; k < 2; ++k)
      if (g.branches[b].cls == BranchClass::Inductor && g.branches[b].name == element_.coupled.at(k))
        inductor[k] = b;
  if (inductor[0] < 0 || inductor[1] < 0)
    throw NetlistError(element_.loc, "coupling " + name() + " needs two inductors");
  stamps.couplings.push_back({inductor[0], inductor[1], element_.value});
}

NgspiceCards Coupling::ngspice(const NgspiceDeckContext&) const {
  NgspiceCards cards;
  cards.lines.push_back(deck_name('k', name()) + " " + deck_name('l', element_.coupled.at(0)) + " " +
                        deck_name('l', element_.coupled.at(1)) + " " + number(element_.value));
  return cards;
}

}  // namespace lcs
