#include "solver/devices/line_kernel.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>

namespace lcs {
namespace {

using cplx = std::complex<double>;

constexpr int kSamplesPerDecade = 25;  // fitting grid density (log-spaced)
constexpr int kCheckDensity = 4;       // the error is measured on a grid this much denser
constexpr int kRelocations = 8;        // vector-fitting pole relocations per pole count
// A remainder whose peak is below this (relative to the function it is a remainder of) is
// rounding: it is returned without poles.
constexpr double kNegligible = 1e-12;
// A pole whose term peaks below this fraction of the tolerance is dropped from the final fit.
constexpr double kPrune = 1e-2;
// In relaxed VF, σ(∞) below this means the relaxation failed: redo with σ(∞) = 1 (plain VF).
constexpr double kRelaxedFloor = 1e-8;

// ---------------------------------------------------------------------------------------------
// Validation

std::string show(double x) {
  std::ostringstream out;
  out << x;
  return out.str();
}

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument(what);
}

void validate(const RlcgLine& line) {
  const double values[] = {line.r, line.l, line.g, line.c, line.length};
  require(std::all_of(std::begin(values), std::end(values),
                      [](double v) { return std::isfinite(v); }),
          "RLCG line: R, L, G, C and length must be finite");
  require(line.l > 0, "RLCG line: L must be > 0 (got " + show(line.l) + " H/m)");
  require(line.c > 0, "RLCG line: C must be > 0 (got " + show(line.c) + " F/m)");
  require(line.r >= 0, "RLCG line: R must be >= 0 (got " + show(line.r) + " ohm/m)");
  require(line.g >= 0, "RLCG line: G must be >= 0 (got " + show(line.g) + " S/m)");
  require(line.length > 0, "RLCG line: length must be > 0 (got " + show(line.length) + " m)");
}

struct Band {
  double w_min = 0, w_max = 0;  // rad/s
};

void validate_fit(double tolerance, int max_poles) {
  require(std::isfinite(tolerance) && tolerance > 0,
          "rational fit: tolerance must be > 0 (got " + show(tolerance) + ")");
  require(max_poles >= 2, "rational fit: max_poles must be >= 2 (got " +
                              std::to_string(max_poles) + ")");
}

Band fit_band(double delay, const KernelFitOptions& options) {
  require(std::isfinite(options.t_short) && options.t_short >= 0,
          "line kernel fit: t_short must be >= 0 (got " + show(options.t_short) + " s)");
  require(std::isfinite(options.t_long) && options.t_long >= 0,
          "line kernel fit: t_long must be >= 0 (got " + show(options.t_long) + " s)");
  const double t_short = options.t_short > 0 ? options.t_short : delay / 20;
  const double t_long = options.t_long > 0 ? options.t_long : 1000 * delay;
  require(t_long > t_short, "line kernel fit: t_long (" + show(t_long) +
                                " s) must exceed t_short (" + show(t_short) + " s)");
  return {1 / (10 * t_long), 10 / t_short};
}

// ---------------------------------------------------------------------------------------------
// Vector fitting of a strictly proper g(s) ≈ Σ r_k/(s − p_k), on samples s = jω (ω > 0) and
// optionally s = 0. Frequencies and values are normalised (ω by the band's geometric mean, g by
// the peak of the function it is a remainder of), so the fit works in units of order one.

struct Problem {
  std::vector<cplx> s, g;              // fitting samples
  std::vector<cplx> check_s, check_g;  // a denser, interleaved grid for the error
  std::optional<double> dc;            // g(0), when finite: matched exactly
  double w_min = 0, w_max = 0;         // the band, normalised
};

struct PoleResidues {
  std::vector<cplx> poles, residues;
  double error = INFINITY;  // max |fit − g| over check points and s = 0 (normalised: relative)
};

// Columns of the real basis at s: a real pole p gives 1/(s − p); a pair (p, p̄) gives
// 1/(s − p) + 1/(s − p̄) and j/(s − p) − j/(s − p̄), whose real coefficients (c', c'') stand for
// the residues c' ± j c''. Poles are listed as in RationalFit (a pair: Im > 0 first).
std::vector<cplx> basis(const std::vector<cplx>& poles, cplx s) {
  std::vector<cplx> row;
  row.reserve(poles.size());
  for (size_t k = 0; k < poles.size(); ++k) {
    const cplx a = 1.0 / (s - poles[k]);
    if (poles[k].imag() == 0) {
      row.push_back(a);
      continue;
    }
    const cplx b = 1.0 / (s - std::conj(poles[k]));
    row.push_back(a + b);
    row.push_back(cplx(0, 1) * (a - b));
    ++k;
  }
  return row;
}

// Real least squares min ||A x − b|| with columns equilibrated; rank deficiency is tolerated
// (column-pivoting QR).
Eigen::VectorXd least_squares(Eigen::MatrixXd a, const Eigen::VectorXd& b) {
  Eigen::VectorXd scale(a.cols());
  for (Eigen::Index j = 0; j < a.cols(); ++j) {
    const double norm = a.col(j).norm();
    scale(j) = norm > 0 ? 1 / norm : 1;
    a.col(j) *= scale(j);
  }
  Eigen::VectorXd x = a.colPivHouseholderQr().solve(b);
  return x.cwiseProduct(scale);
}

// Real rows of complex equations: each complex row becomes its real and imaginary parts; a row at
// s = 0 (all real) only its real part.
struct RealSystem {
  std::vector<Eigen::RowVectorXd> rows;
  std::vector<double> rhs;

