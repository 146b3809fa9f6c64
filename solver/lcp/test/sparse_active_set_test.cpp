// The sparse active-set solver against Lemke's method on the dense LCP it never forms:
//   M = Q - P K^-1 L,  q = b + P K^-1 a   (y = K^-1 (a - L z)).
#include <random>

#include <cmath>

#include <gtest/gtest.h>

#include "solver/lcp/lcp.h"
#include "solver/lcp/sparse_active_set.h"

namespace lcs {
namespace {

using Sparse = SparseActiveSetLcp::Sparse;

// A chain of n cells (a discretised RC line: K = I - h A with A a grounded Laplacian), pair i
// coupled to cell cell_of(i) through P and L: the shape of a diode-clamped ladder's step.
struct ChainProblem {
  Sparse K, L, P, Q;
};

ChainProblem chain_problem(int n, int m, std::mt19937& rng) {
  std::uniform_real_distribution<double> g(0.5, 2.0);
  std::vector<Eigen::Triplet<double>> k, l, p, q;
  for (int i = 0; i < n; ++i) {
    const double left = i > 0 ? g(rng) : 1.0, right = i + 1 < n ? g(rng) : 1.0;
    k.emplace_back(i, i, 1 + left + right);
    if (i > 0) k.emplace_back(i, i - 1, -left);
    if (i + 1 < n) k.emplace_back(i, i + 1, -right);
  }
  for (int j = 0; j < m; ++j) {
    const int cell = j * n / m;
    const double c = g(rng);
    l.emplace_back(cell, j, c);      // the diode's current charges its cell
    p.emplace_back(j, cell, -1.0);   // w = threshold + r z - v(cell)
    q.emplace_back(j, j, 0.1 * g(rng));
  }
  ChainProblem out{Sparse(n, n), Sparse(n, m), Sparse(m, n), Sparse(m, m)};
  out.K.setFromTriplets(k.begin(), k.end());
  out.L.setFromTriplets(l.begin(), l.end());
  out.P.setFromTriplets(p.begin(), p.end());
  out.Q.setFromTriplets(q.begin(), q.end());
  return out;
}

struct DenseLcp {
  Eigen::MatrixXd M;
  Eigen::VectorXd q;
};

DenseLcp dense_lcp(const ChainProblem& c, const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  const Eigen::MatrixXd K(c.K), L(c.L), P(c.P), Q(c.Q);
  Eigen::PartialPivLU<Eigen::MatrixXd> lu(K);
  return {Q - P * lu.solve(L), b + P * lu.solve(a)};
}

TEST(SparseActiveSet, AgreesWithLemkeOnRandomChainsAndCountsWarmHits) {
  std::mt19937 rng(12);
  std::normal_distribution<double> g(0.0, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    const int n = 40 + 13 * trial, m = 20 + 9 * trial;
    const ChainProblem c = chain_problem(n, m, rng);
    SparseActiveSetLcp solver(c.K, c.L, c.P, c.Q);
    for (int call = 0; call < 3; ++call) {
      Eigen::VectorXd a(n), b(m);
      for (int i = 0; i < n; ++i) a(i) = g(rng);
      for (int i = 0; i < m; ++i) b(i) = g(rng);
      Eigen::VectorXd y, z, w;
      ASSERT_TRUE(solver.solve(a, b, y, z, w)) << "trial " << trial;
      const DenseLcp d = dense_lcp(c, a, b);
      EXPECT_LT(lcp_residual(d.M, d.q, z), 1e-10) << "trial " << trial;
      const LcpSolution lemke = solve_lemke(d.M, d.q);
      ASSERT_EQ(lemke.status, LcpStatus::Solved);
      EXPECT_LT((z - lemke.z).cwiseAbs().maxCoeff(), 1e-9 * (1 + lemke.z.cwiseAbs().maxCoeff()));
      EXPECT_LT((w - (d.M * z + d.q)).cwiseAbs().maxCoeff(), 1e-9 * (1 + d.q.cwiseAbs().maxCoeff()));
      // The same data again: the mode just found answers without a flip.
      const long flips = solver.stats().flips, hits = solver.stats().warm_hits;
      Eigen::VectorXd y2, z2, w2;
      ASSERT_TRUE(solver.solve(a, b, y2, z2, w2));
      EXPECT_EQ(solver.stats().flips, flips);
      EXPECT_EQ(solver.stats().warm_hits, hits + 1);
      EXPECT_LT((z2 - z).cwiseAbs().maxCoeff(), 1e-12 * (1 + z.cwiseAbs().maxCoeff()));
    }
  }
}

// Far more than 64 pairs change at once (all off to all on, then back): the 64-pair bitmask of
// the dense warm start is no limit here.
TEST(SparseActiveSet, ThreeHundredPairsSwitchingTogether) {
  std::mt19937 rng(3);
  const int n = 300, m = 300;
  const ChainProblem c = chain_problem(n, m, rng);
  SparseActiveSetLcp solver(c.K, c.L, c.P, c.Q);
  const Eigen::VectorXd a = Eigen::VectorXd::Zero(n);
  Eigen::VectorXd y, z, w;
  ASSERT_TRUE(solver.solve(a, Eigen::VectorXd::Constant(m, 1.0), y, z, w));  // all off
  EXPECT_EQ(z.cwiseAbs().maxCoeff(), 0.0);
  ASSERT_TRUE(solver.solve(a, Eigen::VectorXd::Constant(m, -1.0), y, z, w));  // all driven on
  EXPECT_GT(z.minCoeff(), 0.0);
  EXPECT_GE(solver.stats().flips, m);
  const DenseLcp on = dense_lcp(c, a, Eigen::VectorXd::Constant(m, -1.0));
  EXPECT_LT(lcp_residual(on.M, on.q, z), 1e-10);
  ASSERT_TRUE(solver.solve(a, Eigen::VectorXd::Constant(m, 1.0), y, z, w));  // all off again
  EXPECT_EQ(z.cwiseAbs().maxCoeff(), 0.0);
  EXPECT_GE(solver.stats().flips, 2 * m);
}

// A budget smaller than two factorisations: the cache evicts and the answers stay right.
TEST(SparseActiveSet, EvictsBeyondItsBudgetAndStaysRight) {
  std::mt19937 rng(5);
  std::normal_distribution<double> g(0.0, 1.0);
  const int n = 200, m = 100;
  const ChainProblem c = chain_problem(n, m, rng);
  SparseActiveSetLcp solver(c.K, c.L, c.P, c.Q, /*cache_budget_bytes=*/1);
  for (int call = 0; call < 6; ++call) {
    Eigen::VectorXd a(n), b(m), y, z, w;
    for (int i = 0; i < n; ++i) a(i) = g(rng);
    for (int i = 0; i < m; ++i) b(i) = g(rng);
    ASSERT_TRUE(solver.solve(a, b, y, z, w));
    const DenseLcp d = dense_lcp(c, a, b);
    EXPECT_LT(lcp_residual(d.M, d.q, z), 1e-10);
  }
  EXPECT_GT(solver.stats().evictions, 0);
  EXPECT_LE(solver.stats().cache_bytes, solver.stats().factorisations > 0 ? std::size_t{1} << 20 : 0);
}

// A mode whose system is singular (two pairs with identical rows, both asked to conduct) is
// reported, never answered with a guess.
TEST(SparseActiveSet, SingularModeIsAFailureNotAGuess) {
  Sparse K(1, 1), L(1, 2), P(2, 1), Q(2, 2);
  K.insert(0, 0) = 1;
  L.insert(0, 0) = 1;
  L.insert(0, 1) = 1;
  P.insert(0, 0) = -1;
  P.insert(1, 0) = -1;  // two ideal diodes (no resistance) in parallel: z_1 + z_2 undetermined
  SparseActiveSetLcp solver(K, L, P, Q);
  Eigen::VectorXd y, z, w;
  solver.prefer(Eigen::Vector2d(1, 1));
  EXPECT_FALSE(solver.solve(Eigen::VectorXd::Constant(1, -1.0), Eigen::Vector2d(1, 1), y, z, w));
  EXPECT_EQ(solver.stats().failures, 1);
}

}  // namespace
}  // namespace lcs

