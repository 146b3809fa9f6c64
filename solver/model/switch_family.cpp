#include "solver/model/switch_family.h"

#include <set>

#include "solver/devices/switch.h"
#include "solver/model/initial_state.h"
#include "solver/model/numerical_failure.h"

namespace lcs {

SwitchFamily::SwitchFamily(const CircuitModel& base) : base_(base) {
  for (const std::shared_ptr<Device>& d : base.devices()) {
    const auto* s = dynamic_cast<const Switch*>(d.get());
    if (!s) continue;
    SwitchControl c;
    c.name = s->name();
    c.control = s->control_probe();
    c.sign = s->card().reversed ? -1.0 : 1.0;
    c.vt = c.sign * s->card().vt;
    c.on_above = c.vt + s->card().vh;
    c.off_below = c.vt - s->card().vh;
    c.initially_on = s->element().initially_on;
    switches_.push_back(c);
    base_config_.push_back(s->on() ? 1 : 0);
  }
}

SwitchConfig SwitchFamily::config_of(const CircuitModel& model) const {
  SwitchConfig out;
  for (const std::shared_ptr<Device>& d : model.devices())
    if (const auto* s = dynamic_cast<const Switch*>(d.get())) out.push_back(s->on() ? 1 : 0);
  return out;
}

const CircuitModel& SwitchFamily::model(const SwitchConfig& config) {
  if (config == base_config_) return base_;
  auto it = cache_.find(config);
  if (it != cache_.end()) return *it->second;
  ModelOptions options = base_.options();
  for (size_t k = 0; k < switches_.size(); ++k) options.switch_on[switches_[k].name] = config[k] != 0;
  auto formed = std::make_unique<CircuitModel>(CircuitModel::build(base_.netlist(), options));
  return *cache_.emplace(config, std::move(formed)).first->second;
}

Eigen::VectorXd SwitchFamily::controls(const SwitchConfig& config, const Eigen::VectorXd& x,
                                       const Eigen::VectorXd& z, double t, bool before) {
  const CircuitModel& m = model(config);
  auto it = control_maps_.find(config);
  if (it == control_maps_.end()) {
    std::vector<Probe> probes;
    for (const SwitchControl& s : switches_) probes.push_back(s.control);
    it = control_maps_.emplace(config, m.output_map(probes)).first;
  }
  const OutputMap& o = it->second;
  Eigen::VectorXd y = o.G * x;
  if (z.size() > 0) y += o.H * z;
  y += o.J * (before ? m.inputs().values_before(t) : m.input_values(t)) + o.K * m.input_derivatives(t);
  for (size_t k = 0; k < switches_.size(); ++k) y(k) *= switches_[k].sign;
  return y;
}

SwitchConfig SwitchFamily::next(const SwitchConfig& config, const Eigen::VectorXd& controls) const {
  SwitchConfig out = config;
  for (size_t k = 0; k < switches_.size(); ++k) {
    if (!config[k] && controls(k) > switches_[k].on_above) out[k] = 1;
    if (config[k] && controls(k) < switches_[k].off_below) out[k] = 0;
  }
  return out;
}

std::string SwitchFamily::describe(const SwitchConfig& config) const {
  std::string out;
  for (size_t k = 0; k < switches_.size(); ++k)
    out += (k ? ", " : "") + switches_[k].name + (config[k] ? " on" : " off");
  return out;
}

SwitchConfig initial_configuration(SwitchFamily& family, const SwitchConfig& start, bool uic) {
  const std::vector<SwitchControl>& sw = family.switches();
  SwitchConfig config = start;
  for (size_t k = 0; k < sw.size(); ++k)
    if (sw[k].initially_on) config[k] = *sw[k].initially_on ? 1 : 0;
  std::set<SwitchConfig> seen;
  while (seen.insert(config).second) {
    const InitialState init = initial_state(family.model(config), uic, 0.0);
    const Eigen::VectorXd c = family.controls(config, init.x, init.z, 0.0);
    SwitchConfig wanted = config;
    for (size_t k = 0; k < sw.size(); ++k)
      if (!sw[k].initially_on) wanted[k] = c(k) > sw[k].vt ? 1 : 0;
    if (wanted == config) return config;
    config = wanted;
    if (seen.size() > 64)
      break;
  }
  throw NumericalFailure(0.0, "no consistent state of the switches at t = 0: each configuration's "
                              "operating point asks for another (last tried: " + family.describe(config) +
                              "); give the switches ON or OFF on their cards");
}

}  // namespace lcs