  void add(const Eigen::RowVectorXcd& row, cplx value, bool real_only, double weight = 1) {
    rows.push_back(weight * row.real());
    rhs.push_back(weight * value.real());
    if (real_only) return;
    rows.push_back(weight * row.imag());
    rhs.push_back(weight * value.imag());
  }
  Eigen::MatrixXd matrix() const {
    Eigen::MatrixXd a(rows.size(), rows.front().size());
    for (size_t i = 0; i < rows.size(); ++i) a.row(i) = rows[i];
    return a;
  }
  Eigen::VectorXd vector() const {
    return Eigen::Map<const Eigen::VectorXd>(rhs.data(), static_cast<Eigen::Index>(rhs.size()));
  }
};

Eigen::RowVectorXcd to_row(const std::vector<cplx>& v) {
  return Eigen::Map<const Eigen::RowVectorXcd>(v.data(), static_cast<Eigen::Index>(v.size()));
}

// Poles as RationalFit lists them, from the eigenvalues of a real matrix (which come in exact
// conjugate pairs); a pole in the right half plane is reflected into the left one.
std::vector<cplx> stable_poles(const Eigen::VectorXcd& eigenvalues, double w_min) {
  std::vector<cplx> poles;
  for (const cplx& e : eigenvalues) {
    if (e.imag() < 0) continue;
    double re = -std::abs(e.real());
    if (re == 0) re = -1e-3 * w_min;
    poles.emplace_back(re, e.imag());
    if (e.imag() > 0) poles.emplace_back(re, -e.imag());
  }
  return poles;
}

// One relaxed VF step (Gustavsen 2006): fit σ(s) g(s) ≈ Σ c_k φ_k(s) with σ(s) = d̃ + Σ c̃_k φ_k(s)
// on the current poles, Re Σ_i σ(s_i) = N fixing the scale; the new poles are the zeros of σ,
// the eigenvalues of A − b c̃ᵀ/d̃ for a real realisation (A, b) of the basis.
std::vector<cplx> relocate(const std::vector<cplx>& poles, const Problem& p) {
  const Eigen::Index n = static_cast<Eigen::Index>(poles.size());
  const double samples = static_cast<double>(p.s.size() + (p.dc ? 1 : 0));
  const double dc_weight = std::sqrt(samples);

  auto solve = [&](bool relaxed) {
    RealSystem sys;
    const Eigen::Index cols = 2 * n + (relaxed ? 1 : 0);
    Eigen::RowVectorXd sigma_sum = Eigen::RowVectorXd::Zero(cols);
    double g_norm2 = 0;
    auto equation = [&](cplx s, cplx g, bool real_only, double weight) {
      const Eigen::RowVectorXcd phi = to_row(basis(poles, s));
      Eigen::RowVectorXcd row(cols);
      row.head(n) = phi;
      row.segment(n, n) = -g * phi;
      if (relaxed) row(2 * n) = -g;
      sys.add(row, relaxed ? cplx(0) : g, real_only, weight);
      sigma_sum.segment(n, n) += phi.real();
      g_norm2 += std::norm(weight * g);
    };
    for (size_t i = 0; i < p.s.size(); ++i) equation(p.s[i], p.g[i], false, 1);
    if (p.dc) equation(0.0, *p.dc, true, dc_weight);
    if (relaxed) {
      sigma_sum(2 * n) = samples;
      const double weight = std::sqrt(g_norm2) / samples;
      sys.rows.push_back(weight * sigma_sum);
      sys.rhs.push_back(weight * samples);
    }
    return least_squares(sys.matrix(), sys.vector());
  };

  Eigen::VectorXd x = solve(true);
  double d = x(2 * n);
  if (!(std::abs(d) >= kRelaxedFloor)) {
    x = solve(false);
    d = 1;
  }
  const Eigen::VectorXd c = x.segment(n, n);

  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n, n);
  Eigen::VectorXd b = Eigen::VectorXd::Zero(n);
  for (Eigen::Index k = 0; k < n; ++k) {
    const cplx pole = poles[static_cast<size_t>(k)];
    if (pole.imag() == 0) {
      a(k, k) = pole.real();
      b(k) = 1;
      continue;
    }
    // The pair's block [[α, β], [−β, α]] with b = (2, 0) realises the two basis columns.
    a(k, k) = a(k + 1, k + 1) = pole.real();
    a(k, k + 1) = pole.imag();
    a(k + 1, k) = -pole.imag();
    b(k) = 2;
    ++k;
  }
  const Eigen::MatrixXd zeros_of_sigma = a - b * c.transpose() / d;
  return stable_poles(Eigen::EigenSolver<Eigen::MatrixXd>(zeros_of_sigma, false).eigenvalues(),
                      p.w_min);
}

