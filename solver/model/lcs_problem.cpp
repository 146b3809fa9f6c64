#include "solver/model/lcs_problem.h"

#include <algorithm>
#include <limits>

#include "solver/devices/device.h"

namespace lcs {

Eigen::VectorXd LcsProblem::physical_state(const Eigen::VectorXd& x, double t) const {
  return x + lcs_.Gamma * input_values(t);
}

Eigen::VectorXd LcsProblem::lcs_state(const Eigen::VectorXd& physical, double t) const {
  return physical - lcs_.Gamma * input_values(t);
}

void LcsProblem::accept(double t, const Eigen::VectorXd& x, const Eigen::VectorXd& z) const {
  for (const std::shared_ptr<Device>& d : history_devices_) d->accept(t, x, z);
}

double LcsProblem::max_step() const {
  double h = std::numeric_limits<double>::infinity();
  for (const std::shared_ptr<Device>& d : history_devices_) h = std::min(h, d->max_step());
  return h;
}

}  // namespace lcs
