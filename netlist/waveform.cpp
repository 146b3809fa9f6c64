// Independent source waveforms with ngspice semantics (DC, SIN, PULSE, PWL, EXP, SFFM, AM).
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
#include <optional>

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

// A PWL's parameters (t1 v1 t2 v2 ...) read as knots in place: the functions below take either
// this or a Knots list, so a PWL's value costs a binary search, not a copy of its points (a
// 20,000-point PWL took 241 us a step).
struct ParamKnots {
  const std::vector<double>& p;
  std::size_t size() const { return p.size() / 2; }
  bool empty() const { return size() == 0; }
  Knot operator[](std::size_t i) const { return {p[2 * i], p[2 * i + 1]}; }
  Knot front() const { return (*this)[0]; }
};

// The number of knots with t <= tau (std::upper_bound's index), and with t < tau (lower_bound's).
template <class K>
std::size_t knots_at_or_before(const K& k, double tau) {
  std::size_t lo = 0, hi = k.size();
  while (lo < hi) {
    const std::size_t mid = lo + (hi - lo) / 2;
    if (k[mid].t <= tau) lo = mid + 1;
    else hi = mid;
  }
  return lo;
}
template <class K>
std::size_t knots_before(const K& k, double tau) {
  std::size_t lo = 0, hi = k.size();
  while (lo < hi) {
    const std::size_t mid = lo + (hi - lo) / 2;
    if (k[mid].t < tau) lo = mid + 1;
    else hi = mid;
  }
  return lo;
}

// Value at tau, right-continuous; constant before the first and after the last knot.
template <class K>
double pl_value(const K& k, double tau) {
  if (k.empty()) return 0.0;
  if (tau < k.front().t) return k.front().v;
  const std::size_t i = knots_at_or_before(k, tau) - 1;  // last knot with t <= tau
  if (i + 1 == k.size()) return k[i].v;
  const Knot a = k[i];
  const Knot b = k[i + 1];  // b.t > tau >= a.t, so b.t > a.t
  return a.v + (b.v - a.v) * (tau - a.t) / (b.t - a.t);
}

// Limit from the left at tau.
template <class K>
double pl_left(const K& k, double tau) {
  if (k.empty()) return 0.0;
  if (tau <= k.front().t) return k.front().v;
  const std::size_t j = knots_before(k, tau);  // first knot with t >= tau; j >= 1
  if (j == k.size()) return k[j - 1].v;
  const Knot a = k[j - 1];
  const Knot b = k[j];  // a.t < tau <= b.t
  return a.v + (b.v - a.v) * (tau - a.t) / (b.t - a.t);
}

// Right derivative at tau.
template <class K>
double pl_slope(const K& k, double tau) {
  if (k.empty() || tau < k.front().t) return 0.0;
  const std::size_t i = knots_at_or_before(k, tau) - 1;
  if (i + 1 == k.size()) return 0.0;
  return (k[i + 1].v - k[i].v) / (k[i + 1].t - k[i].t);
}

// Exact bounds over [a, b] (a <= b): the extremes of a piecewise-linear function are at knots or
// at the ends (one-sided limits included, so a jump inside the interval counts both sides).
template <class K>
void pl_range(const K& k, double a, double b, double& lo, double& hi) {
  auto take = [&](double v) {
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  };
  take(pl_value(k, a));
  take(pl_left(k, b));
  take(pl_value(k, b));
  for (std::size_t i = knots_at_or_before(k, a); i < k.size() && k[i].t < b; ++i) take(k[i].v);
}

double param(const std::vector<double>& p, std::size_t i, double fallback = 0.0) {
  return i < p.size() ? p[i] : fallback;
}

std::string fmt(double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.12g", x);
  return buf;
}

