#include "tests/random/waveform_compare.h"

#include <algorithm>
#include <cmath>

namespace lcs::random_circuit {

namespace {

// Linear interpolation in a run's rows at times that never decrease between calls (one pass).
class Cursor {
 public:
  explicit Cursor(const MethodRun& run) : run_(run) {}
  // Sets the weights for time t (inside the run's span, or clamped to it).
  void seek(double t) {
    const std::vector<double>& ts = run_.times;
    while (i_ + 1 < ts.size() && ts[i_ + 1] <= t) ++i_;
    if (i_ + 1 >= ts.size() || t <= ts[i_]) {
      w_ = 0;
      return;
    }
    const double t0 = ts[i_], t1 = ts[i_ + 1];
    w_ = (t - t0) / (t1 - t0);
    // A time equal to a row's to rounding is that row's (k h against the reference's k h).
    if (w_ <= 1e-9) w_ = 0;
    if (w_ >= 1 - 1e-9) w_ = 1;
  }
  double value(int col) const {
    const double a = run_.rows[i_](col);
    return w_ == 0 ? a : (1 - w_) * a + w_ * run_.rows[i_ + 1](col);
  }

 private:
  const MethodRun& run_;
  std::size_t i_ = 0;
  double w_ = 0;
};

// The other run read at a time, plain or as the mean of its values half a step before and after
// (with linear interpolation, the weights 1/4, 1/2, 1/4 on three consecutive rows at a grid time).
class Reader {
 public:
  Reader(const MethodRun& run, double half) : a_(run), b_(run), half_(half), end_(run.times.back()) {}
  void seek(double t) {
    a_.seek(std::max(0.0, t - half_));
    b_.seek(std::min(end_, t + half_));
  }
  double value(int col) const { return half_ > 0 ? 0.5 * (a_.value(col) + b_.value(col)) : a_.value(col); }

 private:
  Cursor a_, b_;
  double half_, end_;
};

bool is_current(const std::string& probe) { return !probe.empty() && probe[0] == 'i'; }

}  // namespace

std::vector<ProbeDiscrepancy> discrepancies(const MethodRun& reference, const MethodRun& other,
                                            const CompareOptions& options) {
  const double shift = options.shift;
  const int probes = static_cast<int>(reference.names.size());
  std::vector<ProbeDiscrepancy> out(static_cast<size_t>(probes));
  if (reference.rows.empty() || other.rows.empty()) return out;

  double widest[2] = {0, 0}, largest[2] = {0, 0};  // by kind: [0] voltages, [1] currents
  std::vector<double> lo(out.size(), INFINITY), hi(out.size(), -INFINITY);
  for (const Eigen::VectorXd& row : reference.rows)
    for (int p = 0; p < probes; ++p) {
      lo[static_cast<size_t>(p)] = std::min(lo[static_cast<size_t>(p)], row(p));
      hi[static_cast<size_t>(p)] = std::max(hi[static_cast<size_t>(p)], row(p));
    }
  for (int p = 0; p < probes; ++p) {
    const size_t q = static_cast<size_t>(p);
    const int kind = is_current(reference.names[q]);
    widest[kind] = std::max(widest[kind], hi[q] - lo[q]);
    largest[kind] = std::max({largest[kind], std::abs(lo[q]), std::abs(hi[q])});
  }
  for (int p = 0; p < probes; ++p) {
    const size_t q = static_cast<size_t>(p);
    const int kind = is_current(reference.names[q]);
    out[q].probe = reference.names[q];
    out[q].scale = std::max({hi[q] - lo[q], 1e-3 * widest[kind], 1e-5 * largest[kind], kind ? 1e-12 : 1e-9});
  }

  // Every reference row within the other run's span.
  const double end = other.times.back();
  const double half = options.average_neighbours ? 0.5 * other.step : 0.0;
  Reader at(other, half), before(other, half), after(other, half);
  std::vector<double> sum(out.size(), 0.0);
  long count = 0;
  for (size_t k = 0; k < reference.times.size() && reference.times[k] <= end; ++k) {
    const double t = reference.times[k];
    at.seek(t);
    before.seek(std::max(0.0, t - shift));
    after.seek(std::min(end, t + shift));
    ++count;
    for (int p = 0; p < probes; ++p) {
      const size_t q = static_cast<size_t>(p);
      // The other run's value nearest the reference among t - shift, t, t + shift.
      const double r = reference.rows[k](p);
      double v = at.value(p);
      if (shift > 0)
        for (const Reader* c : {&before, &after})
          if (std::abs(c->value(p) - r) < std::abs(v - r)) v = c->value(p);
      const double e = std::abs(v - r) / out[q].scale;
      sum[q] += e;
      if (e > out[q].max) {
        out[q].max = e;
        out[q].worst_time = t;
        out[q].reference_value = r;
        out[q].other_value = v;
      }
    }
  }
  for (size_t q = 0; q < out.size(); ++q) out[q].mean = count > 0 ? sum[q] / static_cast<double>(count) : 0;
  return out;
}

}  // namespace lcs::random_circuit
