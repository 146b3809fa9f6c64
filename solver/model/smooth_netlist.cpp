#include "solver/model/smooth_netlist.h"

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
    card.bv = s.bv;  // the breakdown pair: threshold BV, RS, junction (IBV, N) (diode.cpp)
    card.ibv = s.ibv;
  }
  for (auto& [name, card] : out.bjt_models)
    card.smooth = BjtModel::Smooth{options.emission, options.saturation_current};
  return out;
}

}  // namespace lcs
