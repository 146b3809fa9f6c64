#include "solver/devices/switch.h"

#include "solver/devices/two_terminal_cards.h"

#include <cstdio>

namespace lcs {

namespace {

const SwitchModel& model_of(const Element& element, const Netlist& netlist) {
  auto it = netlist.switch_models.find(element.model);
  if (it == netlist.switch_models.end())
    throw NetlistError(element.loc, "switch " + element.name + ": unknown model '" + element.model + "'");
  return it->second;
}

}  // namespace

Switch::Switch(const Element& element, const Netlist& netlist, const DeviceOptions& options)
    : Device(element), card_(model_of(element, netlist)) {
  auto it = options.switch_on.find(element.name);
  on_ = it != options.switch_on.end() ? it->second : element.initially_on.value_or(false);
}

bool Switch::senses() const {
  return element_.kind == ElementKind::VSwitch && element_.nodes.at(2) != element_.nodes.at(3);
}

std::vector<BranchDecl> Switch::branches() const {
  std::vector<BranchDecl> out{{name(), BranchClass::Resistor, element_.nodes.at(0), element_.nodes.at(1)}};
  if (senses()) out.push_back({name() + "#sense", BranchClass::CurrentSource, element_.nodes.at(2), element_.nodes.at(3)});
  return out;
}

void Switch::stamp(const StampContext& context, Stamps& stamps) const {
  const int b = context.branch(0);
  stamps.relations.push_back({b, {{Term::Of::Voltage, b, 1.0}, {Term::Of::Current, b, -(on_ ? card_.ron : card_.roff)}}});
  if (senses()) {
    const int s = context.branch(1);
    stamps.relations.push_back({s, {{Term::Of::Current, s, 1.0}}});  // the sensing branch: i_S = 0
  }
}

Probe Switch::control_probe() const {
  Probe p;
  if (element_.kind == ElementKind::VSwitch) {
    p.kind = Probe::Kind::NodePairVoltage;
    p.a = element_.nodes.at(2);
    p.b = element_.nodes.at(3);
  } else {
    p.kind = Probe::Kind::ElementCurrent;
    p.a = element_.control;
  }
  p.loc = element_.loc;
  return p;
}

// Written through: the same card (ON/OFF kept) and its model under a name unique in the deck.
NgspiceCards Switch::ngspice(const NgspiceDeckContext& context) const {
  // A reversed switch (on as its control falls) is ngspice's SW on the negated control: the control
  // nodes swapped, or for a current control a CCVS of gain -1 driving a fresh node.
  bool voltage = element_.kind == ElementKind::VSwitch;
  std::vector<std::string> before;
  std::string control = voltage ? element_.nodes.at(2) + " " + element_.nodes.at(3) : deck_name('v', element_.control);
  if (card_.reversed) {
    if (voltage) {
      control = element_.nodes.at(3) + " " + element_.nodes.at(2);
    } else {
      const std::string node = context.fresh("lcs_ctl_" + name());
      before.push_back(context.fresh("h_lcs_ctl_" + name()) + " " + node + " 0 " + control + " -1");
      control = node + " 0";
      voltage = true;
    }
  }
  const double vt = card_.reversed ? -card_.vt : card_.vt;
  const std::string model = context.fresh("lcs_sw_" + name());
  std::string rest = control + " " + model;
  if (element_.initially_on) rest += *element_.initially_on ? " ON" : " OFF";
  NgspiceCards cards = two_terminal_cards(deck_name(voltage ? 's' : 'w', name()), element_.nodes.at(0),
                                          element_.nodes.at(1), rest, name(), context);
  cards.lines.insert(cards.lines.begin(), before.begin(), before.end());
  cards.models.push_back(".model " + model + (voltage ? " SW(VT=" : " CSW(IT=") + number(vt) +
                         (voltage ? " VH=" : " IH=") + number(card_.vh) + " RON=" + number(card_.ron) +
                         " ROFF=" + number(card_.roff) + ")");
  return cards;
}

std::vector<std::string> Switch::notes() const {
  const bool voltage = element_.kind == ElementKind::VSwitch;
  const Probe control = control_probe();
  const char* unit = voltage ? "V" : "A";
  const bool reversed = card_.reversed;
  char buf[320];
  std::snprintf(buf, sizeof buf,
                "switch %s: controlled by %s, on %s %.6g %s, off %s %.6g %s (%s = %.6g, %s = %.6g), "
                "RON = %.6g ohm, ROFF = %.6g ohm, %s%s",
                name().c_str(), control.name().c_str(), reversed ? "below" : "above",
                reversed ? card_.vt - card_.vh : card_.vt + card_.vh, unit, reversed ? "above" : "below",
                reversed ? card_.vt + card_.vh : card_.vt - card_.vh, unit,
                voltage ? "VT" : "IT", card_.vt, voltage ? "VH" : "IH", card_.vh, card_.ron, card_.roff,
                on_ ? "on" : "off", element_.initially_on ? (*element_.initially_on ? " (ON on the card)" : " (OFF on the card)") : "");
  return {buf};
}

}  // namespace lcs