// One period of a PULSE (phase 0 at TD), or the whole pulse when it does not repeat. NP, the
// 8th parameter (ngspice 39's vsrcload.c, LTspice's Ncycles): NP > 0 periods, then V1 for good
// from `end` = TD + NP PER on (where the next period would start, at V1).
struct PulseShape {
  double v1 = 0, td = 0, per = 0;  // per <= 0: a single pulse
  double end = INFINITY;
  Knots knots;
  bool over(double t) const { return t > end; }
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
  const double np = param(p, 7);
  if (s.per > 0 && np > 0 && std::isfinite(s.td + np * s.per)) s.end = s.td + np * s.per;
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

// The phase of t >= td in its period, in [0, per) (t - td for a single pulse). Phases within a
// few ulps of a knot (or of the period end) are snapped onto it, so breakpoints computed as
// td + k*per + knot land exactly on the corner and a jump there yields its right value.
// Shape: td, per and knots (a Knots list or a view of one, sorted by t).
template <class Shape>
double pulse_phase(const Shape& s, double t) {
  double tau = t - s.td;
  if (s.per > 0) {
    double k = std::floor(tau / s.per);
    if (!std::isfinite(k)) k = 0;  // a period too small to divide by: no meaningful phase
    tau -= k * s.per;
    double tol = 64 * DBL_EPSILON * std::max({std::fabs(t), std::fabs(s.td), s.per});
    if (tau >= s.per - tol) tau = 0;
    if (!(tau >= 0)) tau = 0;  // also NaN
  }
  double tol = 64 * DBL_EPSILON * std::max({std::fabs(t), std::fabs(s.td), s.per});
  // The first knot within tol of tau: the first at or after tau - tol (or, by rounding, the one
  // before it), found by bisection (a scan cost a 2000-point PWL with r= 15 us a step).
  const std::size_t j = knots_before(s.knots, tau - tol);
  for (std::size_t i = j > 0 ? j - 1 : 0; i < s.knots.size() && i <= j; ++i)
    if (std::fabs(tau - s.knots[i].t) <= tol) {
      tau = s.knots[i].t;
      break;
    }
  if (tau < 0) tau = 0;
  return tau;
}

Knots pwl_knots(const std::vector<double>& p) {
  Knots k;
  for (std::size_t i = 0; i + 1 < p.size(); i += 2) k.push_back({p[i], p[i + 1]});
  return k;
}

// PWL with ngspice's `r=` (vsrcload.c): from its last time point on, the waveform repeats the
// stretch from the time point r to the last one, period last - r. That stretch, as a periodic
// shape whose phase 0 is at the last point (td = last, never ending), read in place from the
// parameters (a copy of the points at each evaluation cost a 2000-point PWL 15 us a step): the
// points from the first at or after r, shifted to start at 0, those before the period's end,
// then the period's end at the stretch's left limit there. nullopt without a repeat (or a
// stretch of zero length). Before the last point the PWL is as written.
struct ShiftedKnots {
  const std::vector<double>& p;
  std::size_t first, end;  // point indices [first, end)
  double from;
  std::size_t size() const { return end - first; }
  bool empty() const { return end == first; }
  Knot operator[](std::size_t i) const { return {p[2 * (first + i)] - from, p[2 * (first + i) + 1]}; }
  Knot front() const { return (*this)[0]; }
};
struct RepeatKnots {
  ShiftedKnots stretch;  // the points before the period's end
  Knot closing;          // (per, the left limit at per)
  std::size_t size() const { return stretch.size() + 1; }
  bool empty() const { return false; }
  Knot operator[](std::size_t i) const { return i < stretch.size() ? stretch[i] : closing; }
  Knot front() const { return (*this)[0]; }
};
struct PwlRepeatView {
  double td, per;
  RepeatKnots knots;
};

std::optional<PwlRepeatView> pwl_repeat_view(const std::vector<double>& p,
                                             std::optional<double> repeat_from) {
  if (!repeat_from || p.size() < 4) return std::nullopt;
  const double from = *repeat_from;
  const ParamKnots all{p};
  const double last = all[all.size() - 1].t, per = last - from;
  if (!(per > 0)) return std::nullopt;
  const std::size_t first = knots_before(all, from);
  const ShiftedKnots full{p, first, all.size(), from};
  const std::size_t before_end = knots_before(full, per);
  return PwlRepeatView{last, per,
                       RepeatKnots{ShiftedKnots{p, first, first + before_end, from},
                                   Knot{per, pl_left(full, per)}}};
}

// Bounds over [a, b] of a periodic shape (PulseShape or PwlRepeatView) from its phase 0 at s.td
// on (a >= s.td).
template <class Shape>
void periodic_range(const Shape& s, double a, double b, double& lo, double& hi) {
  auto take = [&](double v) {
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  };
  const double tau_a = pulse_phase(s, a);
  if (s.per <= 0) {
    pl_range(s.knots, tau_a, b - s.td, lo, hi);
  } else if (b - a >= s.per) {
    for (std::size_t i = 0; i < s.knots.size(); ++i) take(s.knots[i].v);  // a whole period is covered
  } else {
    double tau_b = tau_a + (b - a);
    if (tau_b <= s.per) {
      pl_range(s.knots, tau_a, tau_b, lo, hi);
    } else {
      pl_range(s.knots, tau_a, s.per, lo, hi);
      pl_range(s.knots, 0.0, tau_b - s.per, lo, hi);
    }
  }
}

// The corners of a periodic shape in (t0, t1), from its phase 0 at s.td on, to `add`.
template <class Shape, typename Add>  // Add: bool(double), false once it takes no more
void periodic_breakpoints(const Shape& s, double t0, double t1, std::size_t limit, const Add& add) {
  if (s.per <= 0) {
    for (std::size_t i = 0; i < s.knots.size(); ++i) add(s.td + s.knots[i].t);
    return;
  }
  std::vector<double> corners;
  for (std::size_t i = 0; i < s.knots.size(); ++i) {
    const Knot n = s.knots[i];
    if (n.t < s.per && (corners.empty() || corners.back() != n.t)) corners.push_back(n.t);
  }
  double kfirst = std::max(0.0, std::floor((t0 - s.td) / s.per));
  double klast = std::ceil((t1 - s.td) / s.per);
  if (!std::isfinite(kfirst) || !std::isfinite(klast) || klast < kfirst) return;  // no period in [t0, t1]
  // An integer count, so a period tiny against t (k beyond 2^53) cannot loop forever.
  const double periods = std::min(klast - kfirst, static_cast<double>(limit));
  for (long long j = 0; j <= static_cast<long long>(periods); ++j)
    for (double c : corners)
      if (!add(s.td + (kfirst + static_cast<double>(j)) * s.per + c)) return;
}

// SIN: VO + VA exp(-THETA tau) sin(2 pi FREQ tau + PHASE), tau = t - TD >= 0.
// LTspice's 7th parameter, Ncycles > 0: the sine stops at `end` = TD + NCYCLES/FREQ and holds
// the value it has there (LTspice XVII's help: "the last voltage when Ncycles have completed";
// Ncycles need not be whole). 0 or absent: it does not stop.
struct SinShape {
  double vo, va, freq, td, theta, phase;  // phase in radians
  double end = INFINITY;
  explicit SinShape(const std::vector<double>& p)
      : vo(param(p, 0)),
        va(param(p, 1)),
        freq(param(p, 2)),
        td(param(p, 3)),
        theta(param(p, 4)),
        phase(param(p, 5) * kPi / 180.0) {
    const double ncycles = param(p, 6);
    if (ncycles > 0 && freq > 0 && std::isfinite(td + ncycles / freq)) end = td + ncycles / freq;
  }
  double value(double t) const {
    if (t < td) return vo + va * std::sin(phase);
    double tau = std::min(t, end) - td;
    return vo + va * std::exp(-theta * tau) * std::sin(2 * kPi * freq * tau + phase);
  }
  double derivative(double t) const {
    if (t < td || t >= end) return 0.0;
    double tau = t - td, w = 2 * kPi * freq, x = w * tau + phase;
    return va * std::exp(-theta * tau) * (w * std::cos(x) - theta * std::sin(x));
  }
};

// EXP: V1 before TD1; then V1 + (V2 - V1)(1 - exp(-(t - TD1)/TAU1)), and from TD2 (when it is
// after TD1; else from TD1) also + (V1 - V2)(1 - exp(-(t - TD2)/TAU2)) (ngspice's vsrcload.c).
// A zero time constant is a jump (as a zero PULSE edge is here): ngspice would use TSTEP.
struct ExpShape {
  double v1, v2, td1, tau1, td2, tau2;
  explicit ExpShape(const std::vector<double>& p)
      : v1(param(p, 0)), v2(param(p, 1)), td1(param(p, 2)), tau1(param(p, 3)), td2(param(p, 4)), tau2(param(p, 5)) {}
  // exp(-x/tau) for x >= 0, with tau = 0 meaning the mode has already decayed.
  static double decay(double x, double tau) { return tau > 0 ? std::exp(-x / tau) : 0.0; }
  bool first(double t) const { return t >= td1; }
  bool second(double t) const { return t >= td1 && t >= td2; }
  double value(double t) const {
    double v = v1;
    if (first(t)) v += (v2 - v1) * (1 - decay(t - td1, tau1));
    if (second(t)) v += (v1 - v2) * (1 - decay(t - td2, tau2));
    return v;
  }
  double value_before(double t) const {  // only a zero time constant jumps
    double v = v1;
    if (t > td1) v += (v2 - v1) * (1 - decay(t - td1, tau1));
    if (t > td1 && t > td2) v += (v1 - v2) * (1 - decay(t - td2, tau2));
    return v;
  }
  double derivative(double t) const {
    double d = 0;
    if (first(t) && tau1 > 0) d += (v2 - v1) * decay(t - td1, tau1) / tau1;
    if (second(t) && tau2 > 0) d += (v1 - v2) * decay(t - td2, tau2) / tau2;
    return d;
  }
  // The second corner: TD2, or TD1 when TD2 is not after it.
  double start2() const { return std::max(td1, td2); }
};

// SFFM (ngspice 40+, vsrcload.c): 0 before TD; then, tau = t - TD,
// VO + VA sin(2 pi FC tau + PHASEC + MDI sin(2 pi FS tau + PHASEM)).
struct SffmShape {
  double vo, va, fc, mdi, fs, td, phasem, phasec;  // phases in radians
  explicit SffmShape(const std::vector<double>& p)
      : vo(param(p, 0)), va(param(p, 1)), fc(param(p, 2)), mdi(param(p, 3)), fs(param(p, 4)), td(param(p, 5)),
        phasem(param(p, 6) * kPi / 180.0), phasec(param(p, 7) * kPi / 180.0) {}
  double value(double t) const {
    if (t < td) return 0.0;
    double tau = t - td;
    return vo + va * std::sin(2 * kPi * fc * tau + phasec + mdi * std::sin(2 * kPi * fs * tau + phasem));
  }
  double derivative(double t) const {
    if (t < td) return 0.0;
    double tau = t - td, wc = 2 * kPi * fc, ws = 2 * kPi * fs;
    double inner = ws * tau + phasem;
    return va * std::cos(wc * tau + phasec + mdi * std::sin(inner)) * (wc + mdi * ws * std::cos(inner));
  }
};

// AM (ngspice 40+, vsrcload.c): 0 before TD; then, tau = t - TD,
// VO + (VMO + VMA sin(2 pi FM tau + PHASEM)) sin(2 pi FC tau + PHASEC).
struct AmShape {
  double vo, vmo, vma, fm, fc, td, phasem, phasec;  // phases in radians
  explicit AmShape(const std::vector<double>& p)
      : vo(param(p, 0)), vmo(param(p, 1)), vma(param(p, 2)), fm(param(p, 3)), fc(param(p, 4)), td(param(p, 5)),
        phasem(param(p, 6) * kPi / 180.0), phasec(param(p, 7) * kPi / 180.0) {}
  double value(double t) const {
    if (t < td) return 0.0;
    double tau = t - td;
    return vo + (vmo + vma * std::sin(2 * kPi * fm * tau + phasem)) * std::sin(2 * kPi * fc * tau + phasec);
  }
  double derivative(double t) const {
    if (t < td) return 0.0;
    double tau = t - td, wm = 2 * kPi * fm, wc = 2 * kPi * fc;
    double m = wm * tau + phasem, c = wc * tau + phasec;
    return vma * wm * std::cos(m) * std::sin(c) + (vmo + vma * std::sin(m)) * wc * std::cos(c);
  }
};

}  // namespace

