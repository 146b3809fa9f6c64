// The inputs u(t) of an LCS, as the integrators see them (they never see the netlist):
// u[0] = 1 carries the thresholds VON; u[k], k >= 1, is the k-th independent source's value.
// History inputs (transmission lines) are inputs too: u[k] = a wave that left a line port
// `delay` earlier, read from the DelayHistory the integrators keep up to date.
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Dense>

#include "netlist/waveform.h"
#include "solver/model/delay_history.h"

namespace lcs {

struct InputSignal {
  enum class Quantity { One, Voltage, Current, History };
  Quantity quantity = Quantity::One;  // One: the constant input u[0] = 1
  std::string label;                  // the source's name ("v1"), "1" for u[0]; "t1.port2" for a wave
  int element = -1;                   // index into Netlist::elements; -1 for u[0]
  Waveform waveform;                  // ngspice semantics (DC for u[0], value 1)
  int history = -1;                   // History: index of its wave in the DelayHistory
};

class InputProvider {
 public:
  InputProvider();  // u[0] = 1 only
  explicit InputProvider(std::vector<InputSignal> sources);  // u[1..] = sources

  int size() const { return static_cast<int>(signals_.size()); }
  const InputSignal& operator[](int k) const { return signals_[k]; }
  const std::vector<InputSignal>& signals() const { return signals_; }

  Eigen::VectorXd values(double t) const;
  void values(double t, Eigen::Ref<Eigen::VectorXd> u) const;  // without allocating
  Eigen::VectorXd values_before(double t) const;                // limits from the left
  Eigen::VectorXd derivatives(double t) const;                  // right derivatives
  // Corners of every input in (t0, t1), sorted, duplicates kept (history inputs excluded: their
  // corners arrive as the run makes them, DelayHistory::next_arrival).
  std::vector<double> breakpoints(double t0, double t1) const;

  // History inputs read this; shared by the copies of a model, reset at the start of every run.
  void attach_history(std::shared_ptr<DelayHistory> history) { history_ = std::move(history); }
  const std::shared_ptr<DelayHistory>& history() const { return history_; }

 private:
  std::vector<InputSignal> signals_;
  std::shared_ptr<DelayHistory> history_;
};

}  // namespace lcs
