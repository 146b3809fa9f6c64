// enumerate_lcp_solutions: exact solution sets of small LCPs (checked by hand), deduplication,
// ordering, agreement with Lemke.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <stdexcept>

#include "solver/lcp/lcp.h"
#include "solver/lcp/test/test_util.h"

namespace lcs {
namespace {

Eigen::VectorXd vec(std::initializer_list<double> v) {
  Eigen::VectorXd x(v.size());
  int i = 0;
  for (double a : v) x(i++) = a;
  return x;
}

void expect_solution_set(const std::vector<Eigen::VectorXd>& got,
                         const std::vector<Eigen::VectorXd>& want, double tol = 1e-14) {
  ASSERT_EQ(got.size(), want.size());
  for (size_t i = 0; i < got.size(); ++i)
    EXPECT_LE((got[i] - want[i]).cwiseAbs().maxCoeff(), tol) << i << ": " << got[i].transpose();
}

// M = [[-1, 2], [2, -1]], q = (1, 1). By hand, over the four active sets:
//   {}     z = 0,            w = (1, 1) >= 0                 -> solution
//   {1}    z1 = q1 = 1,      w2 = 2 z1 + q2 = 3 >= 0         -> (1, 0)
//   {2}    z2 = q2 = 1,      w1 = 3 >= 0                     -> (0, 1)
//   {1,2}  z = -M^{-1} q = -(1/3)[[1, 2], [2, 1]] q = (-1, -1) -> rejected
TEST(Enumeration, NonPMatrixWithExactlyThreeSolutions) {
  Eigen::MatrixXd M(2, 2);
  M << -1, 2, 2, -1;
  const Eigen::VectorXd q = vec({1, 1});
  std::vector<Eigen::VectorXd> all = enumerate_lcp_solutions(M, q);
  expect_solution_set(all, {vec({0, 0}), vec({0, 1}), vec({1, 0})});
  for (const Eigen::VectorXd& z : all) EXPECT_EQ(lcp_residual(M, q, z), 0.0);
  // Same matrix, q = (-1, -1): only {1,2} works, z = (1, 1).
  expect_solution_set(enumerate_lcp_solutions(M, vec({-1, -1})), {vec({1, 1})});
}

// M = -I, q = 1: each z_i in {0, 1} independently: 2^n solutions, sorted lexicographically.
TEST(Enumeration, AllVerticesOfTheCube) {
  const int n = 3;
  std::vector<Eigen::VectorXd> all =
      enumerate_lcp_solutions(-Eigen::MatrixXd::Identity(n, n), Eigen::VectorXd::Ones(n));
  std::vector<Eigen::VectorXd> want;
  for (int a : {0, 1})
    for (int b : {0, 1})
      for (int c : {0, 1}) want.push_back(vec({double(a), double(b), double(c)}));
  expect_solution_set(all, want);
}

// Continuum: M = [[1,1],[1,1]], q = (-1,-1) is solved by every z >= 0 with z1 + z2 = 1; M_JJ is
// singular for J = {1,2}, so only the vertex solutions are returned.
TEST(Enumeration, ContinuumReturnsVertices) {
  expect_solution_set(enumerate_lcp_solutions(Eigen::MatrixXd::Ones(2, 2), vec({-1, -1})),
                      {vec({0, 1}), vec({1, 0})});
}

// A degenerate solution reachable from several active sets is reported once.
TEST(Enumeration, Deduplicates) {
  // M = I, q = (0, -1): J = {2} and J = {1, 2} both give z = (0, 1).
  expect_solution_set(enumerate_lcp_solutions(Eigen::MatrixXd::Identity(2, 2), vec({0, -1})),
                      {vec({0, 1})});
  // Scaled by 1e9 / 1e-9: still one solution, deduplicated relative to its size.
  Eigen::MatrixXd M = Eigen::MatrixXd::Identity(2, 2);
  M(0, 0) = 1e9;
  M(1, 1) = 1e-9;
  std::vector<Eigen::VectorXd> all = enumerate_lcp_solutions(M, vec({0, -1}));
  ASSERT_EQ(all.size(), 1u);
  EXPECT_NEAR(all[0](1), 1e9, 1e-3);
}

TEST(Enumeration, EdgeCases) {
  std::vector<Eigen::VectorXd> e = enumerate_lcp_solutions(Eigen::MatrixXd(0, 0), Eigen::VectorXd(0));
  ASSERT_EQ(e.size(), 1u);
  EXPECT_EQ(e[0].size(), 0);
  EXPECT_THROW(enumerate_lcp_solutions(Eigen::MatrixXd::Identity(25, 25), Eigen::VectorXd::Ones(25)),
               std::invalid_argument);
  // q = 0 with M = I: z = 0 only.
  expect_solution_set(enumerate_lcp_solutions(Eigen::MatrixXd::Identity(3, 3), Eigen::VectorXd::Zero(3)),
                      {Eigen::VectorXd::Zero(3)});
}

// General random matrices: every enumerated point solves the LCP, the list is sorted and
// distinct, and whenever Lemke solves, its answer is in the list (data is generic, so the
// solution set is finite).
TEST(Enumeration, ConsistentWithLemkeOnGeneralMatrices) {
  std::mt19937 rng(31);
  int lemke_solved = 0, multi = 0;
  for (int t = 0; t < 400; ++t) {
    const int n = 1 + t % 6;
    Eigen::MatrixXd M = lcp_test::random_matrix(rng, n, n);
    Eigen::VectorXd q = lcp_test::random_vector(rng, n);
    std::vector<Eigen::VectorXd> all = enumerate_lcp_solutions(M, q);
    for (size_t i = 0; i < all.size(); ++i) {
      EXPECT_LE(lcp_residual(M, q, all[i]), lcp_test::abs_tol(M, q, all[i]));
      if (i > 0) {
        EXPECT_TRUE(std::lexicographical_compare(all[i - 1].data(), all[i - 1].data() + n,
                                                 all[i].data(), all[i].data() + n));
        EXPECT_GT((all[i] - all[i - 1]).cwiseAbs().maxCoeff(), 1e-6);
      }
    }
    multi += all.size() > 1;
    LcpSolution s = solve_lemke(M, q);
    if (s.status != LcpStatus::Solved) continue;
    ++lemke_solved;
    bool found = false;
    for (const Eigen::VectorXd& z : all)
      found = found || (z - s.z).cwiseAbs().maxCoeff() <= 1e-8 * (1 + z.norm());
    EXPECT_TRUE(found) << "M=\n" << M << "\nq=" << q.transpose() << "\nz=" << s.z.transpose();
  }
  EXPECT_GT(lemke_solved, 100);  // 159 with this seed; rays are legitimate for general M
  EXPECT_GT(multi, 10);
}

}  // namespace
}  // namespace lcs
