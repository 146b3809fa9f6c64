// solve_lemke: closed forms, random problems by matrix class, infeasible problems, iteration
// limit, bad scaling. Every returned solution is checked with lcp_residual.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>

#include "solver/lcp/lcp.h"
#include "solver/lcp/test/test_util.h"

namespace lcs {
namespace {

using lcp_test::abs_tol;
using lcp_test::planted;
using lcp_test::relative_residual;

// Solve and check status Solved, w = M z + q and the residual.
LcpSolution expect_solved(const Eigen::MatrixXd& M, const Eigen::VectorXd& q, double rel = 1e-9) {
  LcpSolution s = solve_lemke(M, q);
  EXPECT_EQ(s.status, LcpStatus::Solved) << "M=\n" << M << "\nq=" << q.transpose();
  EXPECT_EQ(s.z.size(), q.size());
  if (s.z.size() != q.size()) return s;
  EXPECT_LE(lcp_residual(M, q, s.z), abs_tol(M, q, s.z, rel))
      << "M=\n" << M << "\nq=" << q.transpose() << "\nz=" << s.z.transpose();
  EXPECT_LE(lcp_test::w_mismatch(M, q, s.z, s.w), 1e-13);
  return s;
}

Eigen::VectorXd vec(std::initializer_list<double> v) {
  Eigen::VectorXd x(v.size());
  int i = 0;
  for (double a : v) x(i++) = a;
  return x;
}

TEST(Lemke, NonnegativeQNeedsNoPivots) {
  std::mt19937 rng(1);
  Eigen::MatrixXd M = lcp_test::random_matrix(rng, 5, 5);  // any M
  Eigen::VectorXd q = vec({0, 1, 2, 0, 3});
  LcpSolution s = solve_lemke(M, q);
  EXPECT_EQ(s.status, LcpStatus::Solved);
  EXPECT_EQ(s.pivots, 0);
  EXPECT_EQ(s.z, Eigen::VectorXd::Zero(5));
  EXPECT_EQ(s.w, q);
}

TEST(Lemke, EmptyProblem) {
  LcpSolution s = solve_lemke(Eigen::MatrixXd(0, 0), Eigen::VectorXd(0));
  EXPECT_EQ(s.status, LcpStatus::Solved);
  EXPECT_EQ(s.z.size(), 0);
}

TEST(Lemke, RejectsBadInput) {
  EXPECT_THROW(solve_lemke(Eigen::MatrixXd::Identity(2, 3), Eigen::VectorXd::Zero(2)),
               std::invalid_argument);
  EXPECT_THROW(solve_lemke(Eigen::MatrixXd::Identity(2, 2), Eigen::VectorXd::Zero(3)),
               std::invalid_argument);
  EXPECT_THROW(solve_lemke(Eigen::MatrixXd::Identity(1, 1), vec({std::nan("")})),
               std::invalid_argument);
  Eigen::MatrixXd M = Eigen::MatrixXd::Identity(1, 1);
  M(0, 0) = INFINITY;
  EXPECT_THROW(solve_lemke(M, vec({-1})), std::invalid_argument);
}

// 1x1, m > 0: z = max(0, -q/m).
TEST(Lemke, OneByOneClosedForm) {
  for (double m : {1e-9, 0.5, 1.0, 3.0, 1e9})
    for (double q : {-1e9, -3.0, -1e-8, 0.0, 2.0}) {
      Eigen::MatrixXd M(1, 1);
      M << m;
      LcpSolution s = expect_solved(M, vec({q}));
      double z = std::max(0.0, -q / m);
      EXPECT_NEAR(s.z(0), z, 1e-14 * z) << m << " " << q;
      EXPECT_LE(s.pivots, 2);
      EXPECT_EQ(s.pivots, q < 0 ? 2 : 0);
    }
}

// Known 2x2 answers for M = [[2,1],[1,2]] (worked by hand).
TEST(Lemke, TwoByTwoKnownAnswers) {
  Eigen::MatrixXd M(2, 2);
  M << 2, 1, 1, 2;
  struct Case {
    Eigen::VectorXd q, z;
  } cases[] = {
      {vec({-1, -1}), vec({1.0 / 3, 1.0 / 3})},  // both active
      {vec({-1, 1}), vec({0.5, 0})},             // w2 = 1.5
      {vec({1, -4}), vec({0, 2})},               // w1 = 3
      {vec({-1, -5}), vec({0, 2.5})},            // both-active candidate (-1, 3) infeasible
      {vec({1, 1}), vec({0, 0})},
  };
  for (const Case& c : cases) {
    LcpSolution s = expect_solved(M, c.q);
    EXPECT_LE((s.z - c.z).cwiseAbs().maxCoeff(), 1e-14) << c.q.transpose();
  }
}

// 2x2 P-matrix solved by hand: the unique one of the four candidates that is feasible.
Eigen::VectorXd solve_2x2_by_cases(const Eigen::MatrixXd& M, const Eigen::VectorXd& q) {
  const double a = M(0, 0), b = M(0, 1), c = M(1, 0), d = M(1, 1);
  if (q(0) >= 0 && q(1) >= 0) return vec({0, 0});
  {  // z2 = 0
    double z1 = -q(0) / a;
    if (z1 >= 0 && c * z1 + q(1) >= 0) return vec({z1, 0});
  }
  {  // z1 = 0
    double z2 = -q(1) / d;
    if (z2 >= 0 && b * z2 + q(0) >= 0) return vec({0, z2});
  }
  double det = a * d - b * c;  // Cramer
  return vec({(-q(0) * d + b * q(1)) / det, (-a * q(1) + c * q(0)) / det});
}

TEST(Lemke, TwoByTwoPMatrixClosedForm) {
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int t = 0; t < 500; ++t) {
    Eigen::MatrixXd M = lcp_test::random_p_matrix(rng, 2);
    Eigen::VectorXd q = vec({u(rng), u(rng)});
    LcpSolution s = expect_solved(M, q);
    Eigen::VectorXd z = solve_2x2_by_cases(M, q);
    EXPECT_LE((s.z - z).cwiseAbs().maxCoeff(), 1e-12 * (1 + z.norm())) << M << "\n" << q;
  }
}

TEST(Lemke, RandomSpd) {
  std::mt19937 rng(3);
  for (int n = 1; n <= 30; ++n) {
    Eigen::MatrixXd M = lcp_test::random_spd(rng, n);
    for (int t = 0; t < 20; ++t) {
      // Half random q, half with a planted (unique, since SPD) solution.
      if (t % 2 == 0) {
        expect_solved(M, lcp_test::random_vector(rng, n));
      } else {
        lcp_test::Planted p = planted(rng, M, 0.5);
        LcpSolution s = expect_solved(M, p.q);
        EXPECT_LE((s.z - p.z).cwiseAbs().maxCoeff(), 1e-8 * (1 + p.z.norm())) << "n=" << n;
      }
    }
  }
}

TEST(Lemke, RandomPMatrixUniqueSolutionMatchesEnumeration) {
  std::mt19937 rng(4);
  for (int n = 1; n <= 9; ++n)
    for (int t = 0; t < 15; ++t) {
      Eigen::MatrixXd M = lcp_test::random_p_matrix(rng, n);
      Eigen::VectorXd q = lcp_test::random_vector(rng, n);
      LcpSolution s = expect_solved(M, q);
      std::vector<Eigen::VectorXd> all = enumerate_lcp_solutions(M, q);
      ASSERT_EQ(all.size(), 1u) << "P-matrix LCP has a unique solution";
      EXPECT_LE((s.z - all[0]).cwiseAbs().maxCoeff(), 1e-9 * (1 + all[0].norm()));
    }
  for (int n = 10; n <= 30; ++n)
    for (int t = 0; t < 10; ++t) {
      Eigen::MatrixXd M = lcp_test::random_p_matrix(rng, n);
      lcp_test::Planted p = planted(rng, M, 0.4, /*degenerate=*/t % 2 == 1);
      LcpSolution s = expect_solved(M, p.q);
      EXPECT_LE((s.z - p.z).cwiseAbs().maxCoeff(), 1e-9 * (1 + p.z.norm())) << "n=" << n;
    }
}

// Positive semidefinite, singular: M = [[1,-1],[-1,1]].
TEST(Lemke, PsdSingular) {
  Eigen::MatrixXd M(2, 2);
  M << 1, -1, -1, 1;
  {
    LcpSolution s = expect_solved(M, vec({-1, 2}));  // unique: z = (1, 0), w = (0, 1)
    EXPECT_LE((s.z - vec({1, 0})).norm(), 1e-14);
  }
  {
    // w1 = -w2 forces w = 0: solutions z = (1 + t, t), t >= 0 (a ray of solutions).
    LcpSolution s = expect_solved(M, vec({-1, 1}));
    EXPECT_NEAR(s.z(0) - s.z(1), 1.0, 1e-14);
  }
  {
    // w1 + w2 = -2 < 0: infeasible. M is copositive plus, so Lemke must end on a ray.
    LcpSolution s = solve_lemke(M, vec({-1, -1}));
    EXPECT_EQ(s.status, LcpStatus::RayTermination);
    EXPECT_TRUE(enumerate_lcp_solutions(M, vec({-1, -1})).empty());
  }
}

// Skew-symmetric plus PSD (monotone LCPs) with a planted solution: copositive plus and
// feasible, so Lemke must find a solution (maybe another than the planted one).
TEST(Lemke, MonotoneSkewPlusPsd) {
  std::mt19937 rng(5);
  for (int n = 2; n <= 20; ++n)
    for (int t = 0; t < 10; ++t) {
      Eigen::MatrixXd M = lcp_test::random_monotone(rng, n, t % 3 == 0 ? 0 : n / 2);
      lcp_test::Planted p = planted(rng, M, 0.5, t % 2 == 1);
      expect_solved(M, p.q);
    }
}

// LP  min c^T x  s.t.  A x >= b, x >= 0  as LCP: z = (x, y), M = [[0, -A^T], [A, 0]],
// q = (c, -b). Complementarity gives primal/dual feasibility and c^T x = b^T y.
TEST(Lemke, LinearProgramsAsLcp) {
  std::mt19937 rng(6);
  std::uniform_real_distribution<double> u(0.1, 2.0);
  for (int t = 0; t < 40; ++t) {
    const int m = 1 + t % 6, k = 1 + (t / 6) % 7;  // m constraints, k variables
    Eigen::MatrixXd A(m, k);
    for (int i = 0; i < m; ++i)
      for (int j = 0; j < k; ++j) A(i, j) = u(rng);  // positive: feasible; c > 0: bounded
    Eigen::VectorXd b(m), c(k);
    for (int i = 0; i < m; ++i) b(i) = u(rng);
    for (int j = 0; j < k; ++j) c(j) = u(rng);
    Eigen::MatrixXd M = Eigen::MatrixXd::Zero(k + m, k + m);
    M.topRightCorner(k, m) = -A.transpose();
    M.bottomLeftCorner(m, k) = A;
    Eigen::VectorXd q(k + m);
    q << c, -b;
    LcpSolution s = expect_solved(M, q);
    Eigen::VectorXd x = s.z.head(k), y = s.z.tail(m);
    EXPECT_GE((A * x - b).minCoeff(), -1e-12);
    EXPECT_NEAR(c.dot(x), b.dot(y), 1e-12 * (1 + c.dot(x)));
  }
  // Infeasible LP: -x >= 1 with x >= 0. Then the LCP has no solution and ends on a ray.
  Eigen::MatrixXd M(2, 2);
  M << 0, 1, -1, 0;
  Eigen::VectorXd q = vec({1, -1});
  EXPECT_EQ(solve_lemke(M, q).status, LcpStatus::RayTermination);
  EXPECT_TRUE(enumerate_lcp_solutions(M, q).empty());
}

// Infeasible by rounding alone (issue 9, defect 3): a node reached only through two diodes,
// RON = 9 ohm. KCL ties d1's w (its current) to d2's z: w1 = q1 - z2, and q1, exactly 0, comes
// out of the elimination as -1.4e-17. As given the LCP has no solution (w1 >= 0 needs
// z2 <= q1 < 0); within rounding it has z = 0 (q2 > 0) or z1 = -q2 (q2 < 0).
TEST(Lemke, InfeasibleOnlyByRoundingIsSolved) {
  Eigen::MatrixXd M(2, 2);
  M << 0, -1, 1, 18;
  const LcpSolution up = solve_lemke(M, vec({-1.3877787807814457e-17, 0.22210760746361391}));
  ASSERT_EQ(up.status, LcpStatus::Solved);
  EXPECT_EQ(up.z(0), 0.0);
  EXPECT_EQ(up.z(1), 0.0);
  const LcpSolution down = solve_lemke(M, vec({-1.3877787807814457e-17, -0.2}));
  ASSERT_EQ(down.status, LcpStatus::Solved);
  EXPECT_NEAR(down.z(0), 0.2, 1e-15);
  EXPECT_EQ(down.z(1), 0.0);
  // Infeasible by more than rounding still ends on a ray.
  EXPECT_EQ(solve_lemke(M, vec({-1e-6, 0.2})).status, LcpStatus::RayTermination);
}

TEST(Lemke, InfeasibleEndsOnRay) {
  {
    Eigen::MatrixXd M(1, 1);
    M << -1;
    Eigen::VectorXd q = vec({-1});  // w = -z - 1 < 0
    LcpSolution s = solve_lemke(M, q);
    EXPECT_EQ(s.status, LcpStatus::RayTermination);
    EXPECT_EQ(s.pivots, 2);  // one ray, then one on q shifted by the rounding allowance
    EXPECT_TRUE(enumerate_lcp_solutions(M, q).empty());
  }
  {
    Eigen::MatrixXd M(2, 2);  // skew: w1 = z2 + q1, w2 = -z1 + q2; q2 < 0 is infeasible
    M << 0, 1, -1, 0;
    for (Eigen::VectorXd q : {vec({1, -1}), vec({-1, -1}), vec({0, -2})}) {
      EXPECT_EQ(solve_lemke(M, q).status, LcpStatus::RayTermination) << q.transpose();
      EXPECT_TRUE(enumerate_lcp_solutions(M, q).empty());
    }
  }
  {
    // M = [[P, -P], [-P, P]] (PSD): w_i + w_{k+i} = q_i + q_{k+i} for every z, so making
    // that sum negative leaves no feasible point.
    std::mt19937 rng(7);
    for (int t = 0; t < 20; ++t) {
      const int k = 1 + t % 5;
      Eigen::MatrixXd P = lcp_test::random_spd(rng, k);
      Eigen::MatrixXd M(2 * k, 2 * k);
      M << P, -P, -P, P;
      Eigen::VectorXd q = lcp_test::random_vector(rng, 2 * k);
      q(k) = -q(0) - 1.0;  // w_0 + w_k = -1
      EXPECT_EQ(solve_lemke(M, q).status, LcpStatus::RayTermination);
      if (2 * k <= 8) {
        EXPECT_TRUE(enumerate_lcp_solutions(M, q).empty());
      }
    }
  }
}

TEST(Lemke, IterationLimit) {
  std::mt19937 rng(8);
  Eigen::MatrixXd M = lcp_test::random_spd(rng, 4);
  Eigen::VectorXd q = -Eigen::VectorXd::Ones(4);
  LcpSolution full = expect_solved(M, q);
  ASSERT_GT(full.pivots, 1);
  LemkeOptions o;
  o.max_pivots = 1;
  LcpSolution s = solve_lemke(M, q, o);
  EXPECT_EQ(s.status, LcpStatus::IterationLimit);
  EXPECT_EQ(s.pivots, 1);
  o.max_pivots = full.pivots - 1;
  EXPECT_EQ(solve_lemke(M, q, o).status, LcpStatus::IterationLimit);
  o.max_pivots = full.pivots;
  EXPECT_EQ(solve_lemke(M, q, o).status, LcpStatus::Solved);
}

// Rows and columns scaled by 1e-9 .. 1e9: D1 M D2 z' + D1 q has the solution z' = D2^{-1} z.
TEST(Lemke, BadlyScaledRowsAndColumns) {
  std::mt19937 rng(9);
  const double scales[] = {1e-9, 1e-3, 1.0, 1e3, 1e9};
  std::uniform_int_distribution<int> pick(0, 4);
  for (int n = 2; n <= 15; ++n)
    for (int t = 0; t < 6; ++t) {
      Eigen::MatrixXd M = t % 2 ? lcp_test::random_p_matrix(rng, n) : lcp_test::random_spd(rng, n);
      lcp_test::Planted p = planted(rng, M, 0.5);
      Eigen::VectorXd d1(n), d2(n);
      for (int i = 0; i < n; ++i) {
        d1(i) = scales[pick(rng)];
        d2(i) = t >= 3 ? scales[pick(rng)] : 1.0;  // rows only, then rows and columns
      }
      Eigen::MatrixXd Ms = d1.asDiagonal() * M * d2.asDiagonal();
      Eigen::VectorXd qs = d1.cwiseProduct(p.q);
      LcpSolution s = solve_lemke(Ms, qs);
      ASSERT_EQ(s.status, LcpStatus::Solved);
      EXPECT_LE(relative_residual(Ms, qs, s.z), 1e-9);
      Eigen::VectorXd z = d2.cwiseProduct(s.z);  // back to the unscaled problem
      EXPECT_LE(lcp_residual(M, p.q, z), abs_tol(M, p.q, z));
      EXPECT_LE((z - p.z).cwiseAbs().maxCoeff(), 1e-8 * (1 + p.z.norm()));
    }
}

// Diode-circuit-like: M = B^T G^{-1} B with G a nodal conductance matrix whose conductances
// span 1e-9 .. 1e9 S (SPD, condition number up to ~1e18 in the raw entries).
TEST(Lemke, WideDynamicRangeCircuitMatrix) {
  std::mt19937 rng(10);
  std::uniform_real_distribution<double> expo(-9, 9);
  std::uniform_int_distribution<int> node;
  int solved = 0;
  for (int t = 0; t < 30; ++t) {
    const int nodes = 6 + t % 10, diodes = 2 + t % 7;
    Eigen::MatrixXd G = Eigen::MatrixXd::Zero(nodes, nodes);
    for (int i = 0; i < nodes; ++i) G(i, i) += std::pow(10.0, expo(rng));  // to ground
    for (int e = 0; e < 2 * nodes; ++e) {
      int a = node(rng) % nodes, b = node(rng) % nodes;
      if (a == b) continue;
      double g = std::pow(10.0, expo(rng));
      G(a, a) += g, G(b, b) += g, G(a, b) -= g, G(b, a) -= g;
    }
    Eigen::MatrixXd B = Eigen::MatrixXd::Zero(nodes, diodes);
    for (int d = 0; d < diodes; ++d) {
      int a = node(rng) % nodes, b = node(rng) % nodes;
      B(a, d) += 1;
      if (a != b) B(b, d) -= 1;
    }
    Eigen::MatrixXd M = B.transpose() * G.ldlt().solve(B);
    M = 0.5 * (M + M.transpose());
    Eigen::VectorXd q = lcp_test::random_vector(rng, diodes);
    for (int i = 0; i < diodes; ++i) q(i) *= std::pow(10.0, expo(rng) / 3);
    LcpSolution s = solve_lemke(M, q);
    if (s.status != LcpStatus::Solved) {
      // M is PSD (copositive plus): only a provably infeasible problem may end on a ray.
      EXPECT_EQ(s.status, LcpStatus::RayTermination);
      EXPECT_TRUE(enumerate_lcp_solutions(M, q).empty()) << "t=" << t;
      continue;
    }
    ++solved;
    EXPECT_LE(relative_residual(M, q, s.z), 1e-8) << "t=" << t;
  }
  EXPECT_GT(solved, 20);
}

// Strictly copositive (nonnegative, positive diagonal) with degenerate q (zeros, ties):
// Lemke cannot end on a ray, so it must solve, with few pivots.
TEST(Lemke, DegenerateStrictlyCopositive) {
  std::mt19937 rng(11);
  int max_pivots_seen = 0;
  for (int t = 0; t < 3000; ++t) {
    const int n = 2 + t % 7;
    const auto [M, q] = lcp_test::random_degenerate_integer_problem(rng, n);
    LcpSolution s = expect_solved(M, q, 1e-12);
    EXPECT_LE(s.pivots, 4 * (n + 1)) << "M=\n" << M << "\nq=" << q.transpose();
    max_pivots_seen = std::max(max_pivots_seen, s.pivots);
  }
  RecordProperty("max_pivots_seen", max_pivots_seen);
}

// Murty's example: M lower triangular with 1 on the diagonal and 2 below, q = -1. A P-matrix
// (unique solution z = e_1) on which Lemke with d = 1 needs 2^n pivots. Exercises the
// periodic refactorisation of the basis inverse (every max(64, n) pivots) and shows that the
// default max_pivots = 50 (n + 1) is exceeded for n >= 9.
TEST(Lemke, MurtyExponentialExample) {
  for (int n = 1; n <= 12; ++n) {
    Eigen::MatrixXd M = Eigen::MatrixXd::Identity(n, n);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < i; ++j) M(i, j) = 2;
    const Eigen::VectorXd q = -Eigen::VectorXd::Ones(n);
    LemkeOptions o;
    o.max_pivots = (1 << n) + 1;
    LcpSolution s = solve_lemke(M, q, o);
    ASSERT_EQ(s.status, LcpStatus::Solved) << n;
    EXPECT_EQ(s.pivots, 1 << n);
    Eigen::VectorXd e1 = Eigen::VectorXd::Zero(n);
    e1(0) = 1;
    EXPECT_EQ(s.z, e1);
    EXPECT_EQ(lcp_residual(M, q, s.z), 0.0);
    EXPECT_EQ(solve_lemke(M, q).status,
              (1 << n) > 50 * (n + 1) ? LcpStatus::IterationLimit : LcpStatus::Solved);
  }
}

