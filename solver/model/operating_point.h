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
  // States DC leaves free (a loop of inductors, capacitors with no DC path, not even through a
  // conducting diode): they take the values of least stored energy. Labels listed.
  std::vector<std::string> undetermined;
};

// Throws NumericalFailure when the static LCP has no solution.
OperatingPoint solve_operating_point(const CircuitModel& model, double t = 0.0);

// Every solution of the static LCP (multistable circuits; diode-only circuits have one).
std::vector<OperatingPoint> enumerate_operating_points(const CircuitModel& model, double t = 0.0);

// The warning `op` and `run` print for OperatingPoint::undetermined.
std::string undetermined_state_warning(const std::vector<std::string>& labels);

}  // namespace lcs
