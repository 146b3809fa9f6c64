// C n+ n- value [IC=v0]: an energy-storing branch. A tree capacitor's voltage is a state; a link
// capacitor (in a loop of capacitors and voltage sources) is dependent (circuit_model.h).
#pragma once

#include "solver/devices/device.h"

namespace lcs {

class Capacitor : public Device {
 public:
  Capacitor(const Element& element, const Netlist&, const DeviceOptions&) : Device(element) {}
  std::vector<BranchDecl> branches() const override;
  void stamp(const StampContext& context, Stamps& stamps) const override;
  NgspiceCards ngspice(const NgspiceDeckContext& context) const override;
};

}  // namespace lcs
