// S n+ n- nc+ nc- model [ON|OFF] and W n+ n- vname model [ON|OFF]: ngspice's ideal switches. A
// switch is a resistor branch whose resistance is RON or ROFF by its state; the state is a
// discrete mode of the circuit, changed by the transient driver (switched_transient.h) where the
// control crosses VT + VH (turning on) or VT - VH (turning off). Resistor values do not enter the
// normal tree, so every configuration of the switches has the same states x; only the LCS
// matrices differ (SwitchFamily forms one model per configuration visited).
//
// The control of S is v(nc+) - v(nc-), read over a sensing branch that carries no current (as a
// VCVS reads it, controlled_source.h); the control of W is i(vname), the current of a V source.
#pragma once

#include "solver/devices/device.h"

namespace lcs {

class Switch : public Device {
 public:
  // Throws NetlistError (at the card) when its model is not defined.
  Switch(const Element& element, const Netlist& netlist, const DeviceOptions& options);
  std::vector<BranchDecl> branches() const override;
  void stamp(const StampContext& context, Stamps& stamps) const override;
  NgspiceCards ngspice(const NgspiceDeckContext& context) const override;
  std::vector<std::string> notes() const override;

  const SwitchModel& card() const { return card_; }
  bool on() const { return on_; }  // in the configuration this model was formed for
  // The control as a probe: v(nc+,nc-) for S, i(vname) for W.
  Probe control_probe() const;

 private:
  bool senses() const;
  SwitchModel card_;
  bool on_ = false;
};

}  // namespace lcs
