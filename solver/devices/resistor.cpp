#include "solver/devices/resistor.h"

#include "solver/devices/two_terminal_cards.h"

namespace lcs {

std::vector<BranchDecl> Resistor::branches() const {
  return {{name(), BranchClass::Resistor, element_.nodes.at(0), element_.nodes.at(1)}};
}

void Resistor::stamp(const StampContext& context, Stamps& stamps) const {
  const int b = context.branch(0);
  stamps.relations.push_back({b, {{Term::Of::Voltage, b, 1.0}, {Term::Of::Current, b, -element_.value}}});
}

NgspiceCards Resistor::ngspice(const NgspiceDeckContext& context) const {
  return two_terminal_cards(deck_name('r', name()), element_.nodes.at(0), element_.nodes.at(1),
                            number(element_.value), name(), context);
}

}  // namespace lcs
