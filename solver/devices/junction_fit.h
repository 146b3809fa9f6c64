// A straight line v = VON + RON i standing in for a junction's curve v(i) over a current range:
// how an ideal (piecewise-linear, Stewart 5.4) diode approximates a Shockley one.
//
// The curve is ngspice's level-1 diode, forward or in breakdown:
//   forward:    v(i) = N Vt ln(1 + i / IS) + RS i          (I = IS (exp(V / (N Vt)) - 1))
//   breakdown:  v(i) = BV + NBV Vt ln(i / IBV) + RS i      (I = IBV exp(-(V + BV) / (NBV Vt)), V < 0,
//                                                           v = -V the reverse voltage; NBV
//                                                           ngspice's, default N)
// Both are concave in i, so over [i1, i2] the chord lies below the curve, farthest at the one
// current where the curve's slope equals the chord's; the least-max-error (minimax) line is the
// chord raised by half that distance, and its error is that half, reached at i1, i2 and there.
#pragma once

#include "graph/topology.h"
#include "solver/model/pair_law.h"

namespace lcs {

struct JunctionCurve {
  double offset = 0;      // V: 0 forward, BV in breakdown
  double nvt = 0;         // N Vt, V
  double scale = 1e-14;   // A: IS forward, IBV in breakdown
  bool plus_one = true;   // ln(1 + i/scale) (forward) or ln(i/scale) (breakdown)
  double rs = 0;          // ohm
  double voltage(double current) const;
  double slope(double current) const;  // dv/di
};

JunctionCurve forward_curve(double is, double n, double rs);
JunctionCurve breakdown_curve(double bv, double ibv, double n, double rs);

// The currents [A] a diode carried, forward and in breakdown, over which its curve is fitted;
// hi == 0: none carried (the default range stays).
struct CurrentRange {
  double lo = 0, hi = 0;
  // Set by the refit (diode_refit.h): the junction conducted at every sample of the run, never
  // below `least`, so it never passed through the currents of a turn-on (fit_sensitivity.h).
  bool always_on = false;
  double least = 0;
  bool empty() const { return !(hi > 0); }
};
struct DiodeCurrentRanges {
  CurrentRange forward, reverse;
};

struct LineFit {
  IdealDiodeLaw law;
  double i1 = 0, i2 = 0;    // the current range fitted over
  double max_error = 0;     // V: the largest |line - curve| over [i1, i2]
  double error_fraction = 0;  // max_error over the curve's voltage at i1 (its smallest there)
};

// The chord through (i1, v(i1)) and (i2, v(i2)); i1 < i2.
LineFit chord_fit(const JunctionCurve& curve, double i1, double i2);
// The least-max-error line over [i1, i2]; with i1 == i2 the tangent at i1 (exact there).
LineFit minimax_fit(const JunctionCurve& curve, double i1, double i2);

}  // namespace lcs
