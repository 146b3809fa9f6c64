#include "cli/measure.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <stdexcept>

namespace lcs {
namespace {

std::string number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", x);
  return buf;
}

std::string quoted(const std::string& s) { return "'" + s + "'"; }

// Thrown inside one measure's evaluation: why it cannot be computed.
struct Failure {
  std::string why;
};

const std::vector<double>& column(const MeasureWaveforms& w, const Probe& p) {
  auto it = w.columns.find(p.name());
  if (it == w.columns.end()) throw Failure{"no waveform was recorded for " + p.name()};
  return it->second;
}

// The waveform at time x, linear between rows (x within the run).
double interpolate(const std::vector<double>& t, const std::vector<double>& y, double x) {
  const std::size_t n = t.size();
  if (n == 1) return y[0];
  std::size_t k = static_cast<std::size_t>(std::upper_bound(t.begin(), t.end(), x) - t.begin());
  k = k == 0 ? 0 : std::min(k - 1, n - 2);
  if (x == t[k]) return y[k];
  if (x == t[k + 1]) return y[k + 1];
  return y[k] + (x - t[k]) * (y[k + 1] - y[k]) / (t[k + 1] - t[k]);
}

// The part of the run in [from, to] (clipped to the run): its rows inside, and its ends as
// interpolated points.
struct Window {
  double from = 0, to = 0;
  std::vector<double> t;
  std::vector<std::size_t> rows;  // for each point inside, its row; the ends are interpolated

