// The blocks of pairs an LCP matrix M = Q - P K^-1 L couples, and its blocks formed by sparse
// solves (pair_blocks.h), against the dense M.
#include <gtest/gtest.h>

#include "solver/model/pair_blocks.h"

namespace lcs {
namespace {

using Sparse = Eigen::SparseMatrix<double>;

Sparse sparse(const Eigen::MatrixXd& dense) { return dense.sparseView(); }

// K has two components, unknowns {0, 1} and {2, 3}. Pairs 0 and 2 meet the first (pair 0 by
// its column of L, pair 2 by its row of P), pair 1 the second, and pair 3 meets none but is
// coupled to pair 1 by Q.
struct Example {
  Eigen::MatrixXd K{{4, 1, 0, 0}, {1, 3, 0, 0}, {0, 0, 5, -2}, {0, 0, 1, 2}};
  Eigen::MatrixXd L{{1, 0, 0, 0}, {0, 0, 0, 0}, {0, 2, 0, 0}, {0, 0, 0, 0}};
  Eigen::MatrixXd P{{0, 1, 0, 0}, {0, 0, 0, 3}, {1, 0, 0, 0}, {0, 0, 0, 0}};
  Eigen::MatrixXd Q{{2, 0, 0, 0}, {0, 1, 0, 0.5}, {0, 0, 1, 0}, {0, -0.5, 0, 1}};
  Eigen::MatrixXd M() const { return Q - P * K.inverse() * L; }
};

TEST(PairBlocks, PairsSplitWhereKsComponentsAndQDoNotMeet) {
  const Example e;
  const std::vector<std::vector<int>> blocks =
      coupled_pair_blocks(sparse(e.K), sparse(e.L), sparse(e.P), sparse(e.Q));
  ASSERT_EQ(blocks.size(), 2u);
  EXPECT_EQ(blocks[0], (std::vector<int>{0, 2}));
  EXPECT_EQ(blocks[1], (std::vector<int>{1, 3}));
  // M has no entry between the blocks.
  const Eigen::MatrixXd M = e.M();
  for (int i : blocks[0])
    for (int j : blocks[1]) {
      EXPECT_EQ(M(i, j), 0.0) << i << ", " << j;
      EXPECT_EQ(M(j, i), 0.0) << j << ", " << i;
    }
}

TEST(PairBlocks, BlocksFormedBySparseSolvesEqualTheDenseMatrix) {
  const Example e;
  const std::optional<SchurBlocks> s = SchurBlocks::make(sparse(e.K), sparse(e.L), sparse(e.P), sparse(e.Q));
  ASSERT_TRUE(s.has_value());
  const Eigen::MatrixXd M = e.M();
  const Eigen::MatrixXd b0 = s->block({0, 2}), b1 = s->block({1, 3});
  // M_00 = 2 - P_0 K^-1 L_0 = 2 - (K^-1)_10 = 2 + 1/11; M_20 = -(K^-1)_00 = -3/11.
  EXPECT_NEAR(b0(0, 0), 2 + 1.0 / 11, 1e-15);
  EXPECT_NEAR(b0(1, 0), -3.0 / 11, 1e-15);
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b) {
      EXPECT_NEAR(b0(a, b), M(a * 2, b * 2), 1e-14);
      EXPECT_NEAR(b1(a, b), M(1 + a * 2, 1 + b * 2), 1e-14);
    }
}

TEST(PairBlocks, DiagonalDominanceOfTheSymmetricPart) {
  const Example e;
  const std::optional<SchurBlocks> s = SchurBlocks::make(sparse(e.K), sparse(e.L), sparse(e.P), sparse(e.Q));
  ASSERT_TRUE(s.has_value());
  // Block {0, 2}: M = [2 + 1/11, 0; -3/11, 1]: 1 > (3/11) / 2 and 2 + 1/11 > (3/11) / 2.
  EXPECT_TRUE(s->symmetric_part_dominant({0, 2}));
  // Block {1, 3}: M_11 = 1 - 3 * 2 * (K^-1)_31 with (K^-1)_32 = -1/12, so 1.5; M_13 = 0.5,
  // M_31 = -0.5, M_33 = 1: off sums (0.5 + 0.5) / 2 = 0.5 < 1: dominant.
  EXPECT_NEAR(s->block({1, 3})(0, 0), 1.5, 1e-14);
  EXPECT_TRUE(s->symmetric_part_dominant({1, 3}));
  // Q_33 = 0.4 is below 0.5: not dominant (though the block is still a P-matrix).
  Example weak;
  weak.Q(3, 3) = 0.4;
  const std::optional<SchurBlocks> w =
      SchurBlocks::make(sparse(weak.K), sparse(weak.L), sparse(weak.P), sparse(weak.Q));
  EXPECT_FALSE(w->symmetric_part_dominant({1, 3}));
}

TEST(PairBlocks, ASingularKIsLeftToTheDensePath) {
  Example e;
  e.K(2, 2) = 0;
  e.K(2, 3) = 0;  // row 2 of K empty: structurally singular
  EXPECT_FALSE(SchurBlocks::make(sparse(e.K), sparse(e.L), sparse(e.P), sparse(e.Q)).has_value());
}

}  // namespace
}  // namespace lcs
