#include "solver/devices/controlled_source.h"

#include "solver/devices/two_terminal_cards.h"

#include <cstdio>

namespace lcs {

ControlledSource::ControlledSource(const Element& element, const Netlist& netlist, const DeviceOptions&)
    : Device(element) {
  if (voltage_control()) return;
  for (size_t e = 0; e < netlist.elements.size(); ++e)
    if (netlist.elements[e].name == element.control && netlist.elements[e].kind == ElementKind::VoltageSource)
      control_element_ = static_cast<int>(e);
  if (control_element_ < 0)
    throw NetlistError(element.loc, "'" + element.name + "': controlling voltage source '" + element.control + "'" +
                                        " is not defined");
}

bool ControlledSource::voltage_output() const {
  return element_.kind == ElementKind::Vcvs || element_.kind == ElementKind::Ccvs;
}

bool ControlledSource::voltage_control() const {
  return element_.kind == ElementKind::Vcvs || element_.kind == ElementKind::Vccs;
}

bool ControlledSource::senses() const { return voltage_control() && element_.nodes.at(2) != element_.nodes.at(3); }

char ControlledSource::letter() const {
  switch (element_.kind) {
    case ElementKind::Vcvs: return 'e';
    case ElementKind::Vccs: return 'g';
    case ElementKind::Cccs: return 'f';
    default: return 'h';
  }
}

std::vector<BranchDecl> ControlledSource::branches() const {
  std::vector<BranchDecl> out{{name(), voltage_output() ? BranchClass::VoltageSource : BranchClass::CurrentSource,
                               element_.nodes.at(0), element_.nodes.at(1)}};
  if (senses()) out.push_back({name() + "#sense", BranchClass::CurrentSource, element_.nodes.at(2), element_.nodes.at(3)});
  return out;
}

void ControlledSource::stamp(const StampContext& context, Stamps& stamps) const {
  const int b = context.branch(0);
  std::vector<Term> terms{{voltage_output() ? Term::Of::Voltage : Term::Of::Current, b, 1.0}};
  if (senses()) {
    const int s = context.branch(1);
    stamps.relations.push_back({s, {{Term::Of::Current, s, 1.0}}});  // the sensing branch: i_S = 0
    terms.push_back({Term::Of::Voltage, s, -element_.value});
  } else if (!voltage_control()) {
    int v = -1;  // the controlling source's branch (a V source has exactly one)
    for (int k = 0; k < static_cast<int>(context.graph.branches.size()) && v < 0; ++k)
      if (context.graph.branches[k].element == control_element_) v = k;
    terms.push_back({Term::Of::Current, v, -element_.value});
  }
  stamps.relations.push_back({b, std::move(terms)});
}

// Written through as ngspice cards: the same letter, nodes and gain, the controlling source under
// the name it has in the deck.
NgspiceCards ControlledSource::ngspice(const NgspiceDeckContext& context) const {
  const std::string control = voltage_control() ? element_.nodes.at(2) + " " + element_.nodes.at(3)
                                                : deck_name('v', element_.control);
  return two_terminal_cards(deck_name(letter(), name()), element_.nodes.at(0), element_.nodes.at(1),
                            control + " " + number(element_.value), name(), context);
}

std::vector<std::string> ControlledSource::notes() const {
  char buf[256];
  const std::string control = voltage_control() ? "v(" + element_.nodes.at(2) + "," + element_.nodes.at(3) + ")"
                                                : "i(" + element_.control + ")";
  const char* law = letter() == 'e' ? "v = %.6g * %s" : letter() == 'g' ? "i = %.6g S * %s"
                  : letter() == 'f' ? "i = %.6g * %s" : "v = %.6g ohm * %s";
  char relation[160];
  std::snprintf(relation, sizeof relation, law, element_.value, control.c_str());
  std::snprintf(buf, sizeof buf, "%s %s: %s", element_kind_name(element_.kind), name().c_str(), relation);
  return {buf};
}

}  // namespace lcs
