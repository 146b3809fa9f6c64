// The LCS of a large circuit stored sparse (issue 12). A diode ladder's or rectifier bank's A, B,
// C and D hold a few entries per row, and its time steps, start and operating point are then
// solved on the sparse system (solver/lcp/sparse_active_set.h) in time that grows like the
// circuit. Small circuits, and circuits whose LCS is dense (a multiplier's capacitor loop couples
// every stage), keep the dense path.
#pragma once

#include <memory>

#include <Eigen/Dense>
#include <Eigen/Sparse>

#include "solver/model/lcs_problem.h"

namespace lcs {

struct SparseLcs {
  Eigen::SparseMatrix<double> A, B, C, D;  // exact zeros dropped: the same numbers as the dense
  Eigen::MatrixXd E, F;                    // few input columns: dense
};

// Chosen, not measured as a crossover (to do): small circuits keep the dense LCP, whose warm
// start costs well under a microsecond per step (README, "Speed"); the dense step grows like
// m^2 and the sparse one like the circuit.
constexpr int kSparsePairs = 48;
// States and pairs together from which a circuit with fewer pairs is kept sparse too: an RC line
// of 3000 sections with one diode formed a dense 3000 x 3000 A and stepped on dense factors, and
// one of 20000 sections asked for 3.2 GB before any method could refuse it.
constexpr int kSparseUnknowns = 1024;
// Nonzeros of A, B, C and D over (n + m)^2 above which the LCS counts as dense.
constexpr double kSparseDensity = 0.05;

// The sparse form of (A, B, C, D) when it pays (enough pairs or enough states and pairs, sparse
// enough), else null.
std::unique_ptr<SparseLcs> sparse_lcs_if_worth(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B,
                                               const Eigen::MatrixXd& C, const Eigen::MatrixXd& D,
                                               const Eigen::MatrixXd& E, const Eigen::MatrixXd& F);
// The same rule on formation's own sparse A, B, C, D (exact zeros already dropped): whether they
// are worth keeping sparse.
bool sparse_lcs_worth(const SparseLcs& s);
inline std::unique_ptr<SparseLcs> sparse_lcs_if_worth(const Lcs& s) {
  return sparse_lcs_if_worth(s.A, s.B, s.C, s.D, s.E, s.F);
}

}  // namespace lcs