  std::vector<double> values(const std::vector<double>& times, const std::vector<double>& y) const {
    std::vector<double> out;
    out.reserve(t.size());
    out.push_back(interpolate(times, y, from));
    for (std::size_t r : rows) out.push_back(y[r]);
    if (to > from) out.push_back(interpolate(times, y, to));
    return out;
  }
};

Window window(const MeasureWaveforms& w, double from, std::optional<double> to) {
  const std::vector<double>& t = w.times;
  if (t.empty()) throw Failure{"the run has no rows"};
  const double lo = std::max(from, t.front()), hi = std::min(to.value_or(t.back()), t.back());
  if (lo > hi)
    throw Failure{"no part of the run (t = " + number(t.front()) + " to " + number(t.back()) + " s) lies in the window " +
                  (to ? "t = " + number(from) + " to " + number(*to) + " s" : "t >= " + number(from) + " s")};
  Window win;
  win.from = lo;
  win.to = hi;
  win.t.push_back(lo);
  for (std::size_t k = static_cast<std::size_t>(std::upper_bound(t.begin(), t.end(), lo) - t.begin());
       k < t.size() && t[k] < hi; ++k) {
    win.t.push_back(t[k]);
    win.rows.push_back(k);
  }
  if (hi > lo) win.t.push_back(hi);
  return win;
}

double trapezoid(const std::vector<double>& t, const std::vector<double>& y) {
  double sum = 0;
  for (std::size_t k = 1; k < t.size(); ++k) sum += 0.5 * (y[k] + y[k - 1]) * (t[k] - t[k - 1]);
  return sum;
}

double statistic(const Measure& m, const MeasureWaveforms& w) {
  const Window win = window(w, m.from, m.to);
  const std::vector<double> y = win.values(w.times, column(w, m.probe));
  const double span = win.to - win.from;
  switch (m.kind) {
    case Measure::Kind::Integ:
      return trapezoid(win.t, y);
    case Measure::Kind::Avg:
    case Measure::Kind::Rms: {
      if (!(span > 0)) throw Failure{"the window t = " + number(win.from) + " to " + number(win.to) + " s has no length"};
      if (m.kind == Measure::Kind::Avg) return trapezoid(win.t, y) / span;
      // The exact integral of the square of the waveform, linear between the points: a segment
      // from a to b over dt contributes dt (a^2 + a b + b^2) / 3.
      double squares = 0;
      for (std::size_t k = 1; k < y.size(); ++k)
        squares += (win.t[k] - win.t[k - 1]) * (y[k - 1] * y[k - 1] + y[k - 1] * y[k] + y[k] * y[k]) / 3;
      return std::sqrt(squares / span);
    }
    default:
      break;
  }
  // ngspice keeps the last of equal extremes (its MIN_AT/MAX_AT report the latest time).
  std::size_t lo = 0, hi = 0;
  for (std::size_t k = 1; k < y.size(); ++k) {
    if (y[k] <= y[lo]) lo = k;
    if (y[k] >= y[hi]) hi = k;
  }
  switch (m.kind) {
    case Measure::Kind::Min: return y[lo];
    case Measure::Kind::Max: return y[hi];
    case Measure::Kind::MinAt: return win.t[lo];
    case Measure::Kind::MaxAt: return win.t[hi];
    default: return y[hi] - y[lo];  // PP
  }
}

// The time of the crossing `c` asks for.
double crossing_time(const MeasureCrossing& c, const MeasureWaveforms& w) {
  if (c.at) return *c.at;
  const Window win = window(w, std::max(c.from, c.td), c.to);
  const std::vector<double> y1 = win.values(w.times, column(w, c.probe));
  const std::vector<double> y2 =
      c.other ? win.values(w.times, column(w, *c.other)) : std::vector<double>(win.t.size(), c.level);
  const std::vector<double>& t = win.t;
  // ngspice 39's interpolation on [k-1, k], also for a transition it counted on the window's first
  // interval (then [1, 2] is extrapolated back). A waveform level with the level on both rows has
  // no crossing time (ngspice divides 0 by 0 and fails the measure).
  auto time_on = [&](std::size_t k) {
    const double slope = (y1[k] - y1[k - 1]) - (y2[k] - y2[k - 1]);
    if (slope == 0)
      throw Failure{c.probe.name() + " is level with " + (c.other ? c.other->name() : number(c.level)) + " from t = " +
                    number(t[k - 1]) + " to " + number(t[k]) +
                    " s where the crossing asked for is counted (ngspice fails such a measure)"};
    return t[k - 1] + (y2[k - 1] - y1[k - 1]) * (t[k] - t[k - 1]) / slope;
  };
  using Edge = MeasureCrossing::Edge;
  int rises = 0, falls = 0, crosses = 0;
  std::optional<std::size_t> last;  // the interval of the last transition LAST asks for
  auto matched = [&] {
    switch (c.edge) {
      case Edge::Cross: return !c.last && crosses == c.count;
      case Edge::Rise: return !c.last && rises == c.count;
      case Edge::Fall: return !c.last && falls == c.count;
      default: return false;
    }
  };
  // ngspice 39's counting (com_measure2.c): the second point of the window sets the side, below
  // when y1 < y2, else above; a rise is counted there when the first point is not above
  // (y1 <= y2), never a fall. From the third point on, below -> above when y1 >= y2 (a rise) and
  // above -> below when y1 <= y2 (a fall): a waveform sitting on the level changes side on every
  // row. After each of these points the counts are compared with the one asked for, and a
  // transition there is the one the default (the first) and LAST take; those counted on the
  // first interval never are.
  if (t.size() >= 2) {
    bool below = y1[1] < y2[1];
    if (!below && y1[0] <= y2[0]) ++rises, ++crosses;
    for (std::size_t k = 2; k < t.size(); ++k) {
      bool rise = false, fall = false;
      if (below && y1[k] >= y2[k]) rise = true;
      else if (!below && y1[k] <= y2[k]) fall = true;
      if (rise || fall) {
        below = fall;
        ++crosses;
        ++(rise ? rises : falls);
      }
      if (matched()) return time_on(k);
      if (!(rise || fall)) continue;
      if (c.edge == Edge::First) return time_on(k);
      if (c.last && (c.edge == Edge::Cross || rise == (c.edge == Edge::Rise))) last = k;
    }
  }
  if (last) return time_on(*last);
  const std::string level = c.other ? c.other->name() : number(c.level);
  const std::string between = " between t = " + number(win.from) + " and " + number(win.to) + " s";
  const char* verb = c.edge == Edge::Rise ? "rises through " : c.edge == Edge::Fall ? "falls through " : "crosses ";
  const int seen = c.edge == Edge::Rise ? rises : c.edge == Edge::Fall ? falls : crosses;
  if (seen == 0) throw Failure{c.probe.name() + " never " + verb + level + between};
  if (c.last || c.edge == Edge::First)  // seen: the rise on the first interval
    throw Failure{c.probe.name() + " " + verb + level + between + " only on the window's first interval, which " +
                  (c.last ? "LAST" : "the first crossing") + " does not take (ngspice 39)"};
  const char* key = c.edge == Edge::Rise ? "RISE=" : c.edge == Edge::Fall ? "FALL=" : "CROSS=";
  throw Failure{c.probe.name() + " " + verb + level + " only " + std::to_string(seen) +
                (seen == 1 ? " time" : " times") + between + " (" + key + std::to_string(c.count) + ")"};
}

double find_at(const Probe& p, double at, const MeasureWaveforms& w) {
  const std::vector<double>& t = w.times;
  if (t.empty()) throw Failure{"the run has no rows"};
  if (at < t.front() || at > t.back())
    throw Failure{"AT=" + number(at) + " s is outside the run (t = " + number(t.front()) + " to " + number(t.back()) +
                  " s)"};
  return interpolate(t, column(w, p), at);
}

double evaluate(const Measure& m, const MeasureWaveforms& w) {
  switch (m.kind) {
    case Measure::Kind::FindAt:
      return find_at(m.probe, m.at, w);
    case Measure::Kind::FindWhen:
      return find_at(m.probe, crossing_time(m.when, w), w);
    case Measure::Kind::When:
      return crossing_time(m.when, w);
    case Measure::Kind::Param:
      throw Failure{"a PARAM is computed from the other measures' results"};
    case Measure::Kind::TrigTarg: {
      double trig = 0, targ = 0;
      try {
        trig = crossing_time(m.when, w);
      } catch (const Failure& f) {
        throw Failure{"TRIG: " + f.why};
      }
      try {
        targ = crossing_time(m.targ, w);
      } catch (const Failure& f) {
        throw Failure{"TARG: " + f.why};
      }
      return targ - trig;
    }
    default:
      return statistic(m, w);
  }
}

}  // namespace

