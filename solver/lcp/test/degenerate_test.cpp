// Degenerate LCPs where the plain minimum-ratio rule ties: the lexicographic rule must still
// terminate (Stewart 2.2.1, Lemma 2.9). A textbook Lemke with the plain rule is included as a
// reference and shown to cycle on problems that solve_lemke solves in a few pivots.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>
#include <vector>

#include "solver/lcp/lcp.h"
#include "solver/lcp/test/test_util.h"

namespace lcs {
namespace {

enum class Naive { Solved, Ray, Cycled };

// Dense tableau [I | -M | -1 | q], plain minimum ratio, ties to the smallest (or largest) row.
// Returns Cycled when a (basis, entering variable) state repeats.
Naive naive_lemke(const Eigen::MatrixXd& M, const Eigen::VectorXd& q, bool ties_to_largest) {
  const int n = static_cast<int>(M.rows());
  Eigen::MatrixXd T(n, 2 * n + 2);
  T.leftCols(n).setIdentity();
  T.middleCols(n, n) = -M;
  T.col(2 * n).setConstant(-1);
  T.col(2 * n + 1) = q;
  std::vector<int> basis(n);
  for (int i = 0; i < n; ++i) basis[i] = i;
  auto pivot = [&](int r, int c) {
    T.row(r) /= T(r, c);
    for (int i = 0; i < n; ++i)
      if (i != r) T.row(i) -= T(i, c) * T.row(r);
    basis[r] = c;
  };
  const double qmin = q.minCoeff();
  if (qmin >= 0) return Naive::Solved;
  int r = -1;
  for (int i = 0; i < n; ++i)
    if (q(i) <= qmin + 1e-12 && (r < 0 || ties_to_largest)) r = i;
  int leaving = basis[r];
  pivot(r, 2 * n);
  std::set<std::vector<int>> seen;
  for (;;) {
    if (leaving == 2 * n) return Naive::Solved;
    const int e = leaving < n ? leaving + n : leaving - n;
    std::vector<int> state = basis;
    state.push_back(e);
    if (!seen.insert(state).second) return Naive::Cycled;
    double tmin = 1e300;
    int rr = -1;
    for (int k = 0; k < n; ++k) {
      if (T(k, e) <= 1e-9) continue;
      const double t = std::max(T(k, 2 * n + 1), 0.0) / T(k, e);
      if (t < tmin - 1e-9) tmin = t, rr = k;
      else if (t <= tmin + 1e-9 && ties_to_largest) rr = k;
    }
    if (rr < 0) return Naive::Ray;
    leaving = basis[rr];
    pivot(rr, e);
  }
}

void expect_solved_quickly(const Eigen::MatrixXd& M, const Eigen::VectorXd& q, int max_pivots) {
  LcpSolution s = solve_lemke(M, q);
  ASSERT_EQ(s.status, LcpStatus::Solved) << "M=\n" << M << "\nq=" << q.transpose();
  EXPECT_LE(lcp_residual(M, q, s.z), 1e-12 * (1 + s.z.cwiseAbs().maxCoeff()))
      << "M=\n" << M << "\nq=" << q.transpose() << "\nz=" << s.z.transpose();
  EXPECT_LE(s.pivots, max_pivots);
}

// Found by random search over integer matrices with entries 0..3 and positive diagonal
// (strictly copositive, so Lemke cannot end on a ray) and integer q in -2..1.
TEST(Degenerate, PlainRuleCyclesLexicographicSolves) {
  struct Case {
    std::vector<double> M, q;
    bool ties_to_largest;
  } cases[] = {
      {{1, 0, 1, 1, 0, 0, 1, 0, 0, 1, 2, 0, 1, 0, 3, 0, 0, 0, 1, 3, 0, 3, 3, 1, 1},
       {-2, 0, -2, -2, -2},
       false},
      {{2, 3, 0, 1, 2, 3, 2, 3, 0, 1, 2, 3, 1, 3, 0, 1, 0, 0, 1, 0, 3, 2, 3, 3, 3},
       {-2, -2, 0, -2, -1},
       false},
      {{1, 3, 2, 1, 1, 3, 2, 0, 3, 3, 1, 3, 1, 1, 1, 3, 0, 1, 2, 3, 1, 1, 3, 1, 2},
       {-2, -2, 0, -2, -1},
       true},
      {{2, 2, 3, 2, 2, 2, 3, 1, 0, 0, 2, 0, 1, 2, 1, 0, 1, 0, 1, 3, 1, 3, 3, 1, 1},
       {-1, -1, -2, -2, -2},
       true},
  };
  for (const Case& c : cases) {
    Eigen::MatrixXd M = Eigen::Map<const Eigen::Matrix<double, 5, 5, Eigen::RowMajor>>(c.M.data());
    Eigen::VectorXd q = Eigen::Map<const Eigen::VectorXd>(c.q.data(), 5);
    EXPECT_EQ(naive_lemke(M, q, c.ties_to_largest), Naive::Cycled) << M << "\n" << q.transpose();
    expect_solved_quickly(M, q, 12);
  }
}

// All rows equal: every ratio ties. Solutions: z >= 0 with sum z = 1 (a continuum).
TEST(Degenerate, RankOneAllRowsEqual) {
  for (int n = 1; n <= 12; ++n) {
    Eigen::MatrixXd M = Eigen::MatrixXd::Ones(n, n);
    Eigen::VectorXd q = -Eigen::VectorXd::Ones(n);
    LcpSolution s = solve_lemke(M, q);
    ASSERT_EQ(s.status, LcpStatus::Solved);
    EXPECT_NEAR(s.z.sum(), 1.0, 1e-14);
    EXPECT_LE(lcp_residual(M, q, s.z), 1e-14);
    EXPECT_LE(s.pivots, 2);
  }
}

// Repeated rows in a strictly copositive matrix, equal q entries, zeros in q.
TEST(Degenerate, RepeatedRowsAndZeroQ) {
  Eigen::MatrixXd M(4, 4);
  M << 2, 1, 1, 0,
       2, 1, 1, 0,
       1, 1, 3, 1,
       0, 2, 0, 1;
  for (Eigen::VectorXd q : {Eigen::Vector4d(-1, -1, -1, -1), Eigen::Vector4d(-1, -1, 0, 0),
                            Eigen::Vector4d(0, -1, 0, -1), Eigen::Vector4d(-2, -2, 0, -1)}) {
    expect_solved_quickly(M, q, 10);
    EXPECT_FALSE(enumerate_lcp_solutions(M, q).empty());
  }
}

// Identity and SPD with q having zeros and ties, and P-matrices with planted degenerate
// solutions (z_i = w_i = 0 for some i).
TEST(Degenerate, ZerosAndTiesInQ) {
  std::mt19937 rng(21);
  for (int n = 2; n <= 12; ++n) {
    Eigen::VectorXd q = Eigen::VectorXd::Zero(n);
    for (int i = 0; i < n; i += 2) q(i) = -1;
    expect_solved_quickly(Eigen::MatrixXd::Identity(n, n), q, n + 2);
    Eigen::MatrixXd M = lcp_test::random_spd(rng, n);
    expect_solved_quickly(M, q, 4 * (n + 1));
    Eigen::MatrixXd P = lcp_test::random_p_matrix(rng, n);
    for (int t = 0; t < 10; ++t) {
      lcp_test::Planted p = lcp_test::planted(rng, P, 0.5, /*degenerate=*/true);
      LcpSolution s = solve_lemke(P, p.q);
      ASSERT_EQ(s.status, LcpStatus::Solved);
      EXPECT_LE((s.z - p.z).cwiseAbs().maxCoeff(), 1e-10 * (1 + p.z.norm()));
      EXPECT_LE(s.pivots, 4 * (n + 1));
    }
  }
}

// Many random degenerate problems: never cycles, never needs more than a few pivots.
TEST(Degenerate, RandomIntegerProblemsNeverCycle) {
  std::mt19937 rng(22);
  int plain_cycles = 0;
  for (int t = 0; t < 5000; ++t) {
    const int n = 3 + t % 4;
    const auto [M, q] = lcp_test::random_degenerate_integer_problem(rng, n);
    if (naive_lemke(M, q, false) == Naive::Cycled) ++plain_cycles;
    expect_solved_quickly(M, q, 4 * (n + 1));
    if (HasFailure()) return;
  }
  EXPECT_GT(plain_cycles, 0) << "the sample should contain cycling problems for the plain rule";
}

}  // namespace
}  // namespace lcs
