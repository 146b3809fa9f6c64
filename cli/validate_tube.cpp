#include "cli/validate_tube.h"

#include <algorithm>
#include <cmath>

#include "solver/model/pair_law.h"

namespace lcs {

double model_gap(double peak, double emission, double saturation_current) {
  return peak > saturation_current ? emission * kThermalVoltage * std::log(peak / saturation_current) : 0.0;
}

Netlist netlist_with_shifted_thresholds(const CircuitModel& model,
                                        const std::vector<std::pair<std::string, double>>& gaps) {
  Netlist shifted = model.netlist();
  for (const auto& [diode, gap] : gaps) {
    for (const PairInfo& p : model.pairs()) {
      Element& el = shifted.elements.at(p.element);
      if (el.name != diode || el.kind != ElementKind::Diode) continue;
      DiodeModel card;
      card.name = "lcs_gap_" + el.name;
      card.von = p.law.von + gap;
      card.ron = p.law.ron;
      card.loc = shifted.diode_models.count(el.model) ? shifted.diode_models.at(el.model).loc : el.loc;
      shifted.diode_models[card.name] = card;
      el.model = card.name;
    }
  }
  return shifted;
}

double turn_on_shift(const std::vector<double>& times, const std::vector<double>& vd,
                     const std::vector<double>& id, double gap) {
  double peak = 0;
  for (double i : id) peak = std::max(peak, i);
  const double on = 1e-9 * peak;
  std::vector<double> shifts;
  for (size_t k = 2; k < times.size(); ++k) {
    if (!(id[k - 1] <= on && id[k] > on)) continue;
    const double slope = (vd[k - 1] - vd[k - 2]) / (times[k - 1] - times[k - 2]);
    if (slope > 0) shifts.push_back(gap / slope);
  }
  if (shifts.empty()) return 0;
  std::nth_element(shifts.begin(), shifts.begin() + shifts.size() / 2, shifts.end());
  return shifts[shifts.size() / 2];
}

TubeDistance tube_distance(const std::vector<double>& times, const std::vector<double>& nominal,
                           const std::vector<double>& shifted, const std::vector<double>& witness,
                           double dt) {
  TubeDistance out;
  const size_t n = times.size();
  size_t first = 0, last = 0;  // the samples within [t_k - dt, t_k + dt]
  for (size_t k = 0; k < n; ++k) {
    while (times[first] < times[k] - dt) ++first;
    while (last + 1 < n && times[last + 1] <= times[k] + dt) ++last;
    double lo = INFINITY, hi = -INFINITY;
    for (size_t j = first; j <= last; ++j) {
      lo = std::min({lo, nominal[j], shifted[j]});
      hi = std::max({hi, nominal[j], shifted[j]});
    }
    const double d = std::max({0.0, lo - witness[k], witness[k] - hi});
    if (d > out.max) out.max = d, out.worst_time = times[k];
  }
  return out;
}

}  // namespace lcs
