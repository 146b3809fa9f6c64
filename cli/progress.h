// Progress of long runs on standard error, only when it is a terminal (quiet in pipes, logs, CI).
#pragma once

#include <chrono>
#include <string>

namespace lcs {

class ProgressLine {
 public:
  explicit ProgressLine(std::string label);
  ~ProgressLine();  // erases the line
  bool enabled() const { return enabled_; }
  // Redraws "label  42%" at most a few times per second.
  void update(double fraction, const std::string& detail = "");
  void set_label(std::string label) { label_ = std::move(label); }

 private:
  std::string label_;
  bool enabled_;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point last_;
};

}  // namespace lcs
