#include "solver/integrators/mode_dynamics.h"

#include <limits>

#include "solver/model/empty_safe.h"

namespace lcs {

namespace {

// A row (column) block of a matrix with no columns (rows) points past null (UBSan): C of a
// circuit without states. Nothing to copy then.
Eigen::MatrixXd rows(const Eigen::MatrixXd& M, const std::vector<int>& idx) {
  Eigen::MatrixXd out(idx.size(), M.cols());
  if (M.cols() == 0) return out;
  for (size_t k = 0; k < idx.size(); ++k) out.row(k) = M.row(idx[k]);
  return out;
}

Eigen::MatrixXd cols(const Eigen::MatrixXd& M, const std::vector<int>& idx) {
  Eigen::MatrixXd out(M.rows(), idx.size());
  if (M.rows() == 0) return out;
  for (size_t k = 0; k < idx.size(); ++k) out.col(k) = M.col(idx[k]);
  return out;
}

}  // namespace

ModeDynamics ModeDynamics::build(const Lcs& s, const std::vector<bool>& is_active) {
  ModeDynamics m;
  for (int i = 0; i < s.pairs(); ++i) (is_active[i] ? m.active : m.inactive).push_back(i);
  const int n = s.states(), nu = s.inputs(), a = static_cast<int>(m.active.size());
  const Eigen::MatrixXd Ca = rows(s.C, m.active), Fa = rows(s.F, m.active);
  const Eigen::MatrixXd Ba = cols(s.B, m.active);
  const Eigen::MatrixXd Daa = cols(rows(s.D, m.active), m.active);

  // Split the rows of w_α = 0 into D_αα's range (index zero) and left null space (index one).
  Eigen::MatrixXd U(a, 0), N(a, 0);
  if (a > 0) {
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(Daa, Eigen::ComputeFullU);
    const Eigen::VectorXd& sv = svd.singularValues();
    // Below 1e-13 of the largest: rounding (JacobiSVD is accurate to eps times it). 1e-10 counted a
    // bridge's 0.1 ohm loop as zero beside its 1 GOhm shunt (2e9 ohm), and no mode fitted.
    const double tol = 1e-13 * (sv.size() > 0 ? sv(0) : 0.0);
    int r = 0;
    while (r < sv.size() && sv(r) > tol && sv(r) > 0) ++r;
    // A singular value counted zero that stands far above D_αα's rounding is a loop resistance
    // double precision does not resolve beside the others, not a zero: a floating source's
    // 0.1 ohm diode loop beside its 1 TOhm reference (113 eps of it). Counted zero, the loop is
    // the RON = 0 circuit and charges its capacitor in an impulse (8.2 A where 0.28 A flows).
    // True zeros (ideal loops, RON = 0) come out at 0 .. 0.003 eps on every deck tried.
    constexpr double kZeroFloor = 16 * std::numeric_limits<double>::epsilon();
    if (r < sv.size() && sv(r) > kZeroFloor * sv(0)) {
      m.unresolved = sv(r);
      m.unresolved_beside = sv(0);
    }
    U = svd.matrixU().leftCols(r);
    N = svd.matrixU().rightCols(a - r);
  }
  const int k = static_cast<int>(N.cols());
  // Q z_α = -(Rx x + Ru u + Rd u'):
  //   U^T (C_α x + D_αα z_α + F_α u) = 0,   N^T C_α (A x + B_α z_α + E u) + N^T F_α u' = 0.
  Eigen::MatrixXd Q(a, a), Rx(a, n), Ru(a, nu), Rd(a, nu);
  Q << U.transpose() * Daa, N.transpose() * Ca * Ba;
  if (n > 0) Rx << U.transpose() * Ca, N.transpose() * Ca * s.A;  // no states: nothing (UBSan)
  Ru << U.transpose() * Fa, N.transpose() * Ca * s.E;
  Rd << Eigen::MatrixXd::Zero(a - k, nu), N.transpose() * Fa;
  m.Cc = N.transpose() * Ca;
  m.Fc = N.transpose() * Fa;

  Eigen::FullPivLU<Eigen::MatrixXd> lu;  // of Q; with no active pair Q is 0 x 0: nothing to solve
  if (a > 0) {
    lu.compute(Q);
    const double scale = Q.cwiseAbs().maxCoeff();
    lu.setThreshold(1e-12);
    m.well_posed = scale > 0 && lu.isInvertible();
    if (m.well_posed) m.rcond = lu.rcond();
  } else {
    m.well_posed = true;
  }
  if (!m.well_posed) return m;
  m.Kx = -solve_or_empty(lu, Rx);
  m.Ku = -solve_or_empty(lu, Ru);
  m.Kd = -solve_or_empty(lu, Rd);
  m.Ax = s.A + Ba * m.Kx;
  m.Eu = s.E + Ba * m.Ku;
  m.Ed = Ba * m.Kd;
  const Eigen::MatrixXd Cb = rows(s.C, m.inactive), Fb = rows(s.F, m.inactive);
  const Eigen::MatrixXd Dba = cols(rows(s.D, m.inactive), m.active);
  m.Wx = Cb + Dba * m.Kx;
  m.Wu = Fb + Dba * m.Ku;
  m.Wd = Dba * m.Kd;
  if (k > 0) {
    const Eigen::MatrixXd dir = Ba * N;  // impulse directions
    m.project = dir * (m.Cc * dir).completeOrthogonalDecomposition().pseudoInverse();
  } else {
    m.project = Eigen::MatrixXd::Zero(n, 0);
  }
  return m;
}

}  // namespace lcs
