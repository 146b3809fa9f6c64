// Warm-started LCP solver for a fixed M and a sequence of q (one LCP per integrator step).
//
// Hot path (warm hit): the previous basis J (Lemke's basic z set, or the J of the last warm hit;
// a bitmask) selects a cached
// LU factorisation of the equilibrated S_JJ; one triangular solve gives y_J, then
//   y_J >= -tol  and  v_i = (S y + qt)_i >= -tol for i not in J,   tol = feas_tol * max(1, |y|_inf)
// (normalised units, see lcp_internal.h) accepts the answer. Negative y_J within tol are clamped
// to 0. Otherwise Lemke's method (same equilibration, reused workspace) solves the step and its
// active set becomes the next guess. No heap allocation on a warm hit once the active set's
// factorisation is cached (tested with an interposed malloc in warm_solver_test.cpp).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <unordered_map>
#include <utility>
#include <vector>

#include "solver/lcp/lcp.h"
#include "solver/lcp/lcp_internal.h"

namespace lcs {

namespace {
constexpr int kMaxWarmN = 64;            // active sets are 64-bit masks
constexpr std::size_t kMaxModes = 4096;  // cache cap; cleared when exceeded
constexpr double kMinRcond = 1e-13;      // S_JJ treated as singular below (then Lemke)
}  // namespace

struct LcpWarmSolver::Impl {
  struct Mode {
    std::vector<int> J, rest;
    Eigen::PartialPivLU<Eigen::MatrixXd> lu;
    bool usable = false;
    Eigen::VectorXd rhs, y;
  };

  lcp_detail::LemkeEngine engine;
  std::unordered_map<std::uint64_t, Mode> cache;
  Mode* last_mode = nullptr;
  std::uint64_t last_key = 0;

  Mode& mode(std::uint64_t key, int n) {
    if (last_mode != nullptr && key == last_key) return *last_mode;
    auto it = cache.find(key);
    if (it == cache.end()) {
      if (cache.size() >= kMaxModes) cache.clear();
      const Eigen::MatrixXd& S = engine.equilibration().S;
      Mode m;
      for (int i = 0; i < n; ++i) ((key >> i) & 1u ? m.J : m.rest).push_back(i);
      const int k = static_cast<int>(m.J.size());
      m.rhs.resize(k);
      m.y.resize(k);
      if (k == 0) {
        m.usable = true;
      } else {
        Eigen::MatrixXd SJ(k, k);
        for (int a = 0; a < k; ++a)
          for (int c = 0; c < k; ++c) SJ(a, c) = S(m.J[a], m.J[c]);
        m.lu.compute(SJ);
        const double rc = m.lu.rcond();
        m.usable = m.lu.matrixLU().allFinite() && rc > kMinRcond;
      }
      it = cache.emplace(key, std::move(m)).first;
    }
    last_mode = &it->second;  // node-based map: stays valid until erased/cleared
    last_key = key;
    return *last_mode;
  }
};

LcpWarmSolver::LcpWarmSolver(Eigen::MatrixXd M, LemkeOptions options)
    : M_(std::move(M)), options_(options), impl_(std::make_shared<Impl>()) {
  if (M_.rows() != M_.cols()) throw std::invalid_argument("LcpWarmSolver: M must be square");
  impl_->engine.set_matrix(M_);
  last_.z = Eigen::VectorXd::Zero(M_.rows());
  last_.w = Eigen::VectorXd::Zero(M_.rows());
}

const LcpSolution& LcpWarmSolver::solve(const Eigen::VectorXd& q) {
  const int n = static_cast<int>(M_.rows());
  lcp_detail::check_square(M_, q, "LcpWarmSolver::solve");
  ++stats_.solves;

  if (n <= kMaxWarmN) {
    Impl::Mode& m = impl_->mode(active_, n);
    if (m.usable) {
      const lcp_detail::Equilibration& eq = impl_->engine.equilibration();
      double qn = 0.0;
      for (int i = 0; i < n; ++i) qn = std::max(qn, std::abs(eq.row(i) * q(i)));
      if (!(qn > 0)) qn = 1.0;
      const int k = static_cast<int>(m.J.size());
      bool ok = true;
      double tol = options_.feas_tol;
      if (k > 0) {
        for (int a = 0; a < k; ++a) m.rhs(a) = -eq.row(m.J[a]) * q(m.J[a]) / qn;
        m.y.noalias() = m.lu.solve(m.rhs);
        double ymax = 0.0;
        for (int a = 0; a < k; ++a) ymax = std::max(ymax, std::abs(m.y(a)));
        tol *= std::max(1.0, ymax);
        for (int a = 0; a < k && ok; ++a) ok = m.y(a) >= -tol;  // false for NaN too
      }
      if (ok) {
        last_.z.setZero();
        last_.w = q;
        for (int a = 0; a < k; ++a) {
          const int j = m.J[a];
          const double zj = m.y(a) > 0.0 ? eq.col(j) * m.y(a) * qn : 0.0;
          last_.z(j) = zj;
          if (zj != 0.0) last_.w += M_.col(j) * zj;
        }
        for (int i : m.rest)
          if (!(eq.row(i) * last_.w(i) / qn >= -tol)) {
            ok = false;
            break;
          }
      }
      if (ok) {
        last_.status = LcpStatus::Solved;
        last_.pivots = 0;
        // Keep the basis that worked, zero-level z_j included: at a degenerate vertex (a
        // continuum of solutions, e.g. the potential of a sub-circuit that no conducting diode
        // ties down) the support {z > 0} alone has a singular block.
        ++stats_.warm_hits;
        return last_;
      }
    }
  }

  impl_->engine.solve(M_, q, options_, last_);
  ++stats_.lemke_calls;
  stats_.lemke_pivots += last_.pivots;
  if (last_.status == LcpStatus::Solved && n <= kMaxWarmN) {
    // The final complementary basis, not the support of z (see the warm-hit branch).
    std::uint64_t mask = impl_->engine.basic_z_mask();
    for (int i = 0; i < n; ++i)
      if (last_.z(i) > 0.0) mask |= std::uint64_t{1} << i;
    active_ = mask;
  }
  return last_;
}

}  // namespace lcs
