// lcp_residual and lcp_status_name.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "solver/lcp/lcp.h"

namespace lcs {
namespace {

TEST(LcpResidual, ZeroExactlyAtSolution) {
  Eigen::MatrixXd M(2, 2);
  M << 2, 1, 1, 2;
  Eigen::VectorXd q(2), z(2);
  q << -1, -1;
  z << 1.0 / 3, 1.0 / 3;  // w = 0 up to rounding
  EXPECT_LT(lcp_residual(M, q, z), 1e-15);
  q << -1, 1;
  z << 0.5, 0.0;  // w = (0, 1.5)
  EXPECT_EQ(lcp_residual(M, q, z), 0.0);
}

TEST(LcpResidual, MeasuresEachViolation) {
  Eigen::MatrixXd M = Eigen::MatrixXd::Identity(3, 3);
  Eigen::VectorXd q(3), z(3);
  q << 0, 0, 0;
  z << 2, 0, 0;              // w = z: complementarity violated by min(2, 2) = 2
  EXPECT_DOUBLE_EQ(lcp_residual(M, q, z), 2.0);
  q << 5, 5, 5;
  z << -0.25, 0, 0;          // z negative, w = 4.75 >= 0
  EXPECT_DOUBLE_EQ(lcp_residual(M, q, z), 0.25);
  q << -3, 0, 0;
  z << 0, 0, 0;              // w_1 = -3
  EXPECT_DOUBLE_EQ(lcp_residual(M, q, z), 3.0);
  q << -3, 0, 0;
  z << 3.5, 0, 0;            // w_1 = 0.5, z_1 = 3.5: min = 0.5
  EXPECT_DOUBLE_EQ(lcp_residual(M, q, z), 0.5);
}

TEST(LcpResidual, EmptyAndSizeMismatch) {
  EXPECT_EQ(lcp_residual(Eigen::MatrixXd(0, 0), Eigen::VectorXd(0), Eigen::VectorXd(0)), 0.0);
  EXPECT_THROW(lcp_residual(Eigen::MatrixXd::Identity(2, 2), Eigen::VectorXd::Zero(2),
                            Eigen::VectorXd::Zero(3)),
               std::invalid_argument);
}

TEST(LcpResidual, NanIsInfinite) {
  Eigen::MatrixXd M = Eigen::MatrixXd::Identity(1, 1);
  Eigen::VectorXd q = Eigen::VectorXd::Zero(1), z(1);
  z << std::nan("");
  EXPECT_TRUE(std::isinf(lcp_residual(M, q, z)));
}

TEST(LcpStatusName, AllNamed) {
  EXPECT_EQ(std::string(lcp_status_name(LcpStatus::Solved)), "solved");
  EXPECT_EQ(std::string(lcp_status_name(LcpStatus::RayTermination)), "ray termination");
  EXPECT_EQ(std::string(lcp_status_name(LcpStatus::IterationLimit)), "iteration limit");
  EXPECT_EQ(std::string(lcp_status_name(LcpStatus::NumericalFailure)), "numerical failure");
}

}  // namespace
// lcp_solved_to_rounding: each w_i to the rounding of its own row's products, z to the data's.
// A loop through 1 TOhm beside 0.05 Ohm: both pairs conduct, z = (13.7 + 5e-13, 13.7) exactly,
// and w_0 = 2e12 (z_0 - z_1) - 1 cannot be computed better than 2e12 ulp(13.7) = 3.6e-3 (its
// row's products are 2.7e13; here it comes out -3.9e-3, and w_1 2.5e-3).
TEST(LcpSolvedToRounding, ToleratesEachRowsOwnRounding) {
  Eigen::MatrixXd M(2, 2);
  M << 2e12, -2e12, -2e12, 2e12 + 0.05;
  Eigen::VectorXd q(2), z(2);
  q << -1, 1 - 0.05 * 13.7;
  z << 13.7 + 5e-13, 13.7;
  ASSERT_GT(std::abs((M * z + q)(0)), 1e-4);  // the rounding the natural residual cannot pass
  EXPECT_FALSE(lcp_residual(M, q, z) <= 1e-10 * 13.7);
  EXPECT_TRUE(lcp_solved_to_rounding(M, q, z, 1e-10));
  z << 13.7 + 1.5e-12, 13.7;  // w_0 = +2 beside z_0 > 0: not complementary, in any rounding
  EXPECT_FALSE(lcp_solved_to_rounding(M, q, z, 1e-10));
  z << 13.7, 13.7;  // w_0 = -1
  EXPECT_FALSE(lcp_solved_to_rounding(M, q, z, 1e-10));
}

TEST(LcpSolvedToRounding, RejectsWhatTheNaturalResidualRejectsInOrdinaryRows) {
  Eigen::MatrixXd M(2, 2);
  M << 2, 1, 1, 2;
  Eigen::VectorXd q(2), z(2);
  q << -1, 1;
  z << 0.5, 0.0;  // w = (0, 1.5): solved
  EXPECT_TRUE(lcp_solved_to_rounding(M, q, z, 1e-10));
  z << 0.5 + 1e-8, 0.0;  // w_0 = 2e-8 with z_0 > 0
  EXPECT_FALSE(lcp_solved_to_rounding(M, q, z, 1e-10));
  z << 0.5, -1e-8;  // z_1 < 0
  EXPECT_FALSE(lcp_solved_to_rounding(M, q, z, 1e-10));
  q << -1, -1;
  z << 0.5, 0.0;  // w_1 = -0.5
  EXPECT_FALSE(lcp_solved_to_rounding(M, q, z, 1e-10));
  z << NAN, 0.0;
  EXPECT_FALSE(lcp_solved_to_rounding(M, q, z, 1e-10));
}

}  // namespace lcs
