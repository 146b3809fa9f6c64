// L n+ n- value [IC=i0]: an energy-storing branch. A link inductor's current is a state; a tree
// inductor (in a cutset of inductors and current sources) is dependent (circuit_model.h).
#pragma once

#include "solver/devices/device.h"

namespace lcs {

class Inductor : public Device {
 public:
  Inductor(const Element& element, const Netlist&, const DeviceOptions&) : Device(element) {}
  std::vector<BranchDecl> branches() const override;
  void stamp(const StampContext& context, Stamps& stamps) const override;
  bool current_probed_by_default() const override { return true; }
  NgspiceCards ngspice(const NgspiceDeckContext& context) const override;
};

}  // namespace lcs
