// Independent source waveforms with ngspice semantics (DC, SIN, PULSE, PWL).
//
// PULSE and PWL are piecewise linear. Both are evaluated through one list of knots (time, value)
// with non-decreasing times; two knots at the same time are a jump. Values are right-continuous:
// at a jump, value(t) is the value just after it, consistently with derivative() being the right
// derivative. This is where PULSE differs from ngspice on purpose: an explicit zero rise or fall
// time is a jump here (ngspice replaces it by TSTEP), because ideal circuits can take it.
#include "netlist/waveform.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <limits>

namespace lcs {
namespace {

constexpr double kPi = 3.14159265358979323846;

// More breakpoints than this in one call are not generated (a pathological PER against a long
// interval would otherwise exhaust memory); the list is then cut at the first kMaxBreakpoints.
constexpr std::size_t kMaxBreakpoints = 10'000'000;

struct Knot {
  double t, v;
};
using Knots = std::vector<Knot>;

// Value at tau, right-continuous; constant before the first and after the last knot.
double pl_value(const Knots& k, double tau) {
  if (k.empty()) return 0.0;
  if (tau < k.front().t) return k.front().v;
  auto it = std::upper_bound(k.begin(), k.end(), tau, [](double x, const Knot& n) { return x < n.t; });
  std::size_t i = static_cast<std::size_t>(it - k.begin()) - 1;  // last knot with t <= tau
  if (i + 1 == k.size()) return k[i].v;
  const Knot& a = k[i];
  const Knot& b = k[i + 1];  // b.t > tau >= a.t, so b.t > a.t
  return a.v + (b.v - a.v) * (tau - a.t) / (b.t - a.t);
}

// Limit from the left at tau.
double pl_left(const Knots& k, double tau) {
  if (k.empty()) return 0.0;
  if (tau <= k.front().t) return k.front().v;
  auto it = std::lower_bound(k.begin(), k.end(), tau, [](const Knot& n, double x) { return n.t < x; });
  if (it == k.end()) return k.back().v;
  std::size_t j = static_cast<std::size_t>(it - k.begin());  // first knot with t >= tau; j >= 1
  const Knot& a = k[j - 1];
  const Knot& b = k[j];  // a.t < tau <= b.t
  return a.v + (b.v - a.v) * (tau - a.t) / (b.t - a.t);
}

// Right derivative at tau.
double pl_slope(const Knots& k, double tau) {
  if (k.empty() || tau < k.front().t) return 0.0;
  auto it = std::upper_bound(k.begin(), k.end(), tau, [](double x, const Knot& n) { return x < n.t; });
  std::size_t i = static_cast<std::size_t>(it - k.begin()) - 1;
  if (i + 1 == k.size()) return 0.0;
  return (k[i + 1].v - k[i].v) / (k[i + 1].t - k[i].t);
}

// Exact bounds over [a, b] (a <= b): the extremes of a piecewise-linear function are at knots or
// at the ends (one-sided limits included, so a jump inside the interval counts both sides).
void pl_range(const Knots& k, double a, double b, double& lo, double& hi) {
  auto take = [&](double v) {
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  };
  take(pl_value(k, a));
  take(pl_left(k, b));
  take(pl_value(k, b));
  for (const Knot& n : k)
    if (n.t > a && n.t < b) take(n.v);
}

double param(const std::vector<double>& p, std::size_t i, double fallback = 0.0) {
  return i < p.size() ? p[i] : fallback;
}

std::string fmt(double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.12g", x);
  return buf;
}

// One period of a PULSE (phase 0 at TD), or the whole pulse when it does not repeat.
struct PulseShape {
  double v1 = 0, td = 0, per = 0;  // per <= 0: a single pulse
  Knots knots;
};

PulseShape pulse_shape(const std::vector<double>& p) {
  PulseShape s;
  s.v1 = param(p, 0);
  double v2 = param(p, 1);
  s.td = param(p, 2);
  double tr = std::max(0.0, param(p, 3));
  double tf = std::max(0.0, param(p, 4));
  double pw = std::max(0.0, param(p, 5));
  s.per = param(p, 6);
  Knots full = {{0.0, s.v1}, {tr, v2}, {tr + pw, v2}, {tr + pw + tf, s.v1}};
  if (!(s.per > 0)) {
    s.per = 0;
    s.knots = full;
    return s;
  }
  // Periodic: the shape is cut at PER (ngspice restarts the period even in the middle of an edge).
  for (const Knot& n : full)
    if (n.t < s.per) s.knots.push_back(n);
  s.knots.push_back({s.per, pl_left(full, s.per)});
  return s;
}

// Splits t >= td into (period index, phase in [0, per)). Phases within a few ulps of a knot (or of
// the period end) are snapped onto it, so breakpoints computed as td + k*per + knot land exactly on
// the corner and a jump there yields its right value.
void pulse_phase(const PulseShape& s, double t, double& period_start, double& tau) {
  double x = t - s.td;
  if (s.per <= 0) {
    period_start = s.td;
    tau = x;
  } else {
    double k = std::floor(x / s.per);
    if (!std::isfinite(k)) k = 0;  // a period too small to divide by: no meaningful phase
    tau = x - k * s.per;
    double tol = 64 * DBL_EPSILON * std::max({std::fabs(t), std::fabs(s.td), s.per});
    if (tau >= s.per - tol) {
      k += 1;
      tau = 0;
    }
    if (!(tau >= 0)) tau = 0;  // also NaN
    period_start = s.td + k * s.per;
  }
  double tol = 64 * DBL_EPSILON * std::max({std::fabs(t), std::fabs(s.td), s.per});
  for (const Knot& n : s.knots)
    if (std::fabs(tau - n.t) <= tol) {
      tau = n.t;
      break;
    }
  if (tau < 0) tau = 0;
}

Knots pwl_knots(const std::vector<double>& p) {
  Knots k;
  for (std::size_t i = 0; i + 1 < p.size(); i += 2) k.push_back({p[i], p[i + 1]});
  return k;
}

// SIN: VO + VA exp(-THETA tau) sin(2 pi FREQ tau + PHASE), tau = t - TD >= 0.
struct SinShape {
  double vo, va, freq, td, theta, phase;  // phase in radians
  explicit SinShape(const std::vector<double>& p)
      : vo(param(p, 0)),
        va(param(p, 1)),
        freq(param(p, 2)),
        td(param(p, 3)),
        theta(param(p, 4)),
        phase(param(p, 5) * kPi / 180.0) {}
  double value(double t) const {
    if (t < td) return vo + va * std::sin(phase);
    double tau = t - td;
    return vo + va * std::exp(-theta * tau) * std::sin(2 * kPi * freq * tau + phase);
  }
  double derivative(double t) const {
    if (t < td) return 0.0;
    double tau = t - td, w = 2 * kPi * freq, x = w * tau + phase;
    return va * std::exp(-theta * tau) * (w * std::cos(x) - theta * std::sin(x));
  }
};

}  // namespace

void Waveform::reresolve(double tstep, double tstop) {
  if (written >= 0) params.resize(written);
  resolved = false;
  resolve(tstep, tstop);
}

void Waveform::resolve(double tstep, double tstop) {
  if (resolved) return;
  if (written < 0) written = static_cast<int>(params.size());
  switch (kind) {
    case Kind::Dc:
    case Kind::Pwl:
      break;
    case Kind::Sin:
      if (params.size() < 2) params.resize(2, 0.0);
      if (params.size() < 3) params.push_back(tstop > 0 ? 1.0 / tstop : 0.0);
      params.resize(6, 0.0);  // TD THETA PHASE
      break;
    case Kind::Pulse: {
      if (params.size() < 2) params.resize(2, 0.0);
      const double defaults[] = {0.0 /*TD*/, tstep /*TR*/, tstep /*TF*/, tstop /*PW*/, tstop /*PER*/};
      while (params.size() < 7) params.push_back(defaults[params.size() - 2]);
      break;
    }
  }
  resolved = true;
}

double Waveform::value(double t) const {
  if (!resolved && kind != Kind::Dc) {
    Waveform w = *this;
    w.resolve(0, 0);
    return w.value(t);
  }
  t = std::max(t, 0.0);
  switch (kind) {
    case Kind::Dc:
      return dc;
    case Kind::Sin:
      return SinShape(params).value(t);
    case Kind::Pulse: {
      PulseShape s = pulse_shape(params);
      if (t < s.td) return s.v1;
      double start, tau;
      pulse_phase(s, t, start, tau);
      return pl_value(s.knots, tau);
    }
    case Kind::Pwl:
      return pl_value(pwl_knots(params), t);
  }
  return dc;
}

double Waveform::value_before(double t) const {
  if (!resolved && kind != Kind::Dc) {
    Waveform w = *this;
    w.resolve(0, 0);
    return w.value_before(t);
  }
  t = std::max(t, 0.0);
  switch (kind) {
    case Kind::Dc:
    case Kind::Sin:
      return value(t);
    case Kind::Pulse: {
      PulseShape s = pulse_shape(params);
      if (t <= s.td) return s.v1;
      double start, tau;
      pulse_phase(s, t, start, tau);
      // At the start of a period (other than the first) the left limit is the previous period's end.
      if (tau == 0) return s.per > 0 ? pl_left(s.knots, s.per) : s.v1;
      return pl_left(s.knots, tau);
    }
    case Kind::Pwl:
      return pl_left(pwl_knots(params), t);
  }
  return dc;
}

double Waveform::derivative(double t) const {
  if (!resolved && kind != Kind::Dc) {
    Waveform w = *this;
    w.resolve(0, 0);
    return w.derivative(t);
  }
  t = std::max(t, 0.0);
  switch (kind) {
    case Kind::Dc:
      return 0.0;
    case Kind::Sin:
      return SinShape(params).derivative(t);
    case Kind::Pulse: {
      PulseShape s = pulse_shape(params);
      if (t < s.td) return 0.0;
      double start, tau;
      pulse_phase(s, t, start, tau);
      return pl_slope(s.knots, tau);
    }
    case Kind::Pwl:
      return pl_slope(pwl_knots(params), t);
  }
  return 0.0;
}

std::pair<double, double> Waveform::range(double t0, double t1) const {
  if (!resolved && kind != Kind::Dc) {
    Waveform w = *this;
    w.resolve(0, 0);
    return w.range(t0, t1);
  }
  if (t1 < t0) std::swap(t0, t1);
  t0 = std::max(t0, 0.0);
  t1 = std::max(t1, 0.0);
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  auto take = [&](double v) {
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  };
  switch (kind) {
    case Kind::Dc:
      take(dc);
      break;
    case Kind::Pwl:
      pl_range(pwl_knots(params), t0, t1, lo, hi);
      break;
    case Kind::Pulse: {
      PulseShape s = pulse_shape(params);
      if (t0 < s.td) take(s.v1);
      if (t1 < s.td) break;
      double a = std::max(t0, s.td);
      double start, tau_a;
      pulse_phase(s, a, start, tau_a);
      if (s.per <= 0) {
        pl_range(s.knots, tau_a, t1 - s.td, lo, hi);
      } else if (t1 - a >= s.per) {
        for (const Knot& n : s.knots) take(n.v);  // a whole period is covered
      } else {
        double tau_b = tau_a + (t1 - a);
        if (tau_b <= s.per) {
          pl_range(s.knots, tau_a, tau_b, lo, hi);
        } else {
          pl_range(s.knots, tau_a, s.per, lo, hi);
          pl_range(s.knots, 0.0, tau_b - s.per, lo, hi);
        }
      }
      break;
    }
    case Kind::Sin: {
      SinShape s(params);
      take(s.value(t0));
      take(s.value(t1));
      if (t1 < s.td) break;
      double a = std::max(t0, s.td);
      take(s.value(a));
      // Interior extremes: w cos(x) = theta sin(x), x = w tau + phase, i.e. x = atan2(w, theta) + k pi.
      double w = 2 * kPi * s.freq;
      if (w != 0.0 && s.va != 0.0) {
        double x0 = std::atan2(w, s.theta);
        double ka = (w * (a - s.td) + s.phase - x0) / kPi;
        double kb = (w * (t1 - s.td) + s.phase - x0) / kPi;
        double kmin = std::ceil(std::min(ka, kb)), kmax = std::floor(std::max(ka, kb));
        auto at = [&](double k) {
          double t = s.td + (x0 + k * kPi - s.phase) / w;
          if (t >= a && t <= t1) take(s.value(t));
        };
        // The envelope is monotonic, so the largest swings are among the first or last two.
        if (kmax - kmin <= 4) {
          for (double k = kmin; k <= kmax; k += 1) at(k);
        } else {
          at(kmin);
          at(kmin + 1);
          at(kmax - 1);
          at(kmax);
        }
      }
      break;
    }
  }
  return {lo, hi};
}

std::vector<double> Waveform::breakpoints(double t0, double t1) const {
  if (!resolved && kind != Kind::Dc) {
    Waveform w = *this;
    w.resolve(0, 0);
    return w.breakpoints(t0, t1);
  }
  std::vector<double> out;
  if (t1 < t0) std::swap(t0, t1);
  auto add = [&](double t) {
    if (t > t0 && t < t1 && out.size() < kMaxBreakpoints) out.push_back(t);
  };
  switch (kind) {
    case Kind::Dc:
      break;
    case Kind::Sin:
      add(SinShape(params).td);
      break;
    case Kind::Pwl:
      for (const Knot& n : pwl_knots(params)) add(n.t);
      break;
    case Kind::Pulse: {
      PulseShape s = pulse_shape(params);
      add(s.td);
      if (s.per <= 0) {
        for (const Knot& n : s.knots) add(s.td + n.t);
        break;
      }
      std::vector<double> corners;
      for (const Knot& n : s.knots)
        if (n.t < s.per && (corners.empty() || corners.back() != n.t)) corners.push_back(n.t);
      double kfirst = std::max(0.0, std::floor((t0 - s.td) / s.per));
      double klast = std::ceil((t1 - s.td) / s.per);
      if (!std::isfinite(kfirst) || !std::isfinite(klast)) break;
      // An integer count, so a period tiny against t (k beyond 2^53) cannot loop forever.
      const double periods = std::min(klast - kfirst, static_cast<double>(kMaxBreakpoints));
      for (long long j = 0; j <= static_cast<long long>(periods) && out.size() < kMaxBreakpoints; ++j)
        for (double c : corners) add(s.td + (kfirst + static_cast<double>(j)) * s.per + c);
      break;
    }
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

std::string Waveform::describe() const {
  std::string out;
  auto list = [&](const char* name, std::size_t n) {
    out += name;
    out += "(";
    for (std::size_t i = 0; i < n; ++i) out += (i ? " " : "") + fmt(params[i]);
    out += ")";
  };
  if (kind != Kind::Dc && dc != 0.0) out = "DC " + fmt(dc) + " ";
  switch (kind) {
    case Kind::Dc:
      out = "DC " + fmt(dc);
      break;
    case Kind::Sin: {
      std::size_t n = params.size();
      while (n > 3 && params[n - 1] == 0.0) --n;  // TD, THETA, PHASE default to 0
      list("SIN", n);
      break;
    }
    case Kind::Pulse:
      list("PULSE", params.size());
      break;
    case Kind::Pwl:
      list("PWL", params.size());
      break;
  }
  return out;
}

}  // namespace lcs
