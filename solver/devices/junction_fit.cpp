#include "solver/devices/junction_fit.h"

#include <algorithm>
#include <cmath>

namespace lcs {

double JunctionCurve::voltage(double i) const {
  return offset + nvt * (plus_one ? std::log1p(i / scale) : std::log(i / scale)) + rs * i;
}

double JunctionCurve::slope(double i) const {
  return nvt / (plus_one ? scale + i : i) + rs;
}

JunctionCurve forward_curve(double is, double n, double rs) {
  return {0.0, n * kThermalVoltage, is, true, rs};
}

JunctionCurve breakdown_curve(double bv, double ibv, double n, double rs) {
  return {bv, n * kThermalVoltage, ibv, false, rs};
}

namespace {

// Where the curve's slope equals `s` (inside [i1, i2] for the chord's slope, by the mean value
// theorem): nvt / (c + i) + rs = s.
double point_of_slope(const JunctionCurve& curve, double s, double i1, double i2) {
  const double i = curve.nvt / (s - curve.rs) - (curve.plus_one ? curve.scale : 0.0);
  return std::clamp(i, i1, i2);
}

LineFit finish(const JunctionCurve& curve, LineFit f) {
  const double v1 = curve.voltage(f.i1);
  f.error_fraction = v1 > 0 ? f.max_error / v1 : 0.0;
  return f;
}

}  // namespace

LineFit chord_fit(const JunctionCurve& curve, double i1, double i2) {
  LineFit f;
  f.i1 = i1;
  f.i2 = i2;
  const double v1 = curve.voltage(i1), v2 = curve.voltage(i2);
  f.law.ron = (v2 - v1) / (i2 - i1);
  f.law.von = v1 - f.law.ron * i1;
  const double im = point_of_slope(curve, f.law.ron, i1, i2);
  f.max_error = curve.voltage(im) - (f.law.von + f.law.ron * im);
  return finish(curve, f);
}

LineFit minimax_fit(const JunctionCurve& curve, double i1, double i2) {
  if (!(i2 > i1 * (1 + 1e-9))) {
    LineFit f;
    f.i1 = f.i2 = i1;
    f.law.ron = curve.slope(i1);
    f.law.von = curve.voltage(i1) - f.law.ron * i1;
    return finish(curve, f);
  }
  LineFit f = chord_fit(curve, i1, i2);
  f.max_error /= 2;
  f.law.von += f.max_error;
  return finish(curve, f);
}

}  // namespace lcs
