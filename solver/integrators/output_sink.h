// Where a transient's output rows go (CSV file, standard output, memory for tests).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Dense>

namespace lcs {

class OutputSink {
 public:
  virtual ~OutputSink() = default;
  virtual void begin(const std::vector<std::string>& names) = 0;
  virtual void row(double t, const Eigen::VectorXd& values) = 0;
  // Called once at the end, also after a numerical failure (rows so far are kept, SPEC §4).
  virtual void finish() = 0;
};

// Keeps every row; used by tests and by `bench`.
class MemorySink : public OutputSink {
 public:
  void begin(const std::vector<std::string>& n) override { names = n; }
  void row(double t, const Eigen::VectorXd& v) override {
    times.push_back(t);
    rows.push_back(v);
  }
  void finish() override { finished = true; }
  int column(const std::string& name) const {
    for (size_t k = 0; k < names.size(); ++k)
      if (names[k] == name) return static_cast<int>(k);
    return -1;
  }
  std::vector<std::string> names;
  std::vector<double> times;
  std::vector<Eigen::VectorXd> rows;
  bool finished = false;
};

}  // namespace lcs
