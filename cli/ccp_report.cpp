#include "cli/ccp_report.h"

#include <algorithm>

#include "solver/model/lcs_index.h"

namespace lcs {

namespace {
bool zero_diagonal_pairs(const Eigen::MatrixXd& M, double scale) {
  for (int i = 0; i < M.rows(); ++i)
    if (std::abs(M(i, i)) > 1e-12 * scale) return false;
  return true;
}
}  // namespace

CcpReport ccp_report(const CircuitModel& model) {
  CcpReport r;
  for (const DelayedWave& w : model.delayed())
    if (std::find(r.delays.begin(), r.delays.end(), w.delay) == r.delays.end()) r.delays.push_back(w.delay);
  const Lcs& s = model.lcs();
  const int m = s.pairs();
  r.m0 = s.D;
  r.m1 = s.states() > 0 ? Eigen::MatrixXd(s.C * s.B) : Eigen::MatrixXd::Zero(m, m);
  if (m == 0) {
    r.index = 0;
    return r;
  }
  r.m0_report = p_matrix_report(r.m0);
  r.m1_report = p_matrix_report(r.m1);
  const double scale = std::max(1.0, r.m0.cwiseAbs().maxCoeff());
  if (r.m0_report.verdict == PMatrixReport::Verdict::P) {
    r.index = 0;
  } else if (zero_diagonal_pairs(r.m0, scale) && r.m1_report.verdict == PMatrixReport::Verdict::P) {
    r.index = 1;
  } else if (lcs_index(s).index >= 0) {
    r.index = lcs_index(s).index;  // pairs of mixed index: each carried by its own Markov parameter
  } else {
    r.warnings.push_back(
        "the CCP's existence conditions (Stewart 4.6.1, Theorem 5.6) are not met: M0 = D is not a "
        "P-matrix and m(0+) = CB does not carry every pair as a P-matrix; solutions may not exist or "
        "be unique (a pair with no impedance of its own next to a line port, or transistor feedback)");
  }
  return r;
}

}  // namespace lcs
