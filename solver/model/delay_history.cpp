#include "solver/model/delay_history.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace lcs {

DelayHistory::DelayHistory(std::vector<double> delays)
    : delays_(std::move(delays)), before_(delays_.size(), 0.0) {
  for (double d : delays_) {
    shortest_ = std::min(shortest_, d);
    longest_ = std::max(longest_, d);
  }
}

void DelayHistory::reset(const std::vector<double>& before) {
  before_ = before;
  before_.resize(delays_.size(), 0.0);
  times_.clear();
  values_.clear();
  segments_.clear();
  cached_segment_ = nullptr;
  breaks_.clear();
  kinks_.clear();
  size_ = 0;
  for (double b : before_) size_ = std::max(size_, std::abs(b));
}

void DelayHistory::record(double t, const std::vector<double>& values) {
  if (!times_.empty() && t < times_.back()) t = times_.back();  // rounding of a method's clock
  if (!times_.empty() && t == times_.back()) {
    bool same = true;
    for (size_t k = 0; k < values.size(); ++k)
      if (values[k] != values_.back()[k]) same = false;
    if (same) return;  // the same instant recorded twice
  }
  times_.push_back(t);
  values_.push_back(values);
  for (double v : values) size_ = std::max(size_, std::abs(v));
  trim();
}

void DelayHistory::record_segment(double t0, double t1, Segment exact) {
  if (!segments_.empty() && t0 < segments_.back().t1) t0 = segments_.back().t1;
  if (t1 <= t0) return;
  segments_.push_back({t0, t1, std::move(exact)});
}

// Samples older than every delay (plus the stencil an interpolant needs) are never read again,
// where "now" may trail the newest record by one step: the smooth method records IDA's step and
// then reads rows (and restarts) inside it, and its steps are at most the shortest delay. Kept
// from one longest delay behind the newest record, the rows inside a long step on a plateau read
// trimmed samples and got the waves held before the run (tline_clamp_receiver, --step 1e-12).
void DelayHistory::trim() {
  if (times_.size() < 4096) return;
  const double keep_from = times_.back() - 1.01 * (longest_ + shortest_);
  size_t drop = 0;
  while (drop + 8 < times_.size() && times_[drop + 8] < keep_from) ++drop;
  if (drop < times_.size() / 2) return;  // trims in bulk, amortised O(1) per record
  times_.erase(times_.begin(), times_.begin() + drop);
  values_.erase(values_.begin(), values_.begin() + drop);
  while (!segments_.empty() && segments_.front().t1 < keep_from) segments_.pop_front();
  cached_segment_ = nullptr;
  while (!breaks_.empty() && breaks_.front().t < keep_from) breaks_.pop_front();
}

double DelayHistory::wave(int k, double s, double side) const {
  if (!segments_.empty() && s + side >= segments_.front().t0) {
    auto it = std::upper_bound(segments_.begin(), segments_.end(), s + side,
                               [](double v, const ExactSegment& seg) { return v < seg.t0; });
    --it;  // the last segment starting at or before s
    if (s + side <= it->t1) {
      if (s != cached_s_ || &*it != cached_segment_) {  // waves of one delay are read in turn
        scratch_.resize(delays_.size());
        slopes_.resize(delays_.size());
        it->exact(s, scratch_, slopes_);
        cached_s_ = s;
        cached_segment_ = &*it;
      }
      return scratch_[k];
    }
  }
  if (times_.empty() || s < times_.front()) return before_[k];
  // i: the last sample at or before s (the later of a jump's two samples at its instant).
  const long n = static_cast<long>(times_.size());
  long i = static_cast<long>(std::upper_bound(times_.begin(), times_.end(), s) - times_.begin()) - 1;
  if (times_[i] == s || n == 1) return values_[i][k];
  // The smooth piece around i (no two samples of one instant inside it, no bend between), as far
  // as a stencil can reach.
  double bend_lo = -1e300, bend_hi = 1e300;
  if (!kinks_.empty()) {
    auto it = std::upper_bound(kinks_.begin(), kinks_.end(), s);
    if (it != kinks_.end()) bend_hi = *it;
    if (it != kinks_.begin()) bend_lo = *std::prev(it);
  }
  long lo = i, hi = i;
  while (lo > 0 && i - lo <= degree_ && times_[lo - 1] < times_[lo] && times_[lo - 1] >= bend_lo) --lo;
  while (hi + 1 < n && hi - i <= degree_ && times_[hi + 1] > times_[hi] && times_[hi + 1] <= bend_hi) ++hi;
  // The degree+1 samples of the piece nearest to the interval [t_i, t_i+1] holding s: i and i+1
  // first, when both are in it, then outwards by distance from the interval's midpoint. The
  // stencil depends on the interval, not on s, so the interpolant is continuous in s (each
  // interval's polynomial passes through both its ends). Chosen by distance from s, the linear
  // stencil flipped to (i-1, i) past the midpoint of t_i-1 and t_i+1 and extrapolated: a jump
  // in the input, at which IDA's steps shrank below rounding of t and never passed
  // (tline_lossy_rectifier, --method smooth, t = 0.921 us).
  const long want = std::min<long>(degree_ + 1, hi - lo + 1);
  long a = i, b = i;
  if (want >= 2 && i < hi) b = i + 1;
  const double mid = 0.5 * (times_[a] + times_[b]);
  while (b - a + 1 < want) {
    const bool right_ok = b < hi, left_ok = a > lo;
    if (right_ok && (!left_ok || times_[b + 1] - mid <= mid - times_[a - 1])) ++b;
    else --a;
  }
  // Lagrange form (a handful of points).
  double sum = 0;
  for (long p = a; p <= b; ++p) {
    double w = 1;
    for (long q = a; q <= b; ++q)
      if (q != p) w *= (s - times_[q]) / (times_[p] - times_[q]);
    sum += w * values_[p][k];
  }
  return sum;
}

