// K L1 L2 k: mutual inductance M = k sqrt(L1 L2) between two inductors. No branch of its own.
#pragma once

#include "solver/devices/device.h"

namespace lcs {

class Coupling : public Device {
 public:
  Coupling(const Element& element, const Netlist&, const DeviceOptions&) : Device(element) {}
  std::vector<BranchDecl> branches() const override { return {}; }
  // Throws NetlistError (at the card) when a named element is not an inductor of the circuit.
  void stamp(const StampContext& context, Stamps& stamps) const override;
  NgspiceCards ngspice(const NgspiceDeckContext& context) const override;
};

}  // namespace lcs
