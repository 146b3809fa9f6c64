#include <gtest/gtest.h>
#include "solver/lcp/lcp.h"
#include "solver/lcp/test/test_util.h"
using namespace lcs;
TEST(Smoke, Basic) {
  std::mt19937 rng(1);
  for (int n = 1; n <= 30; ++n) for (int t = 0; t < 20; ++t) {
    Eigen::MatrixXd M = lcp_test::random_p_matrix(rng, n);
    auto p = lcp_test::planted(rng, M, 0.5);
    auto s = solve_lemke(M, p.q);
    ASSERT_EQ(s.status, LcpStatus::Solved) << n;
    ASSERT_LT((s.z - p.z).cwiseAbs().maxCoeff(), 1e-8) << n << " piv " << s.pivots;
  }
}
