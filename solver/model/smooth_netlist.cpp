#include "solver/model/smooth_netlist.h"

#include <cmath>

#include "solver/devices/diode.h"
#include "solver/model/netlist_options.h"

namespace lcs {

Netlist smooth_netlist(const Netlist& netlist, const SmoothingOptions& options) {
  Netlist out = netlist;
  out.smooth_junctions = true;
  const double ifit = read_netlist_options(netlist).ifit.value_or(options.ifit);  // NetlistError
  for (auto& [name, card] : out.diode_models) {
    const SmoothDiodeLaw s = smooth_equivalent(card, resolve_diode_law(card, ifit), options.emission,
                                               options.saturation_current);
    card.von = s.series_von;
    card.ron = s.rs;
    card.is = s.is;
    card.n = s.n;
    card.rs = s.rs;
    card.has_is = card.has_n = card.has_rs = true;
    // The breakdown pair (diode.cpp): threshold BV', RS and the junction (IS, N), with
    // BV' = BV - N Vt ln(IBV / IS) as ngspice's own xbv, so that its current
    // IS (exp((v_r - BV') / (N Vt)) - 1) = IBV exp((v_r - BV) / (N Vt)) - IS is ngspice's
    // breakdown branch (a junction (IBV, N) at BV would carry IBV less: 4.8 mV more clamp
    // voltage at 5 mA with IBV = 1 mA).
    // With NBV the breakdown junction's emission is NBV (diode.cpp's stamp), and so is xbv's.
    if (s.bv) card.bv = *s.bv - s.nbv.value_or(s.n) * kThermalVoltage * std::log(s.ibv / s.is);
    card.nbv = s.nbv;  // none for a VON/RON card: its breakdown is smoothed with the emission above
    card.ibv = s.is;
  }
  for (auto& [name, card] : out.bjt_models)
    card.smooth = BjtModel::Smooth{options.emission, options.saturation_current};
  return out;
}

}  // namespace lcs
