// The state at the start of a transient (SPEC §2): with UIC, zero; otherwise the operating
// point. Then IC= on capacitors and inductors, and `.ic v(node)=` for capacitor voltages,
// override it (a node without .ic keeps its operating-point voltage, or 0 with UIC).
// Perfectly coupled windings (k = 1) share one state: their IC= give it as the flux they carry
// together, and a warning tells when the circuit cannot start with those winding currents.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Dense>

#include "solver/model/circuit_model.h"

namespace lcs {

struct InitialState {
  Eigen::VectorXd x;                  // LCS state at t0
  Eigen::VectorXd z;                  // the operating point's z (zeros with UIC)
  std::vector<bool> held;             // per state: its value set by IC=, .ic or a winding's IC=
  std::vector<std::string> warnings;  // IC= on dependent elements, states with no DC path
  // The other points of a smoothed circuit's tied ideal start (OperatingPoint::other_starts), as
  // (x, z) at t0.
  std::vector<std::pair<Eigen::VectorXd, Eigen::VectorXd>> other_starts;
};

InitialState initial_state(const CircuitModel& model, bool uic, double t0);

}  // namespace lcs