namespace lcs {
namespace {

// Low-rank updates (set_low_rank): on random chains, with right-hand sides that move a little
// from call to call (as a time step's do), the solver with updates of rank <= 4 (so that both
// updates and re-basing factorisations occur) gives the same z as the one that factorises every
// mode, to 1e-12 of its size, and fewer factorisations.
TEST(SparseActiveSet, LowRankUpdatesGiveTheFactorisedAnswers) {
  std::mt19937 rng(7);
  std::normal_distribution<double> g(0.0, 1.0);
  long updates = 0;
  for (int trial = 0; trial < 6; ++trial) {
    const int n = 60 + 20 * trial, m = 30 + 10 * trial;
    const ChainProblem c = chain_problem(n, m, rng);
    SparseActiveSetLcp plain(c.K, c.L, c.P, c.Q), updated(c.K, c.L, c.P, c.Q);
    updated.set_low_rank(4);
    Eigen::VectorXd a(n), b(m);
    for (int i = 0; i < n; ++i) a(i) = g(rng);
    for (int i = 0; i < m; ++i) b(i) = g(rng);
    for (int call = 0; call < 40; ++call) {
      for (int i = 0; i < m; ++i) b(i) += 0.2 * g(rng);
      Eigen::VectorXd y1, z1, w1, y2, z2, w2;
      ASSERT_TRUE(plain.solve(a, b, y1, z1, w1)) << trial;
      ASSERT_TRUE(updated.solve(a, b, y2, z2, w2)) << trial;
      const double size = 1 + z1.cwiseAbs().maxCoeff() + y1.cwiseAbs().maxCoeff();
      EXPECT_LT((z2 - z1).cwiseAbs().maxCoeff(), 1e-12 * size) << trial << " " << call;
      EXPECT_LT((y2 - y1).cwiseAbs().maxCoeff(), 1e-12 * size) << trial << " " << call;
      EXPECT_LT((w2 - w1).cwiseAbs().maxCoeff(), 1e-12 * size) << trial << " " << call;
    }
    EXPECT_LT(updated.stats().factorisations, plain.stats().factorisations) << trial;
    updates += updated.stats().updates;
  }
  EXPECT_GT(updates, 50);
}

// The null space of a mode from a regular one a pair away: [K L; P Q] with K = I, L = (1, 0),
// P = (1, 0) and Q = q. With the pair on and q = 1 the first and last rows are equal: the null
// space is (1, 0, -1)/sqrt(2); with q = -1 the mode is regular: no null vector.
TEST(SparseActiveSetLcp, NullSpaceOfAModeFromARegularOne) {
  using Sparse = SparseActiveSetLcp::Sparse;
  const Eigen::MatrixXd K = Eigen::MatrixXd::Identity(2, 2), L = (Eigen::MatrixXd(2, 1) << 1, 0).finished(),
                        P = (Eigen::MatrixXd(1, 2) << 1, 0).finished();
  for (double q : {1.0, -1.0}) {
    const Eigen::MatrixXd Q = Eigen::MatrixXd::Constant(1, 1, q);
    SparseActiveSetLcp lcp(K.sparseView(), L.sparseView(), P.sparseView(), Sparse(Q.sparseView()));
    Eigen::MatrixXd basis;
    ASSERT_TRUE(lcp.mode_null_space({1}, {0}, 4, 4, basis));
    if (q < 0) {
      EXPECT_EQ(basis.cols(), 0);
      continue;
    }
    ASSERT_EQ(basis.cols(), 1);
    const Eigen::Vector3d v = basis.col(0) * (basis(0, 0) > 0 ? 1.0 : -1.0);
    EXPECT_NEAR(v(0), 1 / std::sqrt(2.0), 1e-14);
    EXPECT_NEAR(v(1), 0.0, 1e-14);
    EXPECT_NEAR(v(2), -1 / std::sqrt(2.0), 1e-14);
    // Too far from the regular mode, or too many free directions asked for: refused.
    EXPECT_FALSE(lcp.mode_null_space({1}, {0}, 0, 4, basis));
    EXPECT_FALSE(lcp.mode_null_space({1}, {0}, 4, 0, basis));
  }
}

}  // namespace
}  // namespace lcs
