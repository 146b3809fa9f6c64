// The ideal switches of a circuit (S, W; solver/devices/switch.h) as discrete modes: one model
// per configuration of switch states, formed when first visited and kept (a ring oscillator of
// 34 switches visits a few dozen of its 2^34 configurations). Resistor values do not enter the
// normal tree, so every configuration has the same states x (and the same pairs z): a run moves
// from one model to the next with x unchanged.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "solver/model/circuit_model.h"

namespace lcs {

struct SwitchControl {
  std::string name;                 // the switch element
  Probe control;                    // v(nc+,nc-) (S) or i(vname) (W)
  // Thresholds on the control as read, sign × the probe: sign −1 for a reversed switch (PSpice's
  // VON < VOFF, on as the control falls), so every switch is "on above, off below".
  double sign = 1;
  double on_above = 0, off_below = 0;  // sign VT + VH and sign VT - VH
  double vt = 0;                       // sign VT
  std::optional<bool> initially_on;  // ON/OFF on the card
};

using SwitchConfig = std::vector<char>;  // per switch, in card order: 1 on, 0 off

class SwitchFamily {
 public:
  // `base`: the circuit in any configuration (its netlist and options are reused).
  explicit SwitchFamily(const CircuitModel& base);
  bool empty() const { return switches_.empty(); }
  const std::vector<SwitchControl>& switches() const { return switches_; }

  // The model of one configuration (formed on first use; `base` itself for its own).
  const CircuitModel& model(const SwitchConfig& config);
  SwitchConfig config_of(const CircuitModel& model) const;
  int formed() const { return static_cast<int>(cache_.size()); }

  // The controls at (x, z, t) in the model of `config`; `before`: with the sources' values from
  // the left at t (a zero-width edge at t not yet taken; their derivatives stay the right ones).
  Eigen::VectorXd controls(const SwitchConfig& config, const Eigen::VectorXd& x, const Eigen::VectorXd& z,
                           double t, bool before = false);
  // The configuration the controls ask for, with hysteresis: an off switch turns on above
  // VT + VH, an on switch off below VT - VH.
  SwitchConfig next(const SwitchConfig& config, const Eigen::VectorXd& controls) const;
  // "s1 on, s2 off"
  std::string describe(const SwitchConfig& config) const;

 private:
  const CircuitModel& base_;
  SwitchConfig base_config_;
  std::vector<SwitchControl> switches_;
  std::map<SwitchConfig, std::unique_ptr<CircuitModel>> cache_;
  std::map<SwitchConfig, OutputMap> control_maps_;
};

// The switch states at t = 0 (SPEC §2, ngspice): ON/OFF from the card, the others from the
// control at t = 0 relative to VT, iterated to a configuration consistent with its own
// operating point (or the UIC state). Throws NumericalFailure when no configuration is
// consistent (the iteration cycles).
SwitchConfig initial_configuration(SwitchFamily& family, const SwitchConfig& start, bool uic);

}  // namespace lcs
