#include "solver/devices/capacitor.h"

#include "solver/devices/two_terminal_cards.h"

namespace lcs {

std::vector<BranchDecl> Capacitor::branches() const {
  return {{name(), BranchClass::Capacitor, element_.nodes.at(0), element_.nodes.at(1)}};
}

void Capacitor::stamp(const StampContext& context, Stamps& stamps) const {
  stamps.storage.push_back({context.branch(0), element_.value, element_.ic});
}

NgspiceCards Capacitor::ngspice(const NgspiceDeckContext& context) const {
  std::string value = number(element_.value);
  if (context.initial_value) value += " IC=" + number(*context.initial_value);
  else if (element_.ic) value += " IC=" + number(*element_.ic);
  return two_terminal_cards(deck_name('c', name()), element_.nodes.at(0), element_.nodes.at(1),
                            value, name(), context);
}

}  // namespace lcs
