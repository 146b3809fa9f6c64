// circuits/lc_tank_bridge.cir (Siconos' DiodeBridge) and its closed form: a charged LC tank
// (L = 10 mH, C = 1 uF, v(0) = 10 V, i_L(0) = 0) feeds an ideal bridge loaded by R = 1 kOhm. The
// bridge always connects R across the tank (|v| either way), so v'' + v'/(RC) + v/(LC) = 0
// exactly: the diodes switch, the tank voltage stays smooth.
#pragma once

#include <cmath>

#include "tests/support/netlist_builder.h"

namespace lcs::testing {

inline Netlist lc_tank_bridge() {
  NetlistBuilder b;
  b.l("l1", "a", "0", 10e-3, 0.0).c("c1", "a", "0", 1e-6, 10.0);
  b.d("d1", "a", "p").d("d2", "n", "a").d("d3", "0", "p").d("d4", "n", "0");
  b.r("r1", "p", "n", 1e3);
  return b.build();
}

// v(a) at time t (underdamped: alpha = 500/s, w0 = 1e4 rad/s).
inline double lc_tank_closed_form(double t) {
  const double R = 1e3, L = 10e-3, C = 1e-6;
  const double alpha = 1 / (2 * R * C), w0 = 1 / std::sqrt(L * C);
  const double wd = std::sqrt(w0 * w0 - alpha * alpha);
  const double v0 = 10, dv0 = -v0 / (R * C);  // i_L(0) = 0: C v' = -v/R
  return std::exp(-alpha * t) * (v0 * std::cos(wd * t) + (dv0 + alpha * v0) / wd * std::sin(wd * t));
}

}  // namespace lcs::testing
