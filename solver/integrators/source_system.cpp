#include "solver/integrators/source_system.h"

#include <algorithm>
#include <stdexcept>
#include <cfloat>
#include <cmath>

namespace lcs {

namespace {
constexpr double kTwoPi = 6.283185307179586476925;
int kind_dimension(char k) {
  switch (k) {
    case 'c': return 1;
    case 'r': return 2;
    case 's':
    case 'x': return 3;
    case 'a': return 7;
    default: return kHistoryDegree + 1;
  }
}

// An AM source (or an SFFM one whose modulation vanishes) after its TD as three rotations:
//   VO + (VMO + VMA sin(wm tau + pm)) sin(wc tau + pc)
//     = VO + VMO sin(wc tau + pc) + VMA/2 cos((wc - wm) tau + pc - pm) - VMA/2 cos((wc + wm) tau + pc + pm).
// Each rotation q (rate w) is carried as [q, q'/w]: d/dt [q, r] = [w r, -w q].
struct AmTerms {
  double vo = 0, td = 0;
  double amplitude[3] = {0, 0, 0}, omega[3] = {0, 0, 0}, phase[3] = {0, 0, 0};
  bool cosine[3] = {false, true, true};  // term 0 is a sine, terms 1 and 2 cosines
  // [q, r] of term j at tau.
  void slots(int j, double tau, double& q, double& r) const {
    const double x = omega[j] * tau + phase[j], a = amplitude[j];
    if (cosine[j]) {
      q = a * std::cos(x);
      r = -a * std::sin(x);
    } else {
      q = a * std::sin(x);
      r = a * std::cos(x);
    }
  }
};

constexpr double kDegree = 3.14159265358979323846 / 180.0;

// The AM terms of an AM waveform, or of an SFFM one that is a plain sinusoid (MDI = 0 or FS = 0).
AmTerms am_terms(const Waveform& w) {
  const std::vector<double>& p = w.params;
  double vo = p.at(0), vmo = p.at(1), vma, wm, wc, pm, pc;
  if (w.kind == Waveform::Kind::Am) {
    vma = p.at(2), wm = kTwoPi * p.at(3), wc = kTwoPi * p.at(4), pm = p.at(6) * kDegree, pc = p.at(7) * kDegree;
  } else {  // SFFM(VO VA FC MDI FS TD PHASEM PHASEC) with a constant inner sine
    vma = 0, wm = 0, wc = kTwoPi * p.at(2), pm = 0;
    pc = p.at(7) * kDegree + p.at(3) * std::sin(p.at(6) * kDegree);
  }
  AmTerms t;
  t.vo = vo;
  t.td = p.at(5);
  t.amplitude[0] = vmo, t.omega[0] = wc, t.phase[0] = pc;
  t.amplitude[1] = vma / 2, t.omega[1] = wc - wm, t.phase[1] = pc - pm;
  t.amplitude[2] = -vma / 2, t.omega[2] = wc + wm, t.phase[2] = pc + pm;
  return t;
}

// SFFM is a sine of a sine: between breakpoints it solves no finite linear ODE (its spectrum is
// the Bessel sidebands FC + k FS for every k), unless its modulation vanishes.
bool sffm_is_sinusoid(const Waveform& w) {
  return w.params.at(3) == 0.0 || w.params.at(4) == 0.0 || w.params.at(1) == 0.0;
}

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

bool event_method_applies(const InputProvider& inputs, std::string* why) {
  for (const InputSignal& signal : inputs.signals()) {
    if (signal.history >= 0 || signal.quantity == InputSignal::Quantity::One) continue;
    const Waveform& w = signal.waveform;
    if (w.kind != Waveform::Kind::Sffm || sffm_is_sinusoid(w)) continue;
    if (why)
      *why = "source " + signal.label + " is " + w.describe() +
             ", a sine of a sine: not a finite linear system, which the event method integrates "
             "exactly between breakpoints (Stewart 8.3); use --method euler, theta, radau3, radau5 or smooth";
    return false;
  }
  return true;
}

SourceSystem::SourceSystem(const LcsProblem& model, double tstop) : provider_(&model.inputs()) {
  std::string why;
  if (!event_method_applies(model.inputs(), &why)) throw std::invalid_argument(why);
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
        in.end = w.sine_end();
      }
      if (w.kind == Waveform::Kind::Exp) {
        in.td = w.params.at(2);
        in.rate1 = w.params.at(3) > 0 ? -1 / w.params.at(3) : 0.0;
        in.rate2 = w.params.at(5) > 0 ? -1 / w.params.at(5) : 0.0;
      }
      if (w.kind == Waveform::Kind::Am || w.kind == Waveform::Kind::Sffm) {
        const AmTerms t = am_terms(w);
        in.td = t.td;
        in.vo = t.vo;
        for (int j = 0; j < 3; ++j) in.am_omega[j] = t.omega[j];
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
      if (t < in.td || t >= in.end || (w.params.at(1) == 0)) return 'c';  // held from `end` on
      return (in.omega == 0 && in.theta == 0) ? 'c' : 's';
    case Waveform::Kind::Pulse:
    case Waveform::Kind::Pwl:
      return w.derivative(t) == 0 ? 'c' : 'r';
    case Waveform::Kind::Exp:
      return (t < in.td || w.params.at(0) == w.params.at(1)) ? 'c' : 'x';
    case Waveform::Kind::Am:
    case Waveform::Kind::Sffm:  // a sinusoid (event_method_applies)
      return t < in.td ? 'c' : 'a';
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
    if (sig[k] == 'x') {
      S(o + 1, o + 1) = inputs_[k].rate1;
      S(o + 2, o + 2) = inputs_[k].rate2;
    }
    if (sig[k] == 'a')
      for (int j = 0; j < 3; ++j) {
        const double w = inputs_[k].am_omega[j];
        S(o + 1 + 2 * j, o + 2 + 2 * j) = w;
        S(o + 2 + 2 * j, o + 1 + 2 * j) = -w;
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
    if (sig[k] == 'x') P(k, o + 1) = P(k, o + 2) = 1;
    if (sig[k] == 'a')
      for (int j = 0; j < 3; ++j) P(k, o + 1 + 2 * j) = 1;
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
    if (sig[k] == 'a')  // each q'/w slot counts as the slope q', as a SIN's does
      for (int j = 0; j < 3; ++j)
        if (inputs_[k].am_omega[j] != 0) w(o + 2 + 2 * j) = std::abs(inputs_[k].am_omega[j]);
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
      case 'x': {  // [c, p1, p2]: c the settled value, p1 and p2 the modes still decaying
        const std::vector<double>& p = in.waveform->params;
        const double v1 = p[0], v2 = p[1], td1 = p[2], td2 = p[4];
        const bool second = t >= td2;  // t >= TD1 on an 'x' segment
        auto mode = [&](double x, double rate) { return rate != 0 ? std::exp(rate * x) : 0.0; };
        out(o + 1) = -(v2 - v1) * mode(t - td1, in.rate1);
        out(o + 2) = second ? -(v1 - v2) * mode(t - td2, in.rate2) : 0.0;
        out(o) = v1 + (v2 - v1) + (second ? v1 - v2 : 0.0);
        break;
      }
      case 'a': {
        const AmTerms terms = am_terms(*in.waveform);
        out(o) = terms.vo;
        for (int j = 0; j < 3; ++j) terms.slots(j, t - in.td, out(o + 1 + 2 * j), out(o + 2 + 2 * j));
        break;
      }
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
