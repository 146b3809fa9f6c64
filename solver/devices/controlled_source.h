// E, G, F, H: ngspice's linear controlled sources, as constitutive relations over other
// branches' quantities (the rows the Ebers–Moll transfer currents already are, bjt.h):
//
//   E n+ n- nc+ nc- gain   VCVS, a tree (voltage-source class) branch:   v_E - gain v_S = 0
//   G n+ n- nc+ nc- gm     VCCS, a link (current-source class) branch:   i_G - gm v_S = 0
//   F n+ n- vname gain     CCCS, a link:                                 i_F - gain i_V = 0
//   H n+ n- vname r        CCVS, a tree branch:                          v_H - r i_V = 0
//
// v_S is the voltage of a sensing branch nc+ -> nc- that carries no current (current-source
// class, i_S = 0: Gnucap's way of reading a voltage as a branch quantity); i_V is the current of
// the controlling V source, positive from its n+ through it to its n- (ngspice's i(vname)). The
// output current flows from n+ through the source to n-, as ngspice's. A sensing branch whose
// two nodes are one node reads 0 and is left out.
#pragma once

#include "solver/devices/device.h"

namespace lcs {

class ControlledSource : public Device {
 public:
  // Throws NetlistError (at the card) when an F or H names no voltage source.
  ControlledSource(const Element& element, const Netlist& netlist, const DeviceOptions& options);
  std::vector<BranchDecl> branches() const override;
  void stamp(const StampContext& context, Stamps& stamps) const override;
  NgspiceCards ngspice(const NgspiceDeckContext& context) const override;
  std::vector<std::string> notes() const override;

  bool voltage_output() const;   // E, H: a voltage-source-like branch
  bool voltage_control() const;  // E, G: controlled by a node-voltage difference

 private:
  bool senses() const;  // the sensing branch exists (nc+ != nc-)
  char letter() const;
  int control_element_ = -1;  // F, H: index of the controlling V source in Netlist::elements
};

}  // namespace lcs
