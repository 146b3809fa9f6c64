// The lossy-line kernels as sums of exponentials (line_kernel.h), checked against the line
// equations (Stewart 1.3.3 (1.13)) written out here independently of the library: in frequency
// on a grid other than the fitting one, and in time against a fixed-Talbot numerical inverse
// Laplace transform.
//
// Measured for the cable of case (3) (R = 0.1 Ω/m, L = 250 nH/m, C = 100 pF/m, G = 0, ℓ = 10 m,
// t_long = 1 µs, t_short = τ/20: band 1e5 .. 4e9 rad/s), default tolerance 1e-4, in about 3 ms:
//   Yc − 1/Z0:  4 poles, all real (−9.1e3 .. −3.7e5 rad/s); max_error 8.1e-5, 8.0e-5 on the
//               independent grid (largest at the band's low end); DC error 0 (to rounding)
//   H e^{sτ}:   4 poles, all real (−7.5e3 .. −3.1e5 rad/s); max_error 4.0e-7, 3.9e-7 on the
//               independent grid; DC error 1e-16
//   step responses against Talbot at 5 ns .. 1 µs: within 2.7e-6 (Yc) and 2.0e-8 (H) of the
//   final value (the tests allow 1e-3).
#include "solver/devices/line_kernel.h"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace lcs {
namespace {

using cplx = std::complex<double>;

// The exact functions, straight from the definitions (no cancellation-free rewriting: a check of
// the library's forms too). γ = sqrt(R + sL) sqrt(G + sC) keeps Re γ ≥ 0 off the cut between
// −R/L and −G/C, which is what the Talbot contour needs.
cplx exact_admittance_remainder(const RlcgLine& x, cplx s) {
  return std::sqrt(x.g + s * x.c) / std::sqrt(x.r + s * x.l) - std::sqrt(x.c / x.l);
}
cplx exact_advanced_propagation(const RlcgLine& x, cplx s) {
  const double tau = x.length * std::sqrt(x.l * x.c);
  return std::exp(-x.length * std::sqrt(x.r + s * x.l) * std::sqrt(x.g + s * x.c) + s * tau);
}

// Fixed Talbot inversion (Abate & Valkó 2004): f(t) ≈ (r/M) [½ F(r) e^{rt} +
// Σ_{k=1}^{M−1} Re(e^{t s_k} F(s_k) (1 + jσ_k))], s_k = r θ_k (cot θ_k + j), θ_k = kπ/M,
// σ_k = θ_k + (θ_k cot θ_k − 1) cot θ_k, r = 2M/(5t). With M = 32 in double precision the
// rounding (amplified by e^{rt} = e^{12.8}) is ~1e-10 relative.
double talbot(const std::function<cplx(cplx)>& transform, double t, int m = 32) {
  const double r = 2.0 * m / (5.0 * t);
  double sum = 0.5 * (transform(r) * std::exp(r * t)).real();
  for (int k = 1; k < m; ++k) {
    const double theta = k * M_PI / m;
    const double cot = 1 / std::tan(theta);
    const cplx s = r * theta * cplx(cot, 1);
    const double sigma = theta + (theta * cot - 1) * cot;
    sum += (std::exp(t * s) * transform(s) * cplx(1, sigma)).real();
  }
  return r / m * sum;
}

// Log-spaced frequencies in [lo, hi] with a step unrelated to the fit's grids (997 points, the
// ends pulled in by a non-round factor).
std::vector<double> independent_grid(double lo, double hi) {
  const int n = 997;
  lo *= 1.000731;
  hi /= 1.000593;
  std::vector<double> w;
  for (int k = 0; k < n; ++k) w.push_back(lo * std::pow(hi / lo, k / (n - 1.0)));
  return w;
}

// max |fit − exact| / max |exact| over the grid.
double relative_error(const RationalFit& fit, const std::function<cplx(cplx)>& exact,
                      const std::vector<double>& w) {
  double error = 0, peak = 0;
  for (double x : w) {
    const cplx e = exact(cplx(0, x));
    error = std::max(error, std::abs(fit(cplx(0, x)) - e));
    peak = std::max(peak, std::abs(e));
  }
  return error / peak;
}

// Every pole stable; complex ones adjacent to their conjugates (Im > 0 first) with conjugate
// residues; real poles with real residues.
void expect_real_kernel(const RationalFit& fit) {
  ASSERT_EQ(fit.poles.size(), fit.residues.size());
  for (size_t k = 0; k < fit.poles.size(); ++k) {
    EXPECT_LT(fit.poles[k].real(), 0) << "pole " << k;
    if (fit.poles[k].imag() == 0) {
      EXPECT_EQ(fit.residues[k].imag(), 0) << "real pole " << k;
      continue;
    }
    ASSERT_GT(fit.poles[k].imag(), 0) << "pair " << k;
    ASSERT_LT(k + 1, fit.poles.size());
    EXPECT_EQ(fit.poles[k + 1], std::conj(fit.poles[k]));
    EXPECT_EQ(fit.residues[k + 1], std::conj(fit.residues[k]));
    ++k;
  }
}

const RlcgLine kCable{0.1, 250e-9, 0, 100e-12, 10};  // Z0 = 50 Ω, τ = 50 ns, Rℓ = 1 Ω

KernelFitOptions cable_options() {
  KernelFitOptions options;
  options.t_long = 1e-6;
  return options;
}

// (1) Lossless: both remainders are exactly zero.
TEST(LineKernel, LosslessLineHasNoPoles) {
  const LineKernel k = fit_line_kernel({0, 250e-9, 0, 100e-12, 10});
  EXPECT_DOUBLE_EQ(k.delay, 50e-9);
  EXPECT_DOUBLE_EQ(k.z0, 50);
  EXPECT_TRUE(k.admittance.poles.empty());
  EXPECT_TRUE(k.propagation.poles.empty());
  EXPECT_EQ(k.admittance.direct, 0);
  EXPECT_EQ(k.propagation.direct, 1);
  EXPECT_EQ(k.admittance.max_error, 0);
  EXPECT_EQ(k.propagation.max_error, 0);
  EXPECT_EQ(k.propagation.step(1e-6), 1);
}

// (2) Distortionless (R/L = G/C): Yc = 1/Z0 and H e^{sτ} = exp(−ℓ sqrt(RG)) exactly.
TEST(LineKernel, DistortionlessLineHasConstantKernels) {
  RlcgLine line = kCable;
  line.g = line.r * line.c / line.l;
  const LineKernel k = fit_line_kernel(line, cable_options());
  const double h = std::exp(-line.length * std::sqrt(line.r * line.g));
  EXPECT_LE(k.admittance.poles.size() + k.propagation.poles.size(), 0u);
  EXPECT_NEAR(k.propagation.direct, h, 1e-9);
  for (double w : independent_grid(k.omega_min, k.omega_max)) {
    EXPECT_LE(std::abs(k.admittance(cplx(0, w))), 1e-9 / k.z0) << w;
    EXPECT_LE(std::abs(k.propagation(cplx(0, w)) - h), 1e-9) << w;
  }
  EXPECT_NEAR(k.propagation(0.0).real(), h, 1e-9);
  EXPECT_NEAR(k.propagation.step(1e-7), h, 1e-9);
}

// (3) A realistic lossy cable: accurate on a grid the fit never saw, exact at DC, stable, real.
TEST(LineKernel, LossyCableFitsWithinToleranceOffTheFittingGrid) {
  const KernelFitOptions options = cable_options();
  const LineKernel k = fit_line_kernel(kCable, options);
  EXPECT_DOUBLE_EQ(k.omega_min, 1 / (10 * options.t_long));
  EXPECT_DOUBLE_EQ(k.omega_max, 10 / (k.delay / 20));
  const double d = std::exp(-kCable.length * kCable.r / (2 * k.z0));
  EXPECT_DOUBLE_EQ(k.propagation.direct, d);
  EXPECT_EQ(k.admittance.direct, 0);

  auto yc = [](cplx s) { return exact_admittance_remainder(kCable, s); };
  auto h = [](cplx s) { return exact_advanced_propagation(kCable, s); };
  const std::vector<double> grid = independent_grid(k.omega_min, k.omega_max);
  for (const RationalFit* fit : {&k.admittance, &k.propagation}) {
    EXPECT_FALSE(fit->poles.empty());
    EXPECT_LE(static_cast<int>(fit->poles.size()), options.max_poles);
    EXPECT_LE(fit->max_error, options.tolerance);
    expect_real_kernel(*fit);
  }
  EXPECT_LE(relative_error(k.admittance, yc, grid), 1e-4);
  EXPECT_LE(relative_error(k.propagation, h, grid), 1e-4);

  // DC: Yc(0) = 0 (G = 0), H(0) = 1.
  EXPECT_NEAR(k.admittance(0.0).real(), -1 / k.z0, 1e-6 / k.z0);
  EXPECT_NEAR(k.propagation(0.0).real(), 1, 1e-6);
  // The library's exact forms agree with the definitions.
  for (double w : grid) {
    EXPECT_NEAR(std::abs(admittance_remainder(kCable, cplx(0, w)) - yc(cplx(0, w))), 0, 1e-12);
    EXPECT_NEAR(std::abs(advanced_propagation(kCable, cplx(0, w)) - h(cplx(0, w))), 0, 1e-9);
  }
}

// The reference inversion itself, on a transform with a branch point at 0 like the line's:
// L{erfc(a / (2 sqrt t))} = e^{−a sqrt s}/s.
TEST(LineKernel, TalbotInversionReference) {
  const double a = 1e-3;
  for (double t : {1e-8, 1e-7, 1e-6, 1e-5}) {
    const double f = talbot([&](cplx s) { return std::exp(-a * std::sqrt(s)) / s; }, t);
    EXPECT_NEAR(f, std::erfc(a / (2 * std::sqrt(t))), 1e-9) << t;
  }
}

// Step responses of a fit against the inverse transform of exact(s)/s at times in (0, t_long].
void expect_step_matches(const RationalFit& fit, const std::function<cplx(cplx)>& exact,
                         double final_value, double t_long) {
  for (double t : {5e-9, 2e-8, 5e-8, 1e-7, 3e-7, t_long}) {
    const double reference = talbot([&](cplx s) { return exact(s) / s; }, t);
    EXPECT_NEAR(fit.step(t), reference, 1e-3 * std::abs(final_value)) << "t = " << t;
  }
}

// (4) The propagation kernel's step response: d + ∫ impulse.
TEST(LineKernel, PropagationStepResponseMatchesInverseLaplace) {
  const KernelFitOptions options = cable_options();
  const LineKernel k = fit_line_kernel(kCable, options);
  expect_step_matches(k.propagation,
                      [](cplx s) { return exact_advanced_propagation(kCable, s); }, 1.0,
                      options.t_long);
  EXPECT_DOUBLE_EQ(k.propagation.step(0), k.propagation.direct);
  EXPECT_EQ(k.propagation.step(-1e-9), 0);
}

// (5) The characteristic admittance remainder's step response.
TEST(LineKernel, AdmittanceStepResponseMatchesInverseLaplace) {
  const KernelFitOptions options = cable_options();
  const LineKernel k = fit_line_kernel(kCable, options);
  expect_step_matches(k.admittance,
                      [](cplx s) { return exact_admittance_remainder(kCable, s); }, -1 / k.z0,
                      options.t_long);
}

// A lossier line with shunt loss too (R = 10 Ω/m, G = 1 mS/m: Rℓ = 2 Z0), in both domains,
// over the default band (t_long = 1000 τ).
TEST(LineKernel, LossyLineWithShuntConductance) {
  const RlcgLine line{10, 250e-9, 1e-3, 100e-12, 10};
  const LineKernel k = fit_line_kernel(line);
  auto yc = [&](cplx s) { return exact_admittance_remainder(line, s); };
  auto h = [&](cplx s) { return exact_advanced_propagation(line, s); };
  const std::vector<double> grid = independent_grid(k.omega_min, k.omega_max);
  EXPECT_LE(relative_error(k.admittance, yc, grid), 1e-4);
  EXPECT_LE(relative_error(k.propagation, h, grid), 1e-4);
  expect_real_kernel(k.admittance);
  expect_real_kernel(k.propagation);
  const double yc0 = std::sqrt(line.g / line.r) - 1 / k.z0;
  const double h0 = std::exp(-line.length * std::sqrt(line.r * line.g));
  EXPECT_NEAR(k.admittance(0.0).real(), yc0, 1e-6 * std::abs(yc0));
  EXPECT_NEAR(k.propagation(0.0).real(), h0, 1e-6 * h0);
  expect_step_matches(k.admittance, yc, yc0, 1e-6);
  expect_step_matches(k.propagation, h, h0, 1e-6);
}

// R = 0 < G: Yc(0) is infinite, so only the band is fitted; the fit is finite and stable.
TEST(LineKernel, ShuntLossOnlyFitsTheBand) {
  const RlcgLine line{0, 250e-9, 1e-2, 100e-12, 10};
  const LineKernel k = fit_line_kernel(line, cable_options());
  auto yc = [&](cplx s) { return exact_admittance_remainder(line, s); };
  EXPECT_LE(relative_error(k.admittance, yc, independent_grid(k.omega_min, k.omega_max)), 1e-4);
  expect_real_kernel(k.admittance);
  EXPECT_TRUE(std::isfinite(k.admittance(0.0).real()));
  EXPECT_NEAR(k.propagation(0.0).real(), 1, 1e-6);
}

// The fitting machinery on a function it can represent exactly, with complex poles (the line's
// kernels have real ones only): a real pole and two resonances, DC included.
TEST(LineKernel, VectorFittingRecoversAKnownRationalFunction) {
  const std::vector<cplx> poles = {-3e5, cplx(-2e5, 4e6), cplx(-2e5, -4e6), cplx(-1e7, 1e8),
                                   cplx(-1e7, -1e8)};
  const std::vector<cplx> residues = {2e5, cplx(1e5, -3e5), cplx(1e5, 3e5), cplx(4e6, 1e6),
                                      cplx(4e6, -1e6)};
  const double direct = 0.25;
  auto f = [&](cplx s) {
    cplx sum = direct;
    for (size_t k = 0; k < poles.size(); ++k) sum += residues[k] / (s - poles[k]);
    return sum;
  };
  const RationalFit fit = fit_rational(f, direct, 1e4, 1e10, 1e-10, 12);
  expect_real_kernel(fit);
  EXPECT_LE(fit.max_error, 1e-10);
  EXPECT_LE(relative_error(fit, f, independent_grid(1e4, 1e10)), 1e-10);
  EXPECT_NEAR(fit(0.0).real(), f(0.0).real(), 1e-12 * std::abs(f(0.0)));
  // Each true pole is found (a sixth one, with a negligible residue, is pruned).
  EXPECT_EQ(fit.poles.size(), poles.size());
  for (const cplx& p : poles) {
    double nearest = INFINITY;
    for (const cplx& q : fit.poles) nearest = std::min(nearest, std::abs(q - p));
    EXPECT_LE(nearest, 1e-6 * std::abs(p)) << p;
  }
  // The kernels in time: Σ r e^{pt}, real.
  for (double t : {1e-8, 1e-7, 1e-6, 1e-5}) {
    double impulse = 0;
    for (size_t k = 0; k < poles.size(); ++k)
      impulse += (residues[k] * std::exp(poles[k] * t)).real();
    EXPECT_NEAR(fit.impulse(t), impulse, 0.1) << t;  // 1e-8 of Σ |r_k| ≈ 1e7
  }
  EXPECT_THROW(fit_rational(f, direct, 0, 1e10), std::invalid_argument);
  EXPECT_THROW(fit_rational(f, direct, 1e10, 1e4), std::invalid_argument);
}

// impulse and step of a hand-made fit: one real pole and one pair.
TEST(LineKernel, RationalFitTimeDomain) {
  RationalFit fit;
  fit.direct = 0.5;
  fit.poles = {-2.0, cplx(-1, 3), cplx(-1, -3)};
  fit.residues = {4.0, cplx(1, 2), cplx(1, -2)};
  const double t = 0.7;
  const double impulse =
      4 * std::exp(-2 * t) + 2 * std::exp(-t) * (std::cos(3 * t) - 2 * std::sin(3 * t));
  EXPECT_NEAR(fit.impulse(t), impulse, 1e-14);
  EXPECT_EQ(fit.impulse(-t), 0);
  // ∫_0^t of the impulse, by Simpson's rule on 2000 intervals.
  double integral = 0;
  const int n = 2000;
  for (int i = 0; i <= n; ++i) {
    const double weight = (i == 0 || i == n) ? 1 : (i % 2 ? 4 : 2);
    integral += weight * fit.impulse(t * i / n);
  }
  integral *= t / n / 3;
  EXPECT_NEAR(fit.step(t), fit.direct + integral, 1e-12);
  EXPECT_NEAR(fit.step(1e-9), fit.direct + 1e-9 * fit.impulse(0), 1e-15);
  EXPECT_NEAR(fit(cplx(0, 1)).real(), (fit.direct + 4.0 / cplx(2, 1) + cplx(1, 2) / cplx(1, -2) +
                                       cplx(1, -2) / cplx(1, 4)).real(), 1e-14);
}

// (6) Parameters out of range or non-finite are rejected.
TEST(LineKernel, InvalidParametersThrow) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const RlcgLine bad[] = {
      {0.1, 0, 0, 1e-10, 1},   {0.1, -1e-7, 0, 1e-10, 1}, {0.1, 2.5e-7, 0, 0, 1},
      {-0.1, 2.5e-7, 0, 1e-10, 1}, {0.1, 2.5e-7, -1e-3, 1e-10, 1}, {0.1, 2.5e-7, 0, 1e-10, 0},
      {0.1, 2.5e-7, 0, 1e-10, -1}, {nan, 2.5e-7, 0, 1e-10, 1},   {0.1, inf, 0, 1e-10, 1},
      {0.1, 2.5e-7, 0, 1e-10, inf},
  };
  for (const RlcgLine& line : bad)
    EXPECT_THROW(fit_line_kernel(line), std::invalid_argument)
        << line.r << " " << line.l << " " << line.g << " " << line.c << " " << line.length;

  KernelFitOptions options;
  options.tolerance = 0;
  EXPECT_THROW(fit_line_kernel(kCable, options), std::invalid_argument);
  options = {};
  options.max_poles = 1;
  EXPECT_THROW(fit_line_kernel(kCable, options), std::invalid_argument);
  options = {};
  options.t_short = 1e-6;
  options.t_long = 1e-7;
  EXPECT_THROW(fit_line_kernel(kCable, options), std::invalid_argument);
  options = {};
  options.t_long = -1;
  EXPECT_THROW(fit_line_kernel(kCable, options), std::invalid_argument);

  try {
    fit_line_kernel({0.1, 0, 0, 1e-10, 1});
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("L must be > 0"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace lcs