void DelayHistory::add_kinks(const std::vector<double>& corners, double t_end) {
  std::vector<double> delays = delays_;
  std::sort(delays.begin(), delays.end());
  delays.erase(std::unique(delays.begin(), delays.end()), delays.end());
  for (double c : corners)
    for (double d : delays)
      for (double t = c; t <= t_end && kinks_.size() < kMaxKinks; t += d) kinks_.push_back(t);
  std::sort(kinks_.begin(), kinks_.end());
  kinks_.erase(std::unique(kinks_.begin(), kinks_.end()), kinks_.end());
}

void DelayHistory::mark_break(double t) {
  if (!breaks_.empty() && breaks_.back().t >= t) return;
  if (breaks_.size() >= kMaxBreaks) return;  // the fits find the rest by halving their steps
  breaks_.push_back({t, {}});
}

// Wave k jumps or bends at b: its values and slopes on the two segments meeting there.
bool DelayHistory::judge(Break& b, double tol) {
  auto left = segments_.end(), right = segments_.end();
  auto after = std::upper_bound(segments_.begin(), segments_.end(), b.t,
                                [](double v, const ExactSegment& seg) { return v < seg.t0; });
  if (after != segments_.begin()) {
    auto at = std::prev(after);  // the last segment starting at or before b
    if (b.t < at->t1) right = at;
    if (at->t0 < b.t && b.t <= at->t1) left = at;
    else if (at != segments_.begin() && b.t <= std::prev(at)->t1) left = std::prev(at);
  }
  const size_t n = delays_.size();
  if (right == segments_.end()) return false;  // not yet recorded past b: judged later
  std::vector<double> vl(n), sl(n), vr(n), sr(n);
  if (left != segments_.end()) {
    left->exact(b.t, vl, sl);
  } else {  // the first segment: before it the waves held their values before the run
    vl = before_;
    sl.assign(n, 0.0);
  }
  right->exact(b.t, vr, sr);
  b.significant.assign(n, 0);
  for (size_t k = 0; k < n; ++k) {
    const double change = std::abs(vr[k] - vl[k]) + delays_[k] * std::abs(sr[k] - sl[k]);
    b.significant[k] = change > tol * std::max(size_, 1e-300);
  }
  return true;
}

double DelayHistory::next_arrival(double t, double t_end, double tol) {
  while (!breaks_.empty() && breaks_.front().t + longest_ <= t) breaks_.pop_front();  // arrived everywhere
  double best = std::numeric_limits<double>::infinity();
  for (Break& b : breaks_) {
    bool any = false;
    for (double d : delays_) any = any || (b.t + d > t && b.t + d <= t_end);
    if (!any) continue;
    if (b.significant.empty() && !judge(b, tol)) {  // not recorded past b yet: assume it matters
      if (b.t + shortest_ > t) best = std::min(best, b.t + shortest_);
      continue;
    }
    for (size_t k = 0; k < delays_.size(); ++k)
      if (b.significant[k] && b.t + delays_[k] > t && b.t + delays_[k] <= t_end) best = std::min(best, b.t + delays_[k]);
  }
  return best;
}

}  // namespace lcs
