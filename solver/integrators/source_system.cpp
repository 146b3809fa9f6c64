#include "solver/integrators/source_system.h"

#include <algorithm>
#include <cfloat>
#include <cmath>

namespace lcs {

namespace {
constexpr double kTwoPi = 6.283185307179586476925;
int kind_dimension(char k) { return k == 'c' ? 1 : k == 'r' ? 2 : k == 's' ? 3 : kHistoryDegree + 1; }

// Chebyshev-Lobatto points of [0, 1] (both ends among them) and the monomial (Vandermonde)
// system on them, factorised once. The ends make each step's polynomial start where the last one
// ended (the exact past at the shared instant, one-sided limits): a fit that left a jump at
// every step would send it down the line, and a line between nearly reflecting ends brings it
// back into the middle of a later step, where the next fit makes two of it (rounding-level
// noise doubling every few round trips, found by a random lossless-line deck).
struct ChebyshevFit {
  Eigen::VectorXd nodes, checks;
  Eigen::PartialPivLU<Eigen::MatrixXd> lu;
  ChebyshevFit() {
    const int m = kHistoryDegree + 1;
    nodes.resize(m);
    for (int i = 0; i < m; ++i) nodes(i) = 0.5 * (1 - std::cos(M_PI * i / (m - 1.0)));
    checks.resize(m - 1);
    for (int i = 1; i < m; ++i) checks(i - 1) = 0.5 * (nodes(i - 1) + nodes(i));
    Eigen::MatrixXd V(m, m);
    for (int i = 0; i < m; ++i)
      for (int k = 0; k < m; ++k) V(i, k) = std::pow(nodes(i), k);
    lu.compute(V);
  }
};
const ChebyshevFit& chebyshev() {
  static const ChebyshevFit fit;
  return fit;
}
}  // namespace

SourceSystem::SourceSystem(const LcsProblem& model, double tstop) : provider_(&model.inputs()) {
  for (const InputSignal& signal : model.inputs().signals()) {
    Input in;
    if (signal.history >= 0) {  // its corners come as the run makes them
      in.history = history_ = true;
    } else if (signal.quantity != InputSignal::Quantity::One) {
      in.waveform = &signal.waveform;
      const Waveform& w = *in.waveform;
      if (w.kind == Waveform::Kind::Sin) {
        in.vo = w.params.at(0);
        in.omega = kTwoPi * w.params.at(2);
        in.td = w.params.at(3);
        in.theta = w.params.at(4);
      }
      // Corners at TSTOP count (a jump there changes the last row), also when the corner's
      // time is computed a few ulps past it (TD + k PER + ...): those are moved onto TSTOP.
      for (double b : w.breakpoints(0.0, tstop + 64 * DBL_EPSILON * tstop))
        breakpoints_.push_back(std::min(b, tstop));
    }
    inputs_.push_back(in);
  }
  std::sort(breakpoints_.begin(), breakpoints_.end());
  breakpoints_.erase(std::unique(breakpoints_.begin(), breakpoints_.end()), breakpoints_.end());
}

char SourceSystem::kind(const Input& in, double t) const {
  if (in.history) return 'h';
  if (!in.waveform) return 'c';
  const Waveform& w = *in.waveform;
  switch (w.kind) {
    case Waveform::Kind::Dc:
      return 'c';
    case Waveform::Kind::Sin:
      if (t < in.td || (w.params.at(1) == 0)) return 'c';
      return (in.omega == 0 && in.theta == 0) ? 'c' : 's';
    case Waveform::Kind::Pulse:
    case Waveform::Kind::Pwl:
      return w.derivative(t) == 0 ? 'c' : 'r';
  }
  return 'c';
}

std::string SourceSystem::signature(double t) const {
  std::string s;
  s.reserve(inputs_.size());
  for (const Input& in : inputs_) s.push_back(kind(in, t));
  return s;
}

int SourceSystem::dimension(const std::string& sig) const {
  int d = 0;
  for (char k : sig) d += kind_dimension(k);
  return d;
}

Eigen::MatrixXd SourceSystem::S(const std::string& sig) const {
  const int p = dimension(sig);
  Eigen::MatrixXd S = Eigen::MatrixXd::Zero(p, p);
  int o = 0;
  for (size_t k = 0; k < sig.size(); ++k) {
    if (sig[k] == 'r') S(o, o + 1) = 1;
    if (sig[k] == 'h')
      for (int j = 0; j < kHistoryDegree; ++j) S(o + j, o + j + 1) = j + 1;
    if (sig[k] == 's') {
      const Input& in = inputs_[k];
      const double rate = std::sqrt(in.omega * in.omega + in.theta * in.theta);
      S(o + 1, o + 2) = rate;
      S(o + 2, o + 1) = -rate;
      S(o + 2, o + 2) = -2 * in.theta;
    }
    o += kind_dimension(sig[k]);
  }
  return S;
}

Eigen::MatrixXd SourceSystem::P(const std::string& sig) const {
  Eigen::MatrixXd P = Eigen::MatrixXd::Zero(static_cast<int>(sig.size()), dimension(sig));
  int o = 0;
  for (size_t k = 0; k < sig.size(); ++k) {
    P(k, o) = 1;
    if (sig[k] == 's') P(k, o + 1) = 1;
    o += kind_dimension(sig[k]);
  }
  return P;
}

Eigen::VectorXd SourceSystem::rounding_weights(const std::string& sig, double segment) const {
  Eigen::VectorXd w = Eigen::VectorXd::Ones(dimension(sig));
  int o = 0;
  for (size_t k = 0; k < sig.size(); ++k) {
    if (sig[k] == 'r') w(o + 1) = segment;
    if (sig[k] == 'h')
      for (int j = 1; j <= kHistoryDegree; ++j) w(o + j) = std::pow(segment, j);
    if (sig[k] == 's') {
      const Input& in = inputs_[k];
      w(o + 2) = std::sqrt(in.omega * in.omega + in.theta * in.theta);
    }
    o += kind_dimension(sig[k]);
  }
  return w;
}

void SourceSystem::sigma(double t, const std::string& sig, Eigen::VectorXd& out) const {
  out.resize(dimension(sig));
  int o = 0;
  for (size_t k = 0; k < sig.size(); ++k) {
    const Input& in = inputs_[k];
    if (sig[k] == 'h') {
      out.segment(o, kHistoryDegree + 1).setZero();
      out(o) = provider_->history()->value(provider_->signals()[k].history, t);
      o += kind_dimension('h');
      continue;
    }
    const double u = in.waveform ? in.waveform->value(t) : 1.0;
    switch (sig[k]) {
      case 'c':
        out(o) = u;
        break;
      case 'r':
        out(o) = u;
        out(o + 1) = in.waveform->derivative(t);
        break;
      case 's':
        out(o) = in.vo;
        out(o + 1) = u - in.vo;
        out(o + 2) = in.waveform->derivative(t) / std::sqrt(in.omega * in.omega + in.theta * in.theta);
        break;
    }
    o += kind_dimension(sig[k]);
  }
}

void SourceSystem::hold_history(double t0, double t1, const std::string& sig, Eigen::Ref<Eigen::VectorXd> sigma) const {
  const DelayHistory& history = *provider_->history();
  int o = 0;
  for (size_t k = 0; k < sig.size(); ++k) {
    if (sig[k] == 'h') {
      sigma.segment(o, kHistoryDegree + 1).setZero();
      sigma(o) = history.value(provider_->signals()[k].history, t0, 1e-9 * (t1 - t0));
    }
    o += kind_dimension(sig[k]);
  }
}

double SourceSystem::fit_history(double t0, double t1, const std::string& sig,
                                 Eigen::Ref<Eigen::VectorXd> sigma) const {
  const ChebyshevFit& cheb = chebyshev();
  const DelayHistory& history = *provider_->history();
  const int m = kHistoryDegree + 1;
  const double h = t1 - t0;
  double worst = 0, size = 0;
  Eigen::VectorXd y(m), c(m);
  int o = 0;
  for (size_t k = 0; k < sig.size(); ++k) {
    if (sig[k] != 'h') {
      o += kind_dimension(sig[k]);
      continue;
    }
    const int wave = provider_->signals()[k].history;
    // The ends as one-sided limits: a wavefront arriving at t0 (to within the rounding of its
    // time) is already there, one arriving at t1 not yet.
    const double nudge = 1e-9 * h;
    for (int i = 0; i < m; ++i)
      y(i) = history.value(wave, t0 + h * cheb.nodes(i), i == 0 ? nudge : i == m - 1 ? -nudge : 0.0);
    c = cheb.lu.solve(y);  // in x = (t - t0) / h
    for (int i = 0; i < cheb.checks.size(); ++i) {
      const double x = cheb.checks(i);
      double p = 0;
      for (int j = m - 1; j >= 0; --j) p = p * x + c(j);
      worst = std::max(worst, std::abs(p - history.value(wave, t0 + h * x)));
    }
    size = std::max(size, y.cwiseAbs().maxCoeff());
    for (int j = 0; j < m; ++j) sigma(o + j) = c(j) / std::pow(h, j);  // Taylor coefficients in t - t0
    o += m;
  }
  return worst / std::max({size, history.magnitude(), 1e-300});
}

}  // namespace lcs
