#include "solver/model/smooth_netlist.h"

#include <cstdlib>

#include "solver/devices/diode.h"

namespace lcs {

Netlist smooth_netlist(const Netlist& netlist, const SmoothingOptions& options) {
  Netlist out = netlist;
  double ifit = options.ifit;
  if (auto it = netlist.options.find("ifit"); it != netlist.options.end()) {
    char* end = nullptr;
    const double v = std::strtod(it->second.c_str(), &end);
    if (!it->second.empty() && *end == '\0' && v > 0) ifit = v;
  }
  for (auto& [name, card] : out.diode_models) {
    const SmoothDiodeLaw s = smooth_equivalent(card, resolve_diode_law(card, ifit), options.emission,
                                               options.saturation_current);
    card.von = s.series_von;
    card.ron = s.rs;
    card.is = s.is;
    card.n = s.n;
    card.rs = s.rs;
    card.has_is = card.has_n = card.has_rs = true;
  }
  return out;
}

}  // namespace lcs
