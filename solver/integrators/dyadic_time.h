// Exact times for the event-driven method: t = (k + f / 2^64) h0. A step of level j has length
// h0 / 2^j and may start only at a multiple of it, so every time reached is representable and
// every step uses one of the cached exponentials exp(M h0 / 2^j).
#pragma once

#include <cmath>
#include <algorithm>
#include <cstdint>
#include <limits>

namespace lcs {

struct DyadicTime {
  std::int64_t k = 0;   // whole steps of h0
  std::uint64_t f = 0;  // fraction of a step, in units of 2^-64

  // A time within rounding of a grid time k h0 is that grid time: t / h0 may round to just above
  // k (161e-6 / 7e-6 = 23.000000000000004 while 23 * 7e-6 == 161e-6), and a source corner
  // there must not be placed after the grid time, whose row would then see it early.
  static DyadicTime from(double t, double h0) {
    const double r = t / h0;
    const double k = std::round(r);
    if (std::abs(r - k) <= 8 * std::numeric_limits<double>::epsilon() * std::max(1.0, std::abs(r)))
      return DyadicTime{static_cast<std::int64_t>(k), 0};
    DyadicTime d;
    d.k = static_cast<std::int64_t>(std::floor(r));
    const double frac = r - static_cast<double>(d.k);
    d.f = frac <= 0 ? 0 : static_cast<std::uint64_t>(std::ldexp(frac, 64));
    return d;
  }
  double seconds(double h0) const {
    return (static_cast<double>(k) + std::ldexp(static_cast<double>(f), -64)) * h0;
  }
  // Level j in [0, 64]: length h0 / 2^j.
  bool aligned(int j) const {
    if (j == 0) return f == 0;
    if (j >= 64) return true;
    return (f & ((std::uint64_t(1) << (64 - j)) - 1)) == 0;
  }
  DyadicTime plus(int j) const {
    DyadicTime d = *this;
    if (j == 0) {
      ++d.k;
      return d;
    }
    const std::uint64_t add = j >= 64 ? 1 : std::uint64_t(1) << (64 - j);
    d.f += add;
    if (d.f < add) ++d.k;  // carry
    return d;
  }
  bool operator<(const DyadicTime& o) const { return k < o.k || (k == o.k && f < o.f); }
  bool operator==(const DyadicTime& o) const { return k == o.k && f == o.f; }
  bool operator<=(const DyadicTime& o) const { return !(o < *this); }
};

}  // namespace lcs
