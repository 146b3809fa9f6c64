// The past of the waves that travel along transmission lines (Stewart 1.3.3): what makes a
// circuit with lines a convolution complementarity problem (4.6) rather than an LCS.
//
// Each history input u_k of the LCS is a wave that left a line port `delay` seconds earlier:
//   u_k(t) = a_k(t - delay),   a_k = g x + h z + j u   (a row of the model, at the earlier time).
// The integrators record a_k after every accepted step (LcsProblem::accept); before the first
// record (t < t0) the wave holds the value it had when the run began (the line's DC state, or
// its IC= with UIC). A jump of a_k (a source edge, a diode switching with RON = 0) is recorded as
// two samples at one time: reads at that instant take the later one, and no interpolant spans it.
// Reads between samples interpolate by a polynomial of the integrator's order through the
// nearest samples of the same smooth piece (so the history is as accurate as the steps), or,
// for the event method, on the exact past of each accepted segment (event_driven.cpp).
#pragma once

#include <deque>
#include <functional>
#include <limits>
#include <vector>

namespace lcs {

class DelayHistory {
 public:
  explicit DelayHistory(std::vector<double> delays = {});

  int size() const { return static_cast<int>(delays_.size()); }
  double delay(int k) const { return delays_[k]; }

  // Forgets every sample: a_k holds before[k] until the first record.
  void reset(const std::vector<double>& before);
  // Degree of the interpolant through recorded samples (1 linear ... 5); the run's method sets it.
  void set_degree(int degree) { degree_ = degree; }
  // Instants where the waves bend (the start, source corners, and their arrivals a delay, two
  // delays, ... later): no interpolant through samples spans one, so a method whose steps land
  // on them keeps its order across a wavefront. At most kMaxKinks are kept (beyond that,
  // interpolants may span a bend: a local error of the step's size squared).
  static constexpr size_t kMaxKinks = 100000;
  void add_kinks(const std::vector<double>& corners, double t_end);

  // Appends a_k(t) for every k (t not before the last record; equal t: a jump).
  void record(double t, const std::vector<double>& values);
  // The exact past, where a method knows it (event): a_k(s) and its slope for s in [t0, t1] of a
  // segment recorded with record_segment. Reads inside such a segment call it instead of
  // interpolating samples (a read at a segment boundary takes the later segment). A method that
  // records segments forgets them (forget_segments) before the objects they refer to go.
  using Segment = std::function<void(double s, std::vector<double>& values, std::vector<double>& slopes)>;
  void record_segment(double t0, double t1, Segment exact);
  void forget_segments() {
    segments_.clear();
    cached_segment_ = nullptr;
  }

  // Breaks: instants where the waves may jump or bend (the event method's mode switches and
  // source corners), each arriving `delay_k` later in history input k. next_arrival() returns
  // the earliest arrival in (t, t_end] of a break where wave k did jump or bend by more than
  // `tol` of the waves' size (a jump, or a change of slope over one delay), so that a wavefront
  // that has died away stops making breakpoints; +inf when none.
  // At most kMaxBreaks are kept in flight (a nearly lossless line network multiplies its
  // wavefronts; past that, bends are found by the event method halving its steps).
  static constexpr size_t kMaxBreaks = 512;
  void mark_break(double t);
  double next_arrival(double t, double t_end, double tol);

  // a_k at time s (s may precede the first record: the value before). `side` (exact segments
  // only): the segment is the one holding s + side, evaluated at s — a one-sided limit where
  // s is within rounding of a segment boundary (a jump arriving).
  double wave(int k, double s, double side = 0) const;
  // u_k(t) = a_k(t - delay_k).
  double value(int k, double t, double side = 0) const { return wave(k, t - delays_[k], side); }
  double magnitude() const { return size_; }  // the largest |a_k| recorded (or held before the run)
  const std::deque<double>& times() const { return times_; }  // the recorded instants (kept ones)

 private:
  struct ExactSegment {
    double t0, t1;
    Segment exact;
  };
  struct Break {
    double t;
    std::vector<char> significant;  // per wave; empty until judged (both sides recorded)
  };
  bool judge(Break& b, double tol);
  double size_ = 0;  // the largest |a_k| recorded
  std::vector<double> delays_;
  double shortest_ = std::numeric_limits<double>::infinity(), longest_ = 0;
  std::vector<double> before_;
  int degree_ = 1;
  std::deque<double> times_;
  std::deque<std::vector<double>> values_;  // values_[i][k] = a_k(times_[i])
  std::deque<ExactSegment> segments_;
  std::deque<Break> breaks_;
  std::vector<double> kinks_;  // sorted
  mutable std::vector<double> scratch_, slopes_;
  mutable double cached_s_ = 0;
  mutable const void* cached_segment_ = nullptr;
  void trim();
};

}  // namespace lcs
