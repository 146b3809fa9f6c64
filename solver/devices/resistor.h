// R n+ n- value: one resistive branch, v - R i = 0.
#pragma once

#include "solver/devices/device.h"

namespace lcs {

class Resistor : public Device {
 public:
  Resistor(const Element& element, const Netlist&, const DeviceOptions&) : Device(element) {}
  std::vector<BranchDecl> branches() const override;
  void stamp(const StampContext& context, Stamps& stamps) const override;
  NgspiceCards ngspice(const NgspiceDeckContext& context) const override;
};

}  // namespace lcs
