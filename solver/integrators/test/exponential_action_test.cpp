// The exponential action (exponential_action.h) against the dense exponential (Eigen's Padé
// scaling and squaring) on matrices like the event method's modes: decaying, oscillating,
// stiff and non-normal, at step lengths from the output step down to a bisection's.
#include <cmath>
#include <random>

#include <gtest/gtest.h>
#include <unsupported/Eigen/MatrixFunctions>

#include "solver/integrators/exponential_action.h"

namespace lcs {
namespace {

// A random matrix with eigenvalues -rate * [1e-3, 1] (a stiff circuit) and an oscillating 2 x 2
// block (a sine source's rotation), made non-normal by a random similarity V: A = V D V^-1, and
// exp(t A) b = V exp(t D) V^-1 b, with exp(t D) in closed form, is the reference.
struct ModeLike {
  Eigen::MatrixXd A, V, Vinv;
  Eigen::VectorXd decay;  // D's diagonal but the rotation
  double omega = 314.159;
  Eigen::VectorXd exact(double t, const Eigen::VectorXd& b) const {
    const int n = static_cast<int>(b.size());
    Eigen::VectorXd c = Vinv * b;
    for (int i = 0; i < n - 2; ++i) c(i) *= std::exp(t * decay(i));
    const double x = c(n - 2), y = c(n - 1), co = std::cos(omega * t), si = std::sin(omega * t);
    c(n - 2) = co * x + si * y;
    c(n - 1) = -si * x + co * y;
    return V * c;
  }
};

ModeLike mode_like(int n, double rate, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  ModeLike m;
  m.decay.resize(n - 2);
  Eigen::MatrixXd D = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n - 2; ++i) D(i, i) = m.decay(i) = -rate * std::pow(10.0, -3.0 * i / (n - 3));
  D(n - 2, n - 1) = m.omega;
  D(n - 1, n - 2) = -m.omega;
  m.V.resize(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) m.V(i, j) = (i == j ? 1.0 : 0.0) + 0.3 * u(rng);
  m.Vinv = m.V.inverse();
  m.A = m.V * D * m.Vinv;
  return m;
}

// Both the action and the dense exponential have a backward error of about 2^-53 of ||t A||,
// so on a stiff step both are off by rounding times ||t A|| and the non-normality: the action
// is held to the dense exponential's own error against the closed form (or 1e-13 of the size,
// whichever is larger). Measured (n = 6, 40, 120): the action's error within 1.2 times the
// dense one's everywhere, and 0.16 to 0.6 times it on the stiff steps (||t A|| from 1e2 to 1e4:
// 2.6e-10 against 6.2e-10 of the size at n = 120, rate 1e8, level 0).
TEST(ExponentialAction, AsAccurateAsTheDenseExponentialFromTheOutputStepToABisectionsStep) {
  for (int n : {6, 40, 80}) {
    for (double rate : {1e3, 1e5, 1e8}) {
      const ModeLike m = mode_like(n, rate, 17u + n);
      const ExponentialAction action(m.A);
      const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(n, -1.0, 2.0);
      for (int level : {0, 5, 20, 43}) {
        const double t = std::ldexp(1e-4, -level);
        const Eigen::VectorXd exact = m.exact(t, b);
        const Eigen::VectorXd dense = (m.A * t).exp() * b;
        Eigen::VectorXd out;
        const long products = action.apply(t, b, out);
        EXPECT_LE(products, action.planned_products(t));
        const double scale = std::max(exact.cwiseAbs().maxCoeff(), b.cwiseAbs().maxCoeff());
        const double dense_error = (dense - exact).cwiseAbs().maxCoeff();
        const double action_error = (out - exact).cwiseAbs().maxCoeff();
        EXPECT_LE(action_error, std::max(dense_error, 1e-13 * scale))
            << "n " << n << " rate " << rate << " level " << level;
      }
    }
  }
}

// A short step costs a few products, a long stiff one many: what the event method weighs
// against forming the dense exponential.
TEST(ExponentialAction, ProductsGrowWithTheNormOfTheStep) {
  const ModeLike m = mode_like(40, 1e5, 3u);
  const ExponentialAction action(m.A);
  const long deep = action.planned_products(std::ldexp(1e-4, -30));
  const long shallow = action.planned_products(1e-4);
  EXPECT_LE(deep, 4);
  EXPECT_GT(shallow, 100);
  // The identity's shift is its whole norm: exp(t I) b = e^t b without a product.
  const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(5, 5);
  const ExponentialAction identity(I);
  Eigen::VectorXd out;
  EXPECT_EQ(identity.apply(0.5, Eigen::VectorXd::Ones(5), out), 0);
  EXPECT_NEAR(out(0), std::exp(0.5), 1e-15);
}

// An RC ladder's mode (tridiagonal, 3n - 2 entries) is multiplied as a sparse matrix: each
// product costs (3n - 2) / n^2 of a dense one, which the event method weighs against forming the
// dense exponential; the result is the dense exponential's to rounding, on a stiff step
// (||t A|| = 4e3) and a bisection's. A full matrix keeps the dense products (cost 1).
TEST(ExponentialAction, ASparseModeIsMultipliedAsSparse) {
  const int n = 100;
  const double g = 1e9;  // 1 / (R C) of one section
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) {
    A(i, i) = i + 1 < n ? -2 * g : -g;
    if (i > 0) A(i, i - 1) = g;
    if (i + 1 < n) A(i, i + 1) = g;
  }
  const ExponentialAction action(A);
  EXPECT_DOUBLE_EQ(action.relative_cost(), (3.0 * n - 2) / (n * n));
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(n, 5.0, -1.0);
  for (double t : {1e-6, std::ldexp(1e-6, -30)}) {
    const Eigen::VectorXd dense = (A * t).exp() * b;
    Eigen::VectorXd out;
    action.apply(t, b, out);
    EXPECT_LE((out - dense).cwiseAbs().maxCoeff(), 1e-12 * b.cwiseAbs().maxCoeff()) << "t " << t;
  }
  EXPECT_EQ(ExponentialAction(mode_like(40, 1e5, 3u).A).relative_cost(), 1.0);
}

}  // namespace
}  // namespace lcs
