// All solutions of a small LCP by enumerating active sets J (z_i > 0 only for i in J).
//
// For every J with S_JJ non-singular the candidate y_J = -S_JJ^{-1} qt_J, y_rest = 0 is kept if
// y >= -tol and v = S y + qt >= -tol (in equilibrated, q-normalised units; tol relative to
// max(1, |y|_inf)). Candidates are clamped to >= 0, mapped back to z and deduplicated.
//
// Limitation: an LCP whose solution set contains a continuum (a face with singular M_JJ, e.g.
// M = [[1,1],[1,1]], q = [-1,-1] has every z >= 0 with z1 + z2 = 1) is represented only by the
// vertex solutions found from non-singular principal submatrices (there: (1,0) and (0,1)).
// Cost: 2^n small LU factorisations, so n <= 24 is enforced (n = 20 already takes ~a second).
#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "solver/lcp/lcp.h"
#include "solver/lcp/lcp_internal.h"

namespace lcs {

namespace {
constexpr double kAcceptTol = 1e-9;   // feasibility of a candidate, normalised units
constexpr double kSameTol = 1e-9;     // two solutions are the same (relative, normalised units)
}  // namespace

std::vector<Eigen::VectorXd> enumerate_lcp_solutions(const Eigen::MatrixXd& M,
                                                     const Eigen::VectorXd& q) {
  lcp_detail::check_square(M, q, "enumerate_lcp_solutions");
  const int n = static_cast<int>(q.size());
  if (n > 24) throw std::invalid_argument("enumerate_lcp_solutions: n > 24");
  if (n == 0) return {Eigen::VectorXd()};
  const lcp_detail::Equilibration eq = lcp_detail::equilibrate(M);
  Eigen::VectorXd qt;
  const double qn = lcp_detail::normalise_q(eq, q, qt);

  std::vector<Eigen::VectorXd> found;  // in normalised units y
  Eigen::VectorXd y(n), v(n);
  std::vector<int> J;
  J.reserve(n);
  for (std::uint32_t mask = 0; mask < (std::uint32_t{1} << n); ++mask) {
    J.clear();
    for (int i = 0; i < n; ++i)
      if (mask & (std::uint32_t{1} << i)) J.push_back(i);
    const int k = static_cast<int>(J.size());
    y.setZero();
    if (k > 0) {
      Eigen::MatrixXd SJ(k, k);
      Eigen::VectorXd rhs(k);
      for (int a = 0; a < k; ++a) {
        rhs(a) = -qt(J[a]);
        for (int c = 0; c < k; ++c) SJ(a, c) = eq.S(J[a], J[c]);
      }
      Eigen::FullPivLU<Eigen::MatrixXd> lu(SJ);
      if (!lu.isInvertible()) continue;
      Eigen::VectorXd yJ = lu.solve(rhs);
      if (!yJ.allFinite()) continue;
      for (int a = 0; a < k; ++a) y(J[a]) = yJ(a);
    }
    const double tol = kAcceptTol * std::max(1.0, y.cwiseAbs().maxCoeff());
    if (y.minCoeff() < -tol) continue;
    v = qt;
    v.noalias() += eq.S * y;
    if (v.minCoeff() < -tol) continue;
    y = y.cwiseMax(0.0);
    bool dup = false;
    for (const Eigen::VectorXd& f : found) {
      double scale = std::max({1.0, f.cwiseAbs().maxCoeff(), y.cwiseAbs().maxCoeff()});
      if ((f - y).cwiseAbs().maxCoeff() <= kSameTol * scale) {
        dup = true;
        break;
      }
    }
    if (!dup) found.push_back(y);
  }

  std::vector<Eigen::VectorXd> out;
  out.reserve(found.size());
  for (const Eigen::VectorXd& f : found) out.push_back(eq.col.cwiseProduct(f) * qn);
  std::sort(out.begin(), out.end(), [](const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
    return std::lexicographical_compare(a.data(), a.data() + a.size(), b.data(),
                                        b.data() + b.size());
  });
  return out;
}

}  // namespace lcs
