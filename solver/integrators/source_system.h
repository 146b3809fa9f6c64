// Independent sources as small autonomous linear systems (for exact integration, 8.3): between
// two breakpoints every input is u_k(t) = P_k σ_k(t) with dσ_k/dt = S_k σ_k, so the circuit and its
// sources together form one linear ODE whose matrix exponential is exact for both.
//   constant (DC, u[0] = 1, a PULSE plateau):  σ = [u],            S = [0]
//   ramp (a PULSE edge, a PWL segment):         σ = [u, u'],       S = [[0 1] [0 0]]
//   SIN after TD, u = VO + p with p'' + 2θp' + (ω² + θ²)p = 0, Ω = sqrt(ω² + θ²):
//                                               σ = [VO, p, p'/Ω], S = [[0 0 0] [0 0 Ω] [0 −Ω −2θ]]
//   (p'/Ω rather than p': S is then a scaled rotation, whose exponential is accurate in every
//   entry; with [0 1; −Ω² 0] the entries range over Ω², and exp(S h) carried errors of 1e-16 Ω² h
//   relative to its small ones: 4e-9 of a 10 kHz source's amplitude between grid times.)
//   EXP after TD1, u = c + p1 + p2 with p1' = -p1/TAU1, p2' = -p2/TAU2 (p2 = 0 before TD2):
//                                               σ = [c, p1, p2],   S = diag(0, −1/TAU1, −1/TAU2)
//   AM after TD, a product of sinusoids = a sum of three, at FC and FC ± FM (source_system.cpp):
//                                               σ = [VO, q1, q1'/w1, q2, q2'/w2, q3, q3'/w3],
//                                               S = three rotations [[0 w] [−w 0]]
//   SFFM (a sine of a sine) is no finite linear system: event_method_applies says no, unless its
//   modulation vanishes (then it is a sinusoid, carried as AM is).
//   a line's history input (the wave that left the other port a delay earlier, 1.3.3): on each
//   step a polynomial of degree kHistoryDegree in s = t - t0 fitted to the exact past
//   (fit_history), σ = [u, u', u''/2, ..., u^(p)/p!] at t0,  S = [[0 1 0 ..] [0 0 2 ..] ...]
// S depends only on the kind of each input (and a SIN's ω, θ, fixed for the run); the segment's
// values live in σ, which is reset from the waveform at every breakpoint and grid time.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "solver/model/lcs_problem.h"

namespace lcs {

constexpr int kHistoryDegree = 7;

// Whether every input of the circuit is a finite linear system between breakpoints, so the
// event method can integrate it exactly: false for an SFFM source with a nonzero modulation, and
// *why (when given) then names the source and says what to use instead. SourceSystem's
// constructor throws std::invalid_argument with the same text.
bool event_method_applies(const InputProvider& inputs, std::string* why);

class SourceSystem {
 public:
  // Breakpoints (source corners, SIN starts) in (0, tstop] are collected once.
  SourceSystem(const LcsProblem& model, double tstop);

  // Which form each input takes on the segment starting at t (one character per input: 'c',
  // 'r', 's', 'x' (EXP), 'a' (AM), 'h'); segments with the same signature share S and P.
  std::string signature(double t) const;
  int dimension(const std::string& signature) const;
  Eigen::MatrixXd S(const std::string& signature) const;
  Eigen::MatrixXd P(const std::string& signature) const;  // u = P σ
  // σ at t on the segment starting at or before t (right values at a corner). History inputs
  // get their value at t and no slope: fit_history gives them their polynomial for a step.
  void sigma(double t, const std::string& signature, Eigen::VectorXd& out) const;
  bool has_history() const { return history_; }
  // The history inputs' slots of σ for the step [t0, t1]: the degree-kHistoryDegree polynomial
  // through their exact values at Chebyshev points. Returns the largest difference between it and
  // the exact values at the points between, relative to the inputs' size: the caller halves the
  // step while it exceeds the tolerance.
  double fit_history(double t0, double t1, const std::string& signature, Eigen::Ref<Eigen::VectorXd> sigma) const;
  // The history inputs held at their value at t0 over [t0, t1] (a step too short for a fit's
  // powers of its length: 1e-9 of a step and less).
  void hold_history(double t0, double t1, const std::string& signature, Eigen::Ref<Eigen::VectorXd> sigma) const;

  // Weights that turn σ into the sizes its rounding is relative to: a ramp's slope u' counts
  // times `segment` (the most it can move u before the next reset: a 1 ps PULSE edge has
  // u' = 5e12 V/s while u moves by 5 V); a SIN's p'/Ω counts times Ω, i.e. as the slope p'
  // (the waveform, read again at every grid time, is itself only known to its slope times the
  // rounding of t: a floor of 1e-16 |p| turned the zero crossings of a 50 Hz source at grid
  // times into extra events); every other slot counts as itself.
  Eigen::VectorXd rounding_weights(const std::string& signature, double segment) const;

  const std::vector<double>& breakpoints() const { return breakpoints_; }

 private:
  struct Input {
    const Waveform* waveform = nullptr;  // nullptr: the constant input u[0] = 1
    double omega = 0, theta = 0, vo = 0, td = 0;
    double end = std::numeric_limits<double>::infinity();      // SIN with NCYCLES: a constant from here on (Waveform::sine_end)
    double rate1 = 0, rate2 = 0;  // EXP: -1/TAU1, -1/TAU2 (0: a jump, the mode already gone)
    double am_omega[3] = {0, 0, 0};  // AM: FC, FC - FM, FC + FM as angular rates
    bool history = false;
  };
  const InputProvider* provider_ = nullptr;
  bool history_ = false;
  char kind(const Input& in, double t) const;
  std::vector<Input> inputs_;
  std::vector<double> breakpoints_;
};

}  // namespace lcs