MeasureResult evaluate_measure(const Measure& measure, const MeasureWaveforms& waveforms) {
  MeasureResult r;
  r.name = measure.name;
  try {
    const double v = evaluate(measure, waveforms);
    if (std::isfinite(v)) r.value = v;
    else r.failure = "the result is not a finite number";
  } catch (const Failure& f) {
    r.failure = f.why;
  }
  return r;
}

// ngspice 39's order: every other measure first, then the PARAMs in card order, each seeing the
// results above it and the other measures below it.
std::vector<MeasureResult> evaluate_measures(const std::vector<Measure>& measures, const MeasureWaveforms& waveforms) {
  std::vector<MeasureResult> out(measures.size());
  for (std::size_t k = 0; k < measures.size(); ++k)
    if (measures[k].kind != Measure::Kind::Param) out[k] = evaluate_measure(measures[k], waveforms);
  for (std::size_t k = 0; k < measures.size(); ++k) {
    const Measure& m = measures[k];
    if (m.kind != Measure::Kind::Param) continue;
    MeasureResult& r = out[k];
    r.name = m.name;
    const MeasureExpression::MeasureLookup lookup = [&](const std::string& name) -> std::optional<double> {
      for (std::size_t j = 0; j < measures.size(); ++j) {
        if (measures[j].name != name) continue;
        if (j == k) throw std::runtime_error("it names its own measure " + quoted(name));
        if (measures[j].kind == Measure::Kind::Param && j > k)
          throw std::runtime_error("measure " + quoted(name) +
                                   " is a PARAM further down (PARAMs are computed in card order, as in ngspice)");
        if (!out[j].value) throw std::runtime_error("measure " + quoted(name) + " failed");
        return out[j].value;
      }
      return std::nullopt;
    };
    try {
      const double v = m.expression.evaluate(lookup);
      if (std::isfinite(v)) r.value = v;
      else r.failure = "the result is not a finite number";
    } catch (const std::runtime_error& e) {
      r.failure = e.what();
    }
  }
  return out;
}

std::vector<Probe> measure_probes(const std::vector<Measure>& measures) {
  std::vector<Probe> out;
  std::set<std::string> seen;
  auto add = [&](const Probe& p) {
    if (seen.insert(p.name()).second) out.push_back(p);
  };
  auto add_crossing = [&](const MeasureCrossing& c) {
    if (c.at) return;
    add(c.probe);
    if (c.other) add(*c.other);
  };
  for (const Measure& m : measures) {
    switch (m.kind) {
      case Measure::Kind::Param:
        break;
      case Measure::Kind::When:
        add_crossing(m.when);
        break;
      case Measure::Kind::TrigTarg:
        add_crossing(m.when);
        add_crossing(m.targ);
        break;
      case Measure::Kind::FindWhen:
        add(m.probe);
        add_crossing(m.when);
        break;
      default:
        add(m.probe);
    }
  }
  return out;
}

void report_measures(const std::vector<MeasureResult>& results, std::ostream& out) {
  for (const MeasureResult& r : results) {
    if (r.value) {
      char buf[64];
      std::snprintf(buf, sizeof buf, "%.9e", *r.value);
      out << r.name << " = " << buf << "\n";
    } else {
      out << "lcspice: warning: .meas " << r.name << " failed: " << r.failure << "\n";
    }
  }
}

MeasureTap::MeasureTap(OutputSink& next, std::size_t visible, std::vector<std::string> needed)
    : next_(next), visible_(visible), needed_(std::move(needed)) {}

void MeasureTap::begin(const std::vector<std::string>& names) {
  const std::size_t shown = std::min(visible_, names.size());
  next_.begin(std::vector<std::string>(names.begin(), names.begin() + static_cast<std::ptrdiff_t>(shown)));
  waveforms_ = MeasureWaveforms{};
  taps_.clear();
  for (const std::string& name : needed_) {
    auto it = std::find(names.begin(), names.end(), name);
    if (it == names.end()) continue;  // evaluate_measure reports it
    taps_.emplace_back(static_cast<std::size_t>(it - names.begin()), &waveforms_.columns[name]);
  }
}

void MeasureTap::row(double t, const Eigen::VectorXd& values) {
  waveforms_.times.push_back(t);
  for (auto& [k, recording] : taps_) recording->push_back(values[static_cast<Eigen::Index>(k)]);
  if (static_cast<std::size_t>(values.size()) <= visible_) {
    next_.row(t, values);
    return;
  }
  shown_ = values.head(static_cast<Eigen::Index>(visible_));
  next_.row(t, shown_);
}

}  // namespace lcs
