// How fast conduction through each complementarity pair moves the state.
#pragma once

#include <Eigen/Dense>

#include "solver/model/lcs_problem.h"
#include "solver/model/sparse_lcs.h"

namespace lcs {

// Per pair i, r_i = sum_j |(CB)_ij| / D_ii: 1/(RON C) for a diode charging C through RON;
// infinity where D_ii <= 0 (an index-one pair: its conduction moves the state without bound).
Eigen::VectorXd conduction_rates(const Lcs& s);
Eigen::VectorXd conduction_rates(const SparseLcs& s);
// The largest finite rate (0 when there is none).
double fastest_finite_rate(const Eigen::VectorXd& rates);

}  // namespace lcs