// Residues for fixed poles: least squares over the samples, with g(0) matched exactly (the
// constraint eliminates the unknown with the largest DC coefficient).
PoleResidues identify_residues(const std::vector<cplx>& poles, const Problem& p) {
  const Eigen::Index n = static_cast<Eigen::Index>(poles.size());
  RealSystem sys;
  for (size_t i = 0; i < p.s.size(); ++i) sys.add(to_row(basis(poles, p.s[i])), p.g[i], false);
  Eigen::MatrixXd a = sys.matrix();
  Eigen::VectorXd b = sys.vector();

  Eigen::VectorXd x;
  if (!p.dc) {
    x = least_squares(a, b);
  } else {
    const Eigen::RowVectorXd e = to_row(basis(poles, 0.0)).real();
    Eigen::Index j = 0;
    Eigen::VectorXd col_norm = a.colwise().norm().transpose();
    (e.transpose().cwiseAbs().cwiseQuotient(col_norm)).maxCoeff(&j);
    // x_j = (g0 − Σ_{i≠j} e_i x_i)/e_j, substituted into A x ≈ b.
    Eigen::MatrixXd reduced(a.rows(), n - 1);
    for (Eigen::Index i = 0, k = 0; i < n; ++i)
      if (i != j) reduced.col(k++) = a.col(i) - a.col(j) * (e(i) / e(j));
    const Eigen::VectorXd y = n > 1 ? least_squares(reduced, b - a.col(j) * (*p.dc / e(j)))
                                    : Eigen::VectorXd();
    x.resize(n);
    double rest = 0;
    for (Eigen::Index i = 0, k = 0; i < n; ++i)
      if (i != j) {
        x(i) = y(k++);
        rest += e(i) * x(i);
      }
    x(j) = (*p.dc - rest) / e(j);
  }

  PoleResidues fit;
  fit.poles = poles;
  for (Eigen::Index k = 0; k < n; ++k) {
    if (poles[static_cast<size_t>(k)].imag() == 0) {
      fit.residues.emplace_back(x(k), 0);
      continue;
    }
    fit.residues.emplace_back(x(k), x(k + 1));
    fit.residues.emplace_back(x(k), -x(k + 1));
    ++k;
  }
  auto value = [&](cplx s) {
    cplx sum = 0;
    for (size_t k = 0; k < fit.poles.size(); ++k) sum += fit.residues[k] / (s - fit.poles[k]);
    return sum;
  };
  fit.error = p.dc ? std::abs(value(0.0) - *p.dc) : 0;
  for (size_t i = 0; i < p.check_s.size(); ++i)
    fit.error = std::max(fit.error, std::abs(value(p.check_s[i]) - p.check_g[i]));
  return fit;
}

// n starting poles (n even): pairs −β/100 ± jβ with β log-spaced over the band.
std::vector<cplx> starting_poles(int n, double w_min, double w_max) {
  std::vector<cplx> poles;
  const int pairs = n / 2;
  for (int k = 0; k < pairs; ++k) {
    const double beta =
        pairs == 1 ? std::sqrt(w_min * w_max)
                   : w_min * std::pow(w_max / w_min, static_cast<double>(k) / (pairs - 1));
    poles.emplace_back(-beta / 100, beta);
    poles.emplace_back(-beta / 100, -beta);
  }
  return poles;
}

