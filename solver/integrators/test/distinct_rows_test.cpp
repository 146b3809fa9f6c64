// SPEC §3: printed times strictly increase. An event a few ulps from a grid time is merged
// into the grid row (issue 9, defect 2: smooth wrote equal consecutive times).
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "solver/integrators/distinct_rows.h"

namespace lcs {
namespace {

struct Written {
  std::vector<double> t, x;
};

DistinctRows rows_into(Written& w) {
  return DistinctRows([&w](double t, const Eigen::VectorXd& x, const Eigen::VectorXd&) {
    w.t.push_back(t);
    w.x.push_back(x(0));
  });
}

Eigen::VectorXd v(double a) { return Eigen::VectorXd::Constant(1, a); }

TEST(DistinctRows, AnEventJustBeforeAGridTimeGivesWayToTheGridRow) {
  Written w;
  DistinctRows rows = rows_into(w);
  const double grid = 0.01, event = std::nextafter(std::nextafter(grid, 0.0), 0.0);
  ASSERT_TRUE(same_printed_time(event, grid));
  rows.add(0.0, v(0), v(0), false);
  rows.add(event, v(1), v(0), true);
  rows.add(grid, v(2), v(0), false);
  rows.add(0.02, v(3), v(0), false);
  rows.flush();
  EXPECT_EQ(w.t, (std::vector<double>{0.0, grid, 0.02}));
  EXPECT_EQ(w.x, (std::vector<double>{0, 2, 3}));
}

TEST(DistinctRows, AnEventJustAfterAGridTimeIsDropped) {
  Written w;
  DistinctRows rows = rows_into(w);
  const double grid = 0.01, event = std::nextafter(grid, 1.0);
  rows.add(grid, v(2), v(0), false);
  rows.add(event, v(1), v(0), true);
  rows.flush();
  EXPECT_EQ(w.t, (std::vector<double>{grid}));
  EXPECT_EQ(w.x, (std::vector<double>{2}));
}

TEST(DistinctRows, TwoEventsPrintingAlikeKeepTheFirstAndDistinctOnesAllStay) {
  Written w;
  DistinctRows rows = rows_into(w);
  const double e1 = 0.0123456789, e2 = std::nextafter(e1, 1.0), e3 = e1 * (1 + 1e-13);
  ASSERT_FALSE(same_printed_time(e1, e3));
  rows.add(e1, v(1), v(0), true);
  rows.add(e2, v(2), v(0), true);
  rows.add(e3, v(3), v(0), true);
  rows.flush();
  rows.add(e3, v(4), v(0), false);  // after a flush: at the last written time
  rows.flush();
  EXPECT_EQ(w.t, (std::vector<double>{e1, e3}));
  EXPECT_EQ(w.x, (std::vector<double>{1, 3}));
}

}  // namespace
}  // namespace lcs
