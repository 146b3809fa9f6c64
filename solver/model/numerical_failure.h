// A numerical failure during analysis (no solution, LCP failure, ...): exit code 3 (SPEC §4).
#pragma once

#include <cstdio>
#include <stdexcept>
#include <string>

namespace lcs {

class NumericalFailure : public std::runtime_error {
 public:
  NumericalFailure(double time, const std::string& why)
      : std::runtime_error("at t = " + format_time(time) + ": " + why), time_(time) {}
  double time() const { return time_; }

 private:
  static std::string format_time(double t) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.9g s", t);
    return buf;
  }
  double time_;
};

}  // namespace lcs