// Zero rows/columns (e.g. a diode with no coupling): w_i = q_i whatever z is.
TEST(Lemke, ZeroRowsAndColumns) {
  Eigen::MatrixXd M(3, 3);
  M << 0, 0, 0,
       0, 2, 1,
       0, 1, 2;
  LcpSolution s = expect_solved(M, vec({1, -1, 1}));
  EXPECT_LE((s.z - vec({0, 0.5, 0})).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_EQ(solve_lemke(M, vec({-1, -1, 1})).status, LcpStatus::RayTermination);
  expect_solved(Eigen::MatrixXd::Zero(2, 2), vec({0, 3}));
  EXPECT_EQ(solve_lemke(Eigen::MatrixXd::Zero(2, 2), vec({0, -3})).status,
            LcpStatus::RayTermination);
}

// Intrinsically ill-conditioned M (SPD, condition 1e12 after any diagonal scaling): Lemke may
// fail, but then says so (NumericalFailure); whatever it calls Solved is accurate.
TEST(Lemke, IllConditionedNeverClaimsFalseSuccess) {
  std::mt19937 rng(12);
  int solved = 0, failed = 0;
  for (int n : {30, 60, 100}) {
    Eigen::MatrixXd Q =
        Eigen::HouseholderQR<Eigen::MatrixXd>(lcp_test::random_matrix(rng, n, n)).householderQ();
    Eigen::VectorXd ev(n);
    for (int i = 0; i < n; ++i) ev(i) = std::pow(1e12, -double(i) / (n - 1));
    Eigen::MatrixXd M = Q * ev.asDiagonal() * Q.transpose();
    M = 0.5 * (M + M.transpose());
    for (int t = 0; t < 6; ++t) {
      lcp_test::Planted p = planted(rng, M, 0.5 + 0.05 * t, t % 2 == 1);
      LcpSolution s = solve_lemke(M, p.q);
      ASSERT_TRUE(s.status == LcpStatus::Solved || s.status == LcpStatus::NumericalFailure)
          << lcp_status_name(s.status);
      if (s.status == LcpStatus::Solved) {
        ++solved;
        EXPECT_LE(relative_residual(M, p.q, s.z), 1e-8) << "n=" << n << " t=" << t;
      } else {
        ++failed;
      }
    }
  }
  EXPECT_GT(solved, failed);
  RecordProperty("numerical_failures", failed);
}

}  // namespace
}  // namespace lcs

