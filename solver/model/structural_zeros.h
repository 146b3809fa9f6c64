// Entries of a solved linear system that are zero for every value of the matrix entries.
//
// Formation solves the static equations E P = R densely (FullPivLU), and rounding then fills
// entries that the circuit's structure makes exactly zero (a diode link's current p = z carries
// 1e-17 of a VON input). Where KCL ties one pair's w to another's z exactly (a node reached only
// through diodes), that rounding makes the LCP infeasible as given, and `op` and the steppers
// end on a ray (issue 9, defect 3). This restores the exact zeros.
#pragma once

#include <Eigen/Dense>

namespace lcs {

// `solution` = E^-1 R computed in floating point (either sign). Sets to exactly 0 each entry
// (r, c) for which no j has E^-1(r, j) structurally nonzero and R(j, c) != 0. The structure of
// E^-1 is read off the inverse of a random matrix with E's nonzero pattern (Schwartz-Zippel:
// an entry of the inverse that is a nonzero rational function of the entries is nonzero at
// random values with probability 1). As a guard against an unlucky draw, an entry is only
// cleared if it is also negligible (1e-9) against its column.
void clear_structural_zeros(const Eigen::MatrixXd& E, const Eigen::MatrixXd& R,
                            Eigen::MatrixXd& solution);

}  // namespace lcs
