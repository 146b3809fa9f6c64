// Rows of an adaptive method with times that stay distinct as printed (SPEC §3: the CSV's times
// strictly increase at 15 significant digits). An event located within a few ulps of a grid
// time (or of another event) would print as a second row at the same time; the grid row wins,
// else the first of the two.
#pragma once

#include <cstdio>
#include <cstring>
#include <functional>
#include <optional>

#include <Eigen/Dense>

namespace lcs {

// True when a and b print alike in the CSV's "%.14e".
inline bool same_printed_time(double a, double b) {
  char sa[32], sb[32];
  std::snprintf(sa, sizeof sa, "%.14e", a);
  std::snprintf(sb, sizeof sb, "%.14e", b);
  return std::strcmp(sa, sb) == 0;
}

// Holds back one row so that a grid row arriving just after an event row can replace it.
class DistinctRows {
 public:
  using Write = std::function<void(double t, const Eigen::VectorXd& x, const Eigen::VectorXd& z)>;
  explicit DistinctRows(Write write) : write_(std::move(write)) {}

  // Rows at or before the last kept time are dropped (an event on a grid time).
  void add(double t, const Eigen::VectorXd& x, const Eigen::VectorXd& z, bool event) {
    if (held_ && t <= held_->t) return;
    if (!held_ && (t <= written_ || same_printed_time(t, written_))) return;  // after a flush
    if (held_ && same_printed_time(t, held_->t)) {
      if (event || !held_->event) return;  // keep the held row
      held_->t = t;                          // a grid row replaces a held event row
      held_->x = x;
      held_->z = z;
      held_->event = false;
      return;
    }
    flush();
    held_ = Row{t, x, z, event};
  }
  // Writes the held row; call at the end and before reporting a failure.
  void flush() {
    if (!held_) return;
    write_(held_->t, held_->x, held_->z);
    written_ = held_->t;
    held_.reset();
  }

 private:
  struct Row {
    double t;
    Eigen::VectorXd x, z;
    bool event;
  };
  Write write_;
  std::optional<Row> held_;
  double written_ = -1;  // time of the last row written (times start at 0)
};

}  // namespace lcs
