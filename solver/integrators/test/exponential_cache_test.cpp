// The event method's exponential cache keeps within its byte budget, dropping the least
// recently used matrix first, and recomputes a dropped one on demand.
#include <gtest/gtest.h>

#include "solver/integrators/exponential_cache.h"

namespace lcs {
namespace {

TEST(ExponentialCache, DropsTheLeastRecentlyUsedPastTheBudget) {
  const std::size_t one = 10 * 10 * sizeof(double);
  ExponentialCache cache(3 * one);
  int computed = 0;
  auto matrix = [&](double v) {
    return [&computed, v] {
      ++computed;
      return Eigen::MatrixXd::Constant(10, 10, v);
    };
  };
  const int owner = 0;
  cache.get(&owner, 0, matrix(0));
  cache.get(&owner, 1, matrix(1));
  cache.get(&owner, 2, matrix(2));
  cache.get(&owner, 0, matrix(0));  // held: level 1 is now the least recently used
  EXPECT_EQ(computed, 3);
  cache.get(&owner, 3, matrix(3));  // drops level 1
  EXPECT_EQ(cache.evictions(), 1);
  EXPECT_EQ(cache.peak_bytes(), 3 * one);
  EXPECT_EQ(cache.get(&owner, 0, matrix(-1))(0, 0), 0.0);  // still held
  EXPECT_EQ(computed, 4);
  EXPECT_EQ(cache.get(&owner, 1, matrix(1))(0, 0), 1.0);  // recomputed
  EXPECT_EQ(computed, 5);
  EXPECT_EQ(cache.evictions(), 2);
}

TEST(ExponentialCache, KeepsOneMatrixLargerThanTheBudget) {
  ExponentialCache cache(8);
  const int owner = 0;
  EXPECT_EQ(cache.get(&owner, 0, [] { return Eigen::MatrixXd::Identity(4, 4); })(3, 3), 1.0);
  EXPECT_EQ(cache.get(&owner, 1, [] { return Eigen::MatrixXd::Identity(5, 5); })(4, 4), 1.0);
  EXPECT_EQ(cache.evictions(), 1);
}

TEST(ExponentialCache, DropsEveryMatrixOfOneOwner) {
  const std::size_t one = 4 * 4 * sizeof(double);
  ExponentialCache cache(10 * one);
  const int a = 0, b = 0;
  int computed = 0;
  auto identity = [&computed] {
    ++computed;
    return Eigen::MatrixXd::Identity(4, 4);
  };
  cache.get(&a, 0, identity);
  cache.get(&b, 0, identity);
  cache.get(&a, 1, identity);
  cache.drop(&a);
  EXPECT_EQ(cache.evictions(), 0);  // dropped with their owner, not for the budget
  cache.get(&b, 0, identity);       // still held
  EXPECT_EQ(computed, 3);
  cache.get(&a, 0, identity);  // computed again
  cache.get(&a, 1, identity);
  EXPECT_EQ(computed, 5);
  EXPECT_EQ(cache.peak_bytes(), 3 * one);
}

}  // namespace
}  // namespace lcs