// Without the poles whose term r/(s − p) stays below `floor` on the whole imaginary axis (its peak
// there is |r| / |Re p|), residues refitted. A pair goes together.
PoleResidues prune(const PoleResidues& fit, const Problem& p, double floor) {
  std::vector<cplx> kept;
  for (size_t k = 0; k < fit.poles.size(); ++k)
    if (std::abs(fit.residues[k]) > floor * std::abs(fit.poles[k].real()))
      kept.push_back(fit.poles[k]);
  if (kept.size() == fit.poles.size() || kept.empty()) return fit;
  return identify_residues(kept, p);
}

// Grow the pole count until the error meets the tolerance; the best fit seen is kept, less the
// poles that contribute next to nothing.
PoleResidues vector_fit(const Problem& p, double tolerance, int max_poles) {
  PoleResidues best;
  for (int n = 2; n <= max_poles; n += 2) {
    std::vector<cplx> poles = starting_poles(n, p.w_min, p.w_max);
    for (int it = 0; it < kRelocations; ++it) {
      poles = relocate(poles, p);
      PoleResidues fit = identify_residues(poles, p);
      if (fit.error < best.error) best = std::move(fit);
    }
    if (best.error <= tolerance) break;
  }
  PoleResidues pruned = prune(best, p, kPrune * tolerance);
  return pruned.error <= std::max(best.error, tolerance) ? pruned : best;
}

// Slowest pole first; a pair stays together.
PoleResidues sorted(PoleResidues fit) {
  std::vector<size_t> heads;  // a real pole, or the first of a pair
  for (size_t k = 0; k < fit.poles.size(); k += fit.poles[k].imag() == 0 ? 1 : 2)
    heads.push_back(k);
  std::stable_sort(heads.begin(), heads.end(), [&](size_t a, size_t b) {
    return std::abs(fit.poles[a]) < std::abs(fit.poles[b]);
  });
  PoleResidues out;
  out.error = fit.error;
  for (size_t k : heads)
    for (size_t j = k; j < k + (fit.poles[k].imag() == 0 ? 1 : 2); ++j) {
      out.poles.push_back(fit.poles[j]);
      out.residues.push_back(fit.residues[j]);
    }
  return out;
}

std::vector<double> log_grid(double lo, double hi, int points) {
  std::vector<double> w(static_cast<size_t>(points));
  for (int k = 0; k < points; ++k)
    w[static_cast<size_t>(k)] = lo * std::pow(hi / lo, static_cast<double>(k) / (points - 1));
  return w;
}

// Fit f(s) = direct + g(s) over the band (and s = 0 when f(0) is finite). A g below kNegligible
// of max(reference, max |f| over the band) gets no poles.
RationalFit fit_remainder(const std::function<cplx(cplx)>& exact, double direct, double reference,
                          const Band& band, double tolerance, int max_poles) {
  const double decades = std::log10(band.w_max / band.w_min);
  const int points = std::max(static_cast<int>(std::ceil(kSamplesPerDecade * decades)),
                              3 * max_poles) + 1;
  const std::vector<double> fit_w = log_grid(band.w_min, band.w_max, points);
  const std::vector<double> check_w =
      log_grid(band.w_min, band.w_max, kCheckDensity * (points - 1) + 1);

  const cplx f0 = exact(0.0);
  const bool has_dc = std::isfinite(f0.real());
  double peak = 0, remainder_peak = has_dc ? std::abs(f0 - direct) : 0;  // peak: over the band
  std::vector<cplx> check_f;
  for (double w : check_w) {
    check_f.push_back(exact(cplx(0, w)));
    peak = std::max(peak, std::abs(check_f.back()));
    remainder_peak = std::max(remainder_peak, std::abs(check_f.back() - direct));
  }

  RationalFit fit;
  fit.direct = direct;
  reference = std::max(reference, peak);
  if (!(remainder_peak > kNegligible * reference)) {
    fit.max_error = remainder_peak / reference;
    return fit;
  }

  if (peak == 0) peak = remainder_peak;  // (only f(0) differs from direct)
  const double w_ref = std::sqrt(band.w_min * band.w_max);
  Problem p;
  p.w_min = band.w_min / w_ref;
  p.w_max = band.w_max / w_ref;
  for (double w : fit_w) {
    p.s.emplace_back(0, w / w_ref);
    p.g.push_back((exact(cplx(0, w)) - direct) / peak);
  }
  for (size_t i = 0; i < check_w.size(); ++i) {
    p.check_s.emplace_back(0, check_w[i] / w_ref);
    p.check_g.push_back((check_f[i] - direct) / peak);
  }
  if (has_dc) p.dc = (f0.real() - direct) / peak;

  const PoleResidues vf = sorted(vector_fit(p, tolerance, max_poles));
  for (size_t k = 0; k < vf.poles.size(); ++k) {
    fit.poles.push_back(vf.poles[k] * w_ref);
    fit.residues.push_back(vf.residues[k] * (w_ref * peak));
  }
  fit.max_error = vf.error;
  return fit;
}

