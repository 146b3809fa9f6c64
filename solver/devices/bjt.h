// Q collector base emitter model: the full Ebers–Moll transistor (Stewart 1.3.2, Figure 5.8(b);
// 5.4.7) as a composite of primitives, as Gnucap's d_bjt.model is a circuit of them:
//
//   junction D_E  base -> emitter    (anode at the base for NPN), a complementarity pair
//   junction D_C  base -> collector  (likewise), a complementarity pair
//   transfer  F   collector -> base  current alpha_F * i_DE  (linear current-controlled source)
//   transfer  R   emitter -> base    current alpha_R * i_DC
//
// so that i_C = alpha_F i_DE - i_DC, i_E(out) = i_DE - alpha_R i_DC. PNP is the mirror image:
// every branch reversed. alpha = beta / (1 + beta) < 1 is what keeps the LCS well posed (5.4.7):
// the transfer sources make D non-symmetric, and with alpha < 1 a lone transistor's D is still a
// P-matrix. A base–emitter capacitance (CJE on the card, or `.options bjtcap=` for every
// transistor) is the book's physical regularisation, never a default; a base–collector one (CJC)
// is the card's too. Both are linear, at their zero-bias values: SPICE's depletion capacitances
// shrink under reverse bias (VJE/MJE, VJC/MJC, not modelled), and the diffusion charges TF, TR
// are not modelled. A junction whose two terminals are one node carries no current (v = 0, as
// the smooth junction at zero bias) and is left out with its transfer source and capacitance.
#pragma once

#include "solver/devices/device.h"
#include "solver/devices/diode.h"

namespace lcs {

// One junction's card as a diode: VONE/VONC over VON, RONE/RONC over RON (both scaled by 1/area),
// smooth IS/alpha * area (the Ebers–Moll saturation currents I_ES = IS/alpha_F, I_CS = IS/alpha_R)
// and NF or NR. A junction with neither VON nor RON gets the diode's piecewise-linear fit.
enum class Junction { BaseEmitter, BaseCollector };
DiodeModel junction_card(const BjtModel& model, Junction junction, double area);

class Bjt : public Device {
 public:
  // Throws NetlistError (at the card) when its model is not defined.
  Bjt(const Element& element, const Netlist& netlist, const DeviceOptions& options);
  std::vector<BranchDecl> branches() const override;
  void stamp(const StampContext& context, Stamps& stamps) const override;
  std::vector<char> terminals_probed_by_default() const override { return {'c', 'b', 'e'}; }
  std::vector<std::pair<int, double>> terminal_current(char terminal) const override;
  NgspiceCards ngspice(const NgspiceDeckContext& context) const override;
  std::vector<std::string> notes() const override;
  std::vector<FittedJunction> fitted_junctions() const override;

  const BjtModel& card() const { return card_; }
  double alpha_f() const { return alpha_f_; }
  double alpha_r() const { return alpha_r_; }
  const ResolvedDiodeLaw& law(Junction j) const { return j == Junction::BaseEmitter ? law_e_ : law_c_; }

 private:
  // Local branch indices of the four primitives (-1: left out, its terminals are one node).
  struct Layout { int de = -1, dc = -1, f = -1, r = -1, cbe = -1, cbc = -1; };
  Layout layout() const;
  const std::string& node(char terminal) const;

  BjtModel card_;
  double area_ = 1;
  double cbe_ = 0;  // base–emitter capacitance: `.options bjtcap=`, else CJE * area, else none
  double cbc_ = 0;  // base–collector capacitance: CJC * area, else none
  double alpha_f_ = 0, alpha_r_ = 0;
  DiodeModel card_e_, card_c_;
  ResolvedDiodeLaw law_e_, law_c_;
};

}  // namespace lcs
