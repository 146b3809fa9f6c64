// The waves of one event-method segment read as Taylor series (taylor_segment.h) equal
// L exp(M r) X0 and its slope L M exp(M r) X0 to rounding, across pieces, with a fitted input's
// coefficients as large as a short step makes them; a segment too stiff for the pieces is left
// to the exact product.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "solver/integrators/taylor_segment.h"

namespace lcs {
namespace {

// A mode like the event method's: x' = A x + B σ_0 (a damped oscillator and a fast decay driven
// by the input's value), σ the Taylor coefficients of a degree-7 input in t - t0 (σ_j' =
// (j+1) σ_j+1), fitted over a step h: σ_j = c_j / h^j.
struct ModeCase {
  Eigen::MatrixXd M, L;
  Eigen::VectorXd X0;
};

ModeCase make_case(double h, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  const int n = 3, p = 8, q = n + p;
  ModeCase c;
  c.M = Eigen::MatrixXd::Zero(q, q);
  c.M(0, 0) = -2e8;
  c.M(0, 1) = 6e9;
  c.M(1, 0) = -6e9;
  c.M(1, 1) = -2e8;
  c.M(2, 2) = -3e9;
  c.M(0, n) = 1e9;
  c.M(2, n) = 5e8;
  for (int j = 0; j + 1 < p; ++j) c.M(n + j, n + j + 1) = j + 1;
  c.X0 = Eigen::VectorXd::Zero(q);
  for (int i = 0; i < n; ++i) c.X0(i) = u(gen);
  for (int j = 0; j < p; ++j) c.X0(n + j) = u(gen) * std::pow(0.3, j) / std::pow(h, j);
  c.L = Eigen::MatrixXd::Zero(2, q);
  c.L(0, 0) = 50;
  c.L(0, n) = 1;
  c.L(1, 1) = -20;
  c.L(1, 2) = 7;
  c.L(1, n) = 0.5;
  return c;
}

// exp(M r) X0 as its Taylor series summed in long double: independent of the scaling and squaring
// whose absolute errors, times a coefficient of 1e126, would swamp a short step's input.
Eigen::VectorXd reference_state(const ModeCase& c, double r) {
  using VectorL = Eigen::Matrix<long double, Eigen::Dynamic, 1>;
  const Eigen::Matrix<long double, Eigen::Dynamic, Eigen::Dynamic> M = c.M.cast<long double>();
  VectorL term = c.X0.cast<long double>(), sum = term;
  for (int k = 1; k < 400; ++k) {
    term = (M * term) * (static_cast<long double>(r) / k);
    sum += term;
  }
  return sum.cast<double>();
}

void expect_exact(const ModeCase& c, double len, int want_pieces) {
  auto exact = [&](double r) { return reference_state(c, r); };
  const std::optional<TaylorSegment> seg = TaylorSegment::build(c.M, c.L, c.X0, len, exact);
  ASSERT_TRUE(seg.has_value());
  EXPECT_EQ(seg->pieces(), want_pieces);
  std::vector<double> a, da;
  double worst = 0, worst_slope = 0, size = 0, slope_size = 0;
  for (int i = 0; i <= 64; ++i) {
    const double r = len * i / 64.0;
    const Eigen::VectorXd X = exact(r);
    const Eigen::VectorXd want = c.L * X, want_slope = c.L * (c.M * X);
    seg->eval(r, a, da);
    ASSERT_EQ(a.size(), 2u);
    for (int k = 0; k < 2; ++k) {
      worst = std::max(worst, std::abs(a[k] - want(k)));
      worst_slope = std::max(worst_slope, std::abs(da[k] - want_slope(k)));
      size = std::max(size, std::abs(want(k)));
      slope_size = std::max(slope_size, std::abs(want_slope(k)));
    }
  }
  EXPECT_LT(worst, 1e-13 * size) << "len " << len;
  EXPECT_LT(worst_slope, 1e-11 * slope_size) << "len " << len;
}

TEST(TaylorSegment, EqualsTheExponentialOnOnePiece) {
  const double h = 1e-11;  // ||M||_1 h = 0.062: one piece
  expect_exact(make_case(h, 1), h, 1);
}

TEST(TaylorSegment, EqualsTheExponentialAcrossPieces) {
  const double h = 4e-10;  // ||M||_1 h = 2.48: five pieces, each anchored on the exact state
  expect_exact(make_case(h, 2), h, 5);
}

TEST(TaylorSegment, KeepsAShortStepsHugeInputCoefficients) {
  const double h = 1e-18;  // σ_7 = c_7 / h^7 ~ 1e126: the shift's terms vanish exactly
  expect_exact(make_case(h, 3), h, 1);
}

// The waves read only the end of a chain x0 -> x1 -> x2 that starts with x1 = x2 = 0: the first
// two wave terms are zero, and only the state's own terms say the series is not done. A stop on
// the newest wave term would read a(r) = 0.
TEST(TaylorSegment, KeepsTermsOfStatesTheWavesDoNotSeeYet) {
  ModeCase c;
  c.M = Eigen::MatrixXd::Zero(3, 3);
  c.M(0, 0) = -1e9;
  c.M(1, 0) = 2e9;
  c.M(2, 1) = 3e9;
  c.X0 = Eigen::Vector3d(1, 0, 0);
  c.L = Eigen::RowVector3d(0, 0, 1);
  const double len = 1e-10;  // ||M||_1 len = 0.3: one piece
  auto exact = [&](double r) { return reference_state(c, r); };
  const std::optional<TaylorSegment> seg = TaylorSegment::build(c.M, c.L, c.X0, len, exact);
  ASSERT_TRUE(seg.has_value());
  std::vector<double> a, da;
  seg->eval(len, a, da);
  const double want = (c.L * reference_state(c, len))(0);
  EXPECT_GT(want, 0.02);
  EXPECT_NEAR(a[0], want, 1e-15 * want);
}

// Reads before the segment are read at its start (as the exact product reads them); reads a
// nudge past its end continue the last piece's series.
TEST(TaylorSegment, ReadsAtAndJustPastTheEnds) {
  const double h = 4e-10;
  const ModeCase c = make_case(h, 5);
  auto exact = [&](double r) { return reference_state(c, r); };
  const std::optional<TaylorSegment> seg = TaylorSegment::build(c.M, c.L, c.X0, h, exact);
  ASSERT_TRUE(seg.has_value());
  std::vector<double> a, da;
  seg->eval(-1e-12, a, da);
  const Eigen::VectorXd at0 = c.L * c.X0;
  for (int k = 0; k < 2; ++k) EXPECT_NEAR(a[k], at0(k), 1e-13 * at0.cwiseAbs().maxCoeff());
  const double past = h * (1 + 1e-9);
  seg->eval(past, a, da);
  const Eigen::VectorXd want = c.L * reference_state(c, past);
  for (int k = 0; k < 2; ++k) EXPECT_NEAR(a[k], want(k), 1e-13 * want.cwiseAbs().maxCoeff());
}

TEST(TaylorSegment, LeavesAStiffSegmentToTheExactProduct) {
  const ModeCase c = make_case(1e-9, 4);  // ||M||_1 len = 6.2: 13 pieces, more than the 8 allowed
  int calls = 0;
  auto exact = [&](double r) {
    ++calls;
    return reference_state(c, r);
  };
  EXPECT_FALSE(TaylorSegment::build(c.M, c.L, c.X0, 1e-9, exact).has_value());
  EXPECT_EQ(calls, 0);
  EXPECT_FALSE(TaylorSegment::build(c.M, c.L, c.X0, 0.0, exact).has_value());
}

}  // namespace
}  // namespace lcs