void Waveform::reresolve(double tstep, double tstop) {
  if (written >= 0) params.resize(written);
  if (frequency_defaulted) params[2] = 0.0;
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
      if (params[2] == 0.0 && tstop > 0) {  // ngspice reads a written 0 as its default too
        params[2] = 1.0 / tstop;
        frequency_defaulted = true;
      }
      params.resize(std::max<std::size_t>(params.size(), 6), 0.0);  // TD THETA PHASE (NCYCLES kept)
      break;
    case Kind::Pulse: {
      if (params.size() < 2) params.resize(2, 0.0);
      const double defaults[] = {0.0 /*TD*/, tstep /*TR*/, tstep /*TF*/, tstop /*PW*/, tstop /*PER*/};
      while (params.size() < 7) params.push_back(defaults[params.size() - 2]);
      break;
    }
    case Kind::Exp:
      if (params.size() < 2) params.resize(2, 0.0);
      if (params.size() < 3) params.push_back(0.0);                // TD1
      if (params.size() < 4) params.push_back(tstep);              // TAU1
      if (params.size() < 5) params.push_back(params[2] + tstep);  // TD2
      if (params.size() < 6) params.push_back(tstep);              // TAU2
      break;
    case Kind::Sffm: {
      if (params.size() < 2) params.resize(2, 0.0);
      if (params.size() < 3) params.push_back(tstop > 0 ? 5.0 / tstop : 0.0);  // FC
      if (params.size() < 4) params.push_back(90.0);                          // MDI
      if (params.size() < 5 || params[4] == 0.0) {                            // FS (0: default)
        params.resize(std::max<std::size_t>(params.size(), 5), 0.0);
        params[4] = tstop > 0 ? 500.0 / tstop : 0.0;
      }
      params.resize(8, 0.0);  // TD PHASEM PHASEC
      double& mdi = params[3];
      if (params[4] != 0.0 && mdi > params[2] / params[4]) mdi = params[2] / params[4];
      if (mdi < 0) mdi = 0;
      break;
    }
    case Kind::Am:
      if (params.size() < 2) params.resize(2, 0.0);
      if (params.size() < 3) params.push_back(1.0);                           // VMA
      if (params.size() < 4) params.push_back(tstop > 0 ? 5.0 / tstop : 0.0);  // FM
      if (params.size() < 5) params.push_back(tstop > 0 ? 500.0 / tstop : 0.0);  // FC
      params.resize(8, 0.0);  // TD PHASEM PHASEC
      break;
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
      if (t < s.td || t >= s.end) return s.v1;  // at `end` itself: the train is over
      return pl_value(s.knots, pulse_phase(s, t));
    }
    case Kind::Pwl:
      if (const std::optional<PwlRepeatView> r = pwl_repeat_view(params, repeat_from); r && t >= r->td)
        return pl_value(r->knots, pulse_phase(*r, t));
      return pl_value(ParamKnots{params}, t);
    case Kind::Exp:
      return ExpShape(params).value(t);
    case Kind::Sffm:
      return SffmShape(params).value(t);
    case Kind::Am:
      return AmShape(params).value(t);
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
      if (t <= s.td || s.over(t)) return s.v1;
      const double tau = pulse_phase(s, t);
      // At the start of a period (other than the first) the left limit is the previous period's end.
      if (tau == 0) return s.per > 0 ? pl_left(s.knots, s.per) : s.v1;
      return pl_left(s.knots, tau);
    }
    case Kind::Pwl:
      if (const std::optional<PwlRepeatView> r = pwl_repeat_view(params, repeat_from); r && t > r->td) {
        const double tau = pulse_phase(*r, t);
        return pl_left(r->knots, tau == 0 ? r->per : tau);  // at a period's start: the last one's end
      }
      return pl_left(ParamKnots{params}, t);
    case Kind::Exp:
      return ExpShape(params).value_before(t);
    case Kind::Sffm:  // 0 up to a TD after the start
    case Kind::Am: {
      const double td = kind == Kind::Sffm ? SffmShape(params).td : AmShape(params).td;
      return td > 0 && t <= td ? 0.0 : value(t);
    }
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
      if (t < s.td || t >= s.end) return 0.0;
      return pl_slope(s.knots, pulse_phase(s, t));
    }
    case Kind::Pwl:
      if (const std::optional<PwlRepeatView> r = pwl_repeat_view(params, repeat_from); r && t >= r->td)
        return pl_slope(r->knots, pulse_phase(*r, t));
      return pl_slope(ParamKnots{params}, t);
    case Kind::Exp:
      return ExpShape(params).derivative(t);
    case Kind::Sffm:
      return SffmShape(params).derivative(t);
    case Kind::Am:
      return AmShape(params).derivative(t);
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
    case Kind::Pwl: {
      const std::optional<PwlRepeatView> r = pwl_repeat_view(params, repeat_from);
      if (!r || t1 < r->td) {
        pl_range(ParamKnots{params}, t0, t1, lo, hi);
        break;
      }
      if (t0 < r->td) pl_range(ParamKnots{params}, t0, r->td, lo, hi);
      periodic_range(*r, std::max(t0, r->td), t1, lo, hi);
      break;
    }
    case Kind::Pulse: {
      PulseShape s = pulse_shape(params);
      if (t0 < s.td || t1 >= s.end) take(s.v1);  // value(end) is V1
      t1 = std::min(t1, s.end);
      if (t1 < s.td || t0 > t1) break;
      periodic_range(s, std::max(t0, s.td), t1, lo, hi);
      break;
    }
    case Kind::Sin: {
      SinShape s(params);
      take(s.value(t0));
      take(s.value(t1));
      t1 = std::min(t1, s.end);  // held from `end` on: value(end) is taken above or below
      take(s.value(t1));
      if (t1 < s.td || t0 > t1) break;
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
    case Kind::Exp: {
      // Monotone on each piece but the last, a sum of two exponentials with at most one extreme.
      ExpShape s(params);
      for (double t : {t0, t1}) take(s.value(t));
      for (double c : {s.td1, s.start2()})
        if (c > t0 && c < t1) take(s.value(c));
      if (s.tau1 > 0 && s.tau2 > 0 && s.tau1 != s.tau2) {
        // d/dt [-(V2-V1) e^{-(t-TD1)/TAU1} + (V2-V1) e^{-(t-TD2)/TAU2}] = 0: e1/TAU1 = e2/TAU2
        double t = (std::log(s.tau1 / s.tau2) + s.td2 / s.tau2 - s.td1 / s.tau1) / (1 / s.tau2 - 1 / s.tau1);
        if (t > std::max(t0, s.start2()) && t < t1) take(s.value(t));
      }
      break;
    }
    case Kind::Sffm: {
      SffmShape s(params);
      if (t0 < s.td) take(0.0);
      if (t1 >= s.td) {
        take(s.vo - std::fabs(s.va));
        take(s.vo + std::fabs(s.va));
      }
      break;
    }
    case Kind::Am: {
      AmShape s(params);
      if (t0 < s.td) take(0.0);
      if (t1 >= s.td) {
        take(s.vo - std::fabs(s.vmo) - std::fabs(s.vma));
        take(s.vo + std::fabs(s.vmo) + std::fabs(s.vma));
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
    return out.size() < kMaxBreakpoints;
  };
  switch (kind) {
    case Kind::Dc:
      break;
    case Kind::Sin:
      add(SinShape(params).td);
      add(SinShape(params).end);
      break;
    case Kind::Exp: {
      ExpShape e(params);
      add(e.td1);
      add(e.start2());
      break;
    }
    case Kind::Sffm:
      add(SffmShape(params).td);
      break;
    case Kind::Am:
      add(AmShape(params).td);
      break;
    case Kind::Pwl:
      for (const Knot& n : pwl_knots(params)) add(n.t);
      if (const std::optional<PwlRepeatView> r = pwl_repeat_view(params, repeat_from))
        periodic_breakpoints(*r, t0, t1, kMaxBreakpoints, add);
      break;
    case Kind::Pulse: {
      PulseShape s = pulse_shape(params);
      add(s.td);
      add(s.end);
      t1 = std::min(t1, s.end);  // `add` reads it: no corner after the train
      periodic_breakpoints(s, t0, t1, kMaxBreakpoints, add);
      break;
    }
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

double Waveform::sine_end() const { return kind == Kind::Sin ? SinShape(params).end : INFINITY; }

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
      if (repeat_from) out += " r=" + fmt(*repeat_from);
      break;
    case Kind::Exp:
      list("EXP", params.size());
      break;
    case Kind::Sffm:
      list("SFFM", params.size());
      break;
    case Kind::Am:
      list("AM", params.size());
      break;
  }
  return out;
}

Waveform Waveform::scaled(double m) const {
  Waveform w = *this;
  w.dc *= m;
  auto scale = [&](std::size_t i) {
    if (i < w.params.size()) w.params[i] *= m;
  };
  switch (kind) {
    case Kind::Dc:
      break;
    case Kind::Sin:    // VO VA
    case Kind::Pulse:  // V1 V2
    case Kind::Exp:    // V1 V2
    case Kind::Sffm:   // VO VA
      scale(0);
      scale(1);
      break;
    case Kind::Am:  // VO VMO VMA (VMA's default 1 is written first, so it is scaled too)
      if (w.params.size() == 2) w.params.push_back(1.0);
      scale(0);
      scale(1);
      scale(2);
      break;
    case Kind::Pwl:
      for (std::size_t i = 1; i < w.params.size(); i += 2) scale(i);
      break;
  }
  return w;
}

}  // namespace lcs
