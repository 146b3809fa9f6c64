// An lcspice probe's values from an ngspice run: plus - minus of the vectors the deck
// translation names for it (ProbeSource).
#pragma once

#include <string>
#include <vector>

#include "ngspice/deck_translation.h"
#include "ngspice/ngspice_session.h"

namespace lcs {

// Throws NgspiceError (NoData) naming the missing vector.
inline std::vector<double> probe_series(const NgspiceResult& r, const ProbeSource& src) {
  auto vec = [&](const std::string& name) -> const std::vector<double>& {
    auto it = r.vectors.find(name);
    if (it == r.vectors.end())
      throw NgspiceError(NgspiceError::Kind::NoData, "ngspice returned no vector '" + name + "'", {});
    return it->second;
  };
  std::vector<double> y(r.time.size(), 0.0);
  if (!src.plus.empty()) y = vec(src.plus);
  if (!src.minus.empty()) {
    const std::vector<double>& m = vec(src.minus);
    for (size_t k = 0; k < y.size(); ++k) y[k] -= m[k];
  }
  return y;
}

}  // namespace lcs
