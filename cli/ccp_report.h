// What `analyze` says about a circuit with transmission lines, which makes it a convolution
// complementarity problem (Stewart 4.6, 5.3) rather than an LCS:
//   w(t) = M0 z(t) + (m * z)(t) + q(t),   0 <= w(t) ⟂ z(t) >= 0,
// with M0 = D (the lines' ports are their characteristic impedances now) and the kernel
// m(t) = C e^{At} B (states, a lossy line's fitted exponentials among them) plus the paths that
// return through the lines: delta and exponential terms starting at the delays. The index of
// 5.3 is the first r with a delta in m^(r) at t = 0: zero when M0 carries every pair, one when
// M0 is zero on the pairs and m(0+) = C B does. Existence and uniqueness (4.6.1, Theorem 5.6):
// index zero with M0 a P-matrix (the Picard iteration of 4.6.1 contracts); index one with
// m(0+) a P-matrix (the condition of Theorem 5.6's first proof, [242]). Otherwise a warning.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Dense>

#include "solver/lcp/p_matrix.h"
#include "solver/model/circuit_model.h"

namespace lcs {

struct CcpReport {
  std::vector<double> delays;     // distinct line delays [s]
  Eigen::MatrixXd m0, m1;         // M0 = D and m(0+) = C B
  PMatrixReport m0_report, m1_report;
  int index = -1;                 // 0, 1, or -1 (neither carries the pairs)
  std::vector<std::string> warnings;
};

CcpReport ccp_report(const CircuitModel& model);

}  // namespace lcs
