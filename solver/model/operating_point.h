// DC operating point (SPEC §1 `op`): capacitors open, inductors shorted, sources at time t.
// With dx/dt = 0 the LCS becomes the static problem 0 = A x + B z + E u, w = C x + D z + F u,
// i.e. LCP(q, D - C A^-1 B) with q = (F - C A^-1 E) u.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Dense>

#include "solver/model/circuit_model.h"

namespace lcs {

struct OperatingPoint {
  Eigen::VectorXd x;  // LCS state
  Eigen::VectorXd z;
  int pivots = 0;
  // States with no DC path at all (not even through a conducting diode): undetermined by the
  // circuit; they take the minimum-norm value (0), as SPICE's GMIN would give. Labels listed.
  std::vector<std::string> undetermined;
};

// Throws NumericalFailure when the static LCP has no solution.
OperatingPoint solve_operating_point(const CircuitModel& model, double t = 0.0);

// Every solution of the static LCP (multistable circuits; diode-only circuits have one).
std::vector<OperatingPoint> enumerate_operating_points(const CircuitModel& model, double t = 0.0);

}  // namespace lcs
