// V n+ n- waveform and I n+ n- waveform: independent sources, each one input u_k of the LCS.
// A voltage source's branch (tree) is v - u_k = 0; a current source's (link) is i - u_k = 0.
#pragma once

#include "solver/devices/device.h"

namespace lcs {

class IndependentSource : public Device {
 public:
  IndependentSource(const Element& element, const Netlist&, const DeviceOptions&);
  std::vector<BranchDecl> branches() const override;
  void stamp(const StampContext& context, Stamps& stamps) const override;
  bool current_probed_by_default() const override { return voltage_; }
  NgspiceCards ngspice(const NgspiceDeckContext& context) const override;

 private:
  NgspiceCards stopped_sine_cards(const NgspiceDeckContext& context) const;

  bool voltage_;
};

}  // namespace lcs
