#include "solver/model/diode_law.h"

#include <cmath>

namespace lcs {

double shockley_voltage(const DiodeModel& model, double current) {
  return model.n * kThermalVoltage * std::log1p(current / model.is) + model.rs * current;
}

ResolvedDiodeLaw resolve_diode_law(const DiodeModel& model, double ifit) {
  ResolvedDiodeLaw r;
  if (model.von || model.ron) {
    r.law.von = model.von.value_or(0.0);
    r.law.ron = model.ron.value_or(0.0);
    return r;
  }
  r.fitted = true;
  r.fit_i1 = ifit / 10;
  r.fit_i2 = ifit * 10;
  const double v1 = shockley_voltage(model, r.fit_i1), v2 = shockley_voltage(model, r.fit_i2);
  r.law.ron = (v2 - v1) / (r.fit_i2 - r.fit_i1);
  r.law.von = v1 - r.law.ron * r.fit_i1;
  return r;
}

SmoothDiodeLaw smooth_equivalent(const DiodeModel& card, const ResolvedDiodeLaw& law,
                                 double emission, double saturation_current) {
  if (law.fitted || card.has_is || card.has_n || card.has_rs) return {0.0, card.is, card.n, card.rs};
  return {law.law.von, saturation_current, emission, law.law.ron};
}

}  // namespace lcs
