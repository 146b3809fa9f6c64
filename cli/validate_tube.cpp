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
  for (const auto& [junction, gap] : gaps) {
    for (const PairInfo& p : model.pairs()) {
      if (p.name != junction) continue;
      Element& el = shifted.elements.at(p.element);
      if (el.kind == ElementKind::Diode) {
        // A card of its own per diode, its other parameters kept (BV); "d1:bv" is its breakdown
        // pair, whose threshold is BV and resistance Rrev. Resistances are per unit area: the
        // device divides them by the element's area again.
        const std::string own = "lcs_gap_" + el.name;
        if (el.model != own) {
          DiodeModel card = shifted.diode_models.count(el.model) ? shifted.diode_models.at(el.model) : DiodeModel{};
          if (!shifted.diode_models.count(el.model)) card.loc = el.loc;
          card.name = own;
          shifted.diode_models[own] = card;
          el.model = own;
        }
        DiodeModel& card = shifted.diode_models.at(own);
        const double area = el.value > 0 ? el.value : 1.0;
        const bool breakdown = p.name.size() >= 3 && p.name.compare(p.name.size() - 3, 3, ":bv") == 0;
        if (breakdown) {
          card.bv = p.law.von + gap;
          card.rrev = p.law.ron * area;
        } else {
          card.von = p.law.von + gap;
          card.ron = p.law.ron * area;
        }
      } else if (el.kind == ElementKind::Bjt) {
        // A card of its own per transistor, both junctions written out: VONE/RONE for "q1:be",
        // VONC/RONC for "q1:bc" (RON as the card gives it: the device divides it by the area).
        const std::string own = "lcs_gap_" + el.name;
        if (el.model != own) {
          BjtModel card = shifted.bjt_models.at(el.model);
          card.name = own;
          shifted.bjt_models[own] = card;
          el.model = own;
        }
        BjtModel& card = shifted.bjt_models.at(own);
        const double area = el.value > 0 ? el.value : 1.0;
        const bool emitter = p.name.size() >= 3 && p.name.compare(p.name.size() - 3, 3, ":be") == 0;
        (emitter ? card.vone : card.vonc) = p.law.von + gap;
        (emitter ? card.rone : card.ronc) = p.law.ron * area;
      }
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
  // The samples within [t_k - dt, t_k + dt], the ends included whatever the rounding of the
  // output times (dt is often exactly one output interval: both neighbours belong in).
  const double reach = dt * (1 + 1e-9);
  size_t first = 0, last = 0;
  for (size_t k = 0; k < n; ++k) {
    while (times[first] < times[k] - reach) ++first;
    while (last + 1 < n && times[last + 1] <= times[k] + reach) ++last;
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
