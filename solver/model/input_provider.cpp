#include "solver/model/input_provider.h"

#include <algorithm>

namespace lcs {

namespace {
InputSignal constant_one() {
  InputSignal one;
  one.label = "1";
  one.waveform.dc = 1.0;
  return one;
}
}  // namespace

InputProvider::InputProvider() : signals_{constant_one()} {}

InputProvider::InputProvider(std::vector<InputSignal> sources) : signals_{constant_one()} {
  for (InputSignal& s : sources) signals_.push_back(std::move(s));
}

Eigen::VectorXd InputProvider::values(double t) const {
  Eigen::VectorXd u(signals_.size());
  values(t, u);
  return u;
}

void InputProvider::values(double t, Eigen::Ref<Eigen::VectorXd> u) const {
  u(0) = 1.0;
  for (size_t k = 1; k < signals_.size(); ++k)
    u(k) = signals_[k].history >= 0 ? history_->value(signals_[k].history, t) : signals_[k].waveform.value(t);
}

Eigen::VectorXd InputProvider::values_before(double t) const {
  Eigen::VectorXd u(signals_.size());
  u(0) = 1.0;
  for (size_t k = 1; k < signals_.size(); ++k)
    u(k) = signals_[k].history >= 0 ? history_->value(signals_[k].history, t) : signals_[k].waveform.value_before(t);
  return u;
}

Eigen::VectorXd InputProvider::derivatives(double t) const {
  Eigen::VectorXd du(signals_.size());
  du(0) = 0.0;
  // A history input enters only resistive relations (a line port), never a source loop's
  // Gamma u': its derivative is not needed.
  for (size_t k = 1; k < signals_.size(); ++k)
    du(k) = signals_[k].history >= 0 ? 0.0 : signals_[k].waveform.derivative(t);
  return du;
}

std::vector<double> InputProvider::breakpoints(double t0, double t1) const {
  std::vector<double> out;
  for (size_t k = 1; k < signals_.size(); ++k)
    if (signals_[k].history < 0)
      for (double b : signals_[k].waveform.breakpoints(t0, t1)) out.push_back(b);
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace lcs