// (e^{pt} − 1)/p, without cancellation for small |pt|.
cplx exp_minus_one_over(cplx p, double t) {
  const cplx z = p * t;
  if (std::abs(z) < 1e-3) return t * (1.0 + z / 2.0 + z * z / 6.0 + z * z * z / 24.0);
  return (std::exp(z) - 1.0) / p;
}

}  // namespace

// ---------------------------------------------------------------------------------------------

cplx RationalFit::operator()(cplx s) const {
  cplx sum = direct;
  for (size_t k = 0; k < poles.size(); ++k) sum += residues[k] / (s - poles[k]);
  return sum;
}

double RationalFit::impulse(double t) const {
  if (t < 0) return 0;
  double sum = 0;
  for (size_t k = 0; k < poles.size(); ++k) sum += (residues[k] * std::exp(poles[k] * t)).real();
  return sum;
}

double RationalFit::step(double t) const {
  if (t < 0) return 0;
  double sum = direct;
  for (size_t k = 0; k < poles.size(); ++k)
    sum += (residues[k] * exp_minus_one_over(poles[k], t)).real();
  return sum;
}

// Yc − 1/Z0 = (Yc² − C/L)/(Yc + 1/Z0) = (GL − RC) / (L (R + sL) (Yc + 1/Z0)): no cancellation,
// and exactly 0 for a distortionless line.
cplx admittance_remainder(const RlcgLine& line, cplx s) {
  const double numerator = line.g * line.l - line.r * line.c;
  if (numerator == 0) return 0;
  const cplx series = line.r + s * line.l, shunt = line.g + s * line.c;
  if (series == 0.0) return INFINITY;
  const cplx yc = std::sqrt(shunt) / std::sqrt(series);
  return numerator / (line.l * series * (yc + std::sqrt(line.c / line.l)));
}

// H e^{sτ} = exp(−ℓ (γ − s sqrt(LC))) with γ − s sqrt(LC) = (γ² − s²LC)/(γ + s sqrt(LC))
// = (RG + s(RC + GL))/(γ + s sqrt(LC)). γ = sqrt(R + sL) sqrt(G + sC): Re γ ≥ 0 for Re s ≥ 0.
cplx advanced_propagation(const RlcgLine& line, cplx s) {
  if (s == 0.0) return std::exp(-line.length * std::sqrt(line.r * line.g));
  const cplx gamma = std::sqrt(line.r + s * line.l) * std::sqrt(line.g + s * line.c);
  const cplx excess = (line.r * line.g + s * (line.r * line.c + line.g * line.l)) /
                      (gamma + s * std::sqrt(line.l * line.c));
  return std::exp(-line.length * excess);
}

RationalFit fit_rational(const std::function<cplx(cplx)>& f, double direct, double omega_min,
                         double omega_max, double tolerance, int max_poles) {
  require(std::isfinite(direct), "rational fit: direct must be finite");
  require(omega_min > 0 && omega_max > omega_min && std::isfinite(omega_max),
          "rational fit: need 0 < omega_min < omega_max (got " + show(omega_min) + ", " +
              show(omega_max) + ")");
  validate_fit(tolerance, max_poles);
  return fit_remainder(f, direct, 0.0, {omega_min, omega_max}, tolerance, max_poles);
}

LineKernel fit_line_kernel(const RlcgLine& line, const KernelFitOptions& options) {
  validate(line);
  validate_fit(options.tolerance, options.max_poles);
  LineKernel kernel;
  kernel.line = line;
  kernel.delay = line.length * std::sqrt(line.l * line.c);
  kernel.z0 = std::sqrt(line.l / line.c);
  const Band band = fit_band(kernel.delay, options);
  kernel.omega_min = band.w_min;
  kernel.omega_max = band.w_max;

  kernel.admittance = fit_remainder([&](cplx s) { return admittance_remainder(line, s); }, 0.0,
                                    1 / kernel.z0, band, options.tolerance, options.max_poles);
  const double d = std::exp(-line.length * (line.r / (2 * kernel.z0) + line.g * kernel.z0 / 2));
  kernel.propagation = fit_remainder([&](cplx s) { return advanced_propagation(line, s); }, d,
                                     0.0, band, options.tolerance, options.max_poles);
  return kernel;
}

}  // namespace lcs
