// The kernels of a lossy (RLCG) transmission line as sums of exponentials, so that a simulator
// can carry every convolution of the line as a handful of ODE states.
//
// The telegrapher's equations of a uniform line (Stewart 1.3.3 (1.13)), with per-unit-length
// R, L, G, C and length ℓ, give in the Laplace domain
//
//   γ(s) = sqrt((R + sL)(G + sC)),   Yc(s) = sqrt((G + sC)/(R + sL)),   H(s) = exp(−ℓ γ(s)),
//
// delay τ = ℓ sqrt(LC), Z0 = sqrt(L/C), and the port relations (currents into the line)
//
//   I1 = Yc V1 − H (Yc V2 + I2),   I2 = Yc V2 − H (Yc V1 + I1).
//
// fit_line_kernel writes the two non-trivial parts as rational functions with stable poles,
//
//   Yc(s)         = 1/Z0 + Σ a_k/(s − p_k)     (strictly proper remainder)
//   H(s) e^{sτ}   = d    + Σ c_k/(s − q_k),    d = exp(−ℓ (R/(2 Z0) + G Z0/2)) = H e^{sτ} at s → ∞,
//
// by relaxed vector fitting (Gustavsen & Semlyen 1999; Gustavsen 2006) on s = jω over a band
// set by the run's time scales, plus s = 0, where the fit is made exact.
#pragma once

#include <complex>
#include <functional>
#include <vector>

namespace lcs {

// Per-unit-length resistance (Ω/m), inductance (H/m), conductance (S/m), capacitance (F/m), and
// the length (m). L > 0, C > 0, R ≥ 0, G ≥ 0, length > 0.
struct RlcgLine {
  double r = 0, l = 0, g = 0, c = 0, length = 1;
};

// f(s) ≈ direct + Σ residues[k] / (s − poles[k]). Every pole has Re < 0; a complex pole is
// listed next to its conjugate (the one with Im > 0 first), and so are their residues, so that
// the time-domain kernel is real. Slowest pole (smallest |p|) first.
struct RationalFit {
  double direct = 0;
  std::vector<std::complex<double>> poles, residues;
  // max |fit − exact| over the band (and at s = 0 when the exact value is finite there), relative
  // to max |exact| over the band.
  double max_error = 0;

  std::complex<double> operator()(std::complex<double> s) const;
  // Σ residues e^{poles t} for t ≥ 0 (0 before): the kernel without its δ of weight `direct`.
  double impulse(double t) const;
  // direct + ∫_0^t impulse: the response to a unit step applied at t = 0 (0 before).
  double step(double t) const;
};

struct KernelFitOptions {
  // Shortest time scale that matters (s): the band reaches 10/(2π t_short) Hz, i.e. ω = 10/t_short.
  // 0: τ/20.
  double t_short = 0;
  // Longest time scale, the run's TSTOP (s): the band starts at 1/(20π t_long) Hz, i.e.
  // ω = 1/(10 t_long). 0: 1000 τ. Must exceed t_short.
  double t_long = 0;
  // Target max_error of each fit; the pole count grows (2, 4, ...) until it is met.
  double tolerance = 1e-4;
  // Most poles per fit; when the tolerance is not met by then, the best fit found is returned
  // (its max_error says how good). At least 2.
  int max_poles = 40;
};

struct LineKernel {
  RlcgLine line;
  double delay = 0;                   // τ = ℓ sqrt(LC) (s)
  double z0 = 0;                      // sqrt(L/C) (Ω)
  double omega_min = 0, omega_max = 0;  // the fitting band (rad/s)
  RationalFit admittance;             // Yc(s) − 1/Z0 (direct = 0)
  RationalFit propagation;            // H(s) e^{sτ} (direct = d)
};

// The exact functions the fits approximate, in forms without cancellation (for Re s ≥ 0; also
// elsewhere off the branch cut on the negative real axis): Yc(s) − 1/Z0, infinite at s = 0 when
// R = 0 < G, and H(s) e^{sτ}.
std::complex<double> admittance_remainder(const RlcgLine& line, std::complex<double> s);
std::complex<double> advanced_propagation(const RlcgLine& line, std::complex<double> s);

// Relaxed vector fitting of f(s) ≈ direct + Σ r_k/(s − p_k) (direct given: f(s) → direct as
// s → ∞) on s = jω, ω log-spaced over [omega_min, omega_max], and at s = 0, matched exactly, when
// f(0) is finite. f must be real (f(s̄) = conj f(s)). Starting from pairs −β/100 ± jβ spread over
// the band, the pole count grows 2, 4, ... up to max_poles until max_error ≤ tolerance; the best
// fit is returned either way, less the poles whose terms stay below 1% of the tolerance. A
// remainder f − direct below 1e-12 of max |f| gets no poles (max_error is then relative to
// max |f|). Throws std::invalid_argument for a band, tolerance or max_poles out of range.
RationalFit fit_rational(const std::function<std::complex<double>(std::complex<double>)>& f,
                         double direct, double omega_min, double omega_max,
                         double tolerance = 1e-4, int max_poles = 40);

// Both kernels of a line, by fit_rational over the band the options set. Throws
// std::invalid_argument for a line or options out of range (see above) or non-finite.
// A lossless line (R = G = 0) and a distortionless one (R/L = G/C) have constant kernels: both
// fits come back without poles (Yc − 1/Z0 counts as zero below 1e-12/Z0; max_error is then
// relative to 1/Z0, 0 up to rounding). When R = 0 < G, Yc(0) is infinite and only the band is
// fitted: the admittance fit is finite at s = 0, and the line's DC shunt conductance Gℓ is lost.
LineKernel fit_line_kernel(const RlcgLine& line, const KernelFitOptions& options = {});

}  // namespace lcs