namespace lcs {
namespace {

// The pattern of a node reached only through two junctions (event_next_mode_test.cpp): a link
// diode (row 0: its voltage margin, 502 its resistance path, +1 the other's reverse voltage) and
// a reverse-biased tree junction (row 1: its current, minus the link's). The solution
// z = (0, 3.61), w = (0, 0) leaves pair 0 degenerate; the basis must hold z_0 (at zero), or
// M_JJ over J = {z > 0} = {1} is the singular [0]. basic_z names it.
TEST(Lemke, BasicSetHoldsTheDegeneratePairThatFixesTheOthers) {
  Eigen::MatrixXd M(2, 2);
  M << 502, 1, -1, 0;
  Eigen::VectorXd q(2);
  q << -3.61, 0;
  const LcpSolution s = solve_lemke(M, q);
  ASSERT_EQ(s.status, LcpStatus::Solved);
  EXPECT_EQ(s.z(0), 0.0);
  EXPECT_NEAR(s.z(1), 3.61, 1e-12);
  EXPECT_EQ(s.basic_z, (std::vector<int>{0, 1}));
}

TEST(Lemke, BasicSetIsEmptyWithoutPivots) {
  const LcpSolution s = solve_lemke(Eigen::MatrixXd::Identity(2, 2), Eigen::VectorXd::Ones(2));
  EXPECT_TRUE(s.basic_z.empty());
}

}  // namespace
}  // namespace lcs
