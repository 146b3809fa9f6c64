// Warm-started LCP solver for a fixed M and a sequence of q (one LCP per integrator step).
//
// Hot path (warm hit): the previous basis J (Lemke's basic z set, or the J of the last warm hit;
// one char per pair, any number of pairs) selects a cached
// LU factorisation of the equilibrated S_JJ; one triangular solve gives y_J, then
//   y_J >= -tol  and  v_i = (S y + qt)_i >= -tol for i not in J,   tol = feas_tol * max(1, |y|_inf)
// (normalised units, see lcp_internal.h) accepts the answer. Negative y_J within tol are clamped
// to 0. Otherwise Lemke's method (same equilibration, reused workspace) solves the step and its
// active set becomes the next guess. No heap allocation on a warm hit once the active set's
// factorisation is cached (tested with an interposed malloc in warm_solver_test.cpp).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <stdexcept>
#include <unordered_map>
#include <utility>
#include <vector>

#include "solver/lcp/lcp.h"
#include "solver/lcp/lcp_internal.h"
#include "solver/lcp/p_matrix.h"
#include "solver/lcp/sparse_active_set.h"

namespace lcs {

namespace {
constexpr std::size_t kMaxModes = 4096;  // cache cap; cleared when exceeded
// Bytes of cached LU factors (8 k^2 per mode of k active pairs) past which the cache is cleared:
// 64 modes of 1000 pairs, or every mode of a small circuit.
constexpr std::size_t kWarmCacheBytes = std::size_t{512} << 20;
constexpr double kMinRcond = 1e-13;      // S_JJ treated as singular below (then Lemke)
// From this many pairs a missed warm hit pivots from the last basis before Lemke. Below, Lemke's
// own pivots are few, and up to 16 pairs the multiplicity watch enumerates (solve()).
constexpr int kMinPivotedPairs = 32;
// Up to this many pairs a Lemke ray, iteration limit or cycle is checked by principal pivoting
// (polish_by_principal_pivoting): each of its rounds factorises a dense M_JJ, so past a few
// hundred pairs a genuinely infeasible step (a current source into a reverse diode) would cost
// minutes before its error.
constexpr int kMaxPolishedAfterRay = 256;
}  // namespace

struct LcpWarmSolver::Impl {
  struct Mode {
    std::vector<int> J, rest;
    Eigen::PartialPivLU<Eigen::MatrixXd> lu;
    bool usable = false;
    Eigen::VectorXd rhs, y;
  };

  lcp_detail::LemkeEngine engine;
  std::unordered_map<std::string, Mode> cache;  // keyed by the active set, one char per pair
  std::size_t cache_bytes = 0;
  Mode* last_mode = nullptr;
  std::string last_key;

  // No allocation when `key` is the last mode's or already cached (the warm hit's path).
  Mode& mode(const std::string& key, int n) {
    if (last_mode != nullptr && key == last_key) return *last_mode;
    auto it = cache.find(key);
    if (it == cache.end()) {
      const Eigen::MatrixXd& S = engine.equilibration().S;
      Mode m;
      for (int i = 0; i < n; ++i) (key[i] ? m.J : m.rest).push_back(i);
      const int k = static_cast<int>(m.J.size());
      const std::size_t bytes = 8 * static_cast<std::size_t>(k) * k + 16 * static_cast<std::size_t>(n);
      if (cache.size() >= kMaxModes || cache_bytes + bytes > kWarmCacheBytes) {
        cache.clear();
        cache_bytes = 0;
      }
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
      cache_bytes += bytes;
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
  active_.assign(M_.rows(), 0);
  engine_q_ = Eigen::VectorXd::Zero(M_.rows());
}

void LcpWarmSolver::watch_multiplicity() {
  const PMatrixReport report = p_matrix_report(M_, 0);  // the cheap tests only
  several_possible_ = !report.symmetric_psd && report.verdict != PMatrixReport::Verdict::P;
}

void LcpWarmSolver::prefer(const Eigen::VectorXd& z, bool always) {
  const int n = static_cast<int>(M_.rows());
  if ((stats_.solves > 0 && !always) || z.size() != n) return;
  for (int i = 0; i < n; ++i) active_[i] = z(i) > 0.0;
  preferred_ = true;
}

void LcpWarmSolver::continue_last_block(int blocks) {
  const int n = static_cast<int>(M_.rows());
  if (blocks <= 1 || n % blocks != 0 || n == 0) return;
  const int m = n / blocks;
  const auto last = active_.begin() + (n - m);  // in place: radau's steady steps do not allocate
  bool uniform = true;
  for (int b = 0; b + 1 < blocks && uniform; ++b) uniform = std::equal(last, active_.end(), active_.begin() + b * m);
  if (uniform) return;
  for (int b = 0; b + 1 < blocks; ++b) std::copy(last, active_.end(), active_.begin() + b * m);
}

// Several solutions (Stewart 5.4.7: transistor feedback): the warm start keeps the one
// continuous with the previous state. Enumeration (2^n solves) tells whether others exist: on
// warm hits only until the first time it finds them and only for n <= kMaxCountedOnWarmHit, at
// Lemke's solves (the previous mode has ended) up to kMaxCounted. Where the previous mode has
// ended, Lemke's solution is taken: at the regenerative switchings of an astable or a Schmitt
// trigger the step's LCP has several solutions (the switched state, and states that keep the
// other transistor half on), and the end of Lemke's complementary path from the ray is the
// switched one, checked against the event method and ngspice (tests/bjt_circuits_test.cpp); the
// nearest mode would keep both on. (From kMinPivotedPairs pairs a miss first follows q from the
// last answer by pivots, solve_once; at such a switching that path folds back and Lemke decides.
// Where pairs reach zero together, which of them leaves first is a heuristic outside
// P-matrices: the TTL adders' runs equal Lemke's to 6.7e-10 V.) With no previous state at all
// (a start without .ic/.nodeset choosing) the solutions are told apart by their index
// sign(det M_JJ) (J = {z > 0}; the indices of a nondegenerate LCP's solutions sum to 1): an
// index -1 solution is a saddle of the fast dynamics any small charge storage adds (a
// flip-flop's balanced state); a single index +1 solution is taken, several are the run's exit 3.
const LcpSolution& LcpWarmSolver::solve(const Eigen::VectorXd& q) {
  constexpr int kMaxCountedOnWarmHit = 8, kMaxCounted = 16;
  const int n = static_cast<int>(M_.rows());
  const bool had_previous = stats_.solves > 0 || preferred_;
  const long hits = stats_.warm_hits;
  solve_once(q);
  multiplicity_ = Multiplicity::Unknown;
  if (!several_possible_ || last_.status != LcpStatus::Solved) return last_;
  const bool warm_hit = stats_.warm_hits > hits;
  if (warm_hit && (several_seen_ || n > kMaxCountedOnWarmHit)) return last_;
  if (!warm_hit && n > kMaxCounted) return last_;
  const std::vector<Eigen::VectorXd> all = distinct_in_w(M_, q, enumerate_lcp_solutions(M_, q));
  if (all.size() <= 1) {
    multiplicity_ = Multiplicity::One;
    return last_;
  }
  several_seen_ = true;
  differ_.clear();
  double scale = 1e-300;
  for (const Eigen::VectorXd& z : all) scale = std::max(scale, z.cwiseAbs().maxCoeff());
  for (int i = 0; i < n; ++i) {
    bool on = false, off = false;
    for (const Eigen::VectorXd& z : all) (z(i) > 1e-9 * scale ? on : off) = true;
    if (on && off) differ_.push_back(i);
  }
  solutions_ = static_cast<int>(all.size());
  if (warm_hit && had_previous) {
    multiplicity_ = Multiplicity::SeveralKeptContinuous;
    return last_;
  }
  if (had_previous) {  // the previous mode has ended: Lemke's solution, as without transistors
    multiplicity_ = Multiplicity::SeveralTookLemke;
    return last_;
  }
  std::vector<const Eigen::VectorXd*> stable;
  for (const Eigen::VectorXd& z : all)
    if (lcp_solution_index(M_, z) > 0) stable.push_back(&z);
  if (stable.size() != 1) {
    multiplicity_ = Multiplicity::SeveralNoneContinuous;
    last_.status = LcpStatus::NotUnique;
    return last_;
  }
  multiplicity_ = Multiplicity::SeveralTookStable;
  last_.z = *stable.front();
  last_.w = M_ * last_.z + q;
  for (int i = 0; i < n; ++i) active_[i] = last_.z(i) > 0.0;
  return last_;
}

// Lemke's tableau drifts on an ill-conditioned M (a 30-stage multiplier's step: entries from
// 0.1 to 1e3 over long capacitor chains) and can end on a complementary basis whose solution
// misses the tolerance, or on a ray that rounding made: a bridge whose floating source and load
// are referenced by 1 TOhm has M = 2e12 u u^T + (entries of 0.05 .. 0.15), positive definite,
// and the equilibrated tableau's pivots on the small part are at the 1e-14 of the large one, so
// Lemke's path ended on a ray at the first conduction (every fixed-step method stopped there).
// From `start`'s mode, block principal pivoting with fresh LU solves of M_JJ
// (sparse_active_set.h, here with no free variables) reaches the solution when one exists; its
// answer is accepted only when it solves the LCP as given to rounding (lcp_solved_to_rounding).
void LcpWarmSolver::polish_by_principal_pivoting(const Eigen::VectorXd& q, const Eigen::VectorXd& start) {
  const int n = static_cast<int>(M_.rows());
  const SparseActiveSetLcp::Sparse none(0, 0), L(0, n), P(n, 0);
  const SparseActiveSetLcp::Sparse Q = M_.sparseView();
  SparseActiveSetLcp pivoting(none, L, P, Q);
  pivoting.prefer(start);
  Eigen::VectorXd y, z, w;
  if (!pivoting.solve(Eigen::VectorXd(0), q, y, z, w)) return;
  if (!lcp_solved_to_rounding(M_, q, z, options_.feas_tol)) return;
  last_.z = z;
  last_.w = M_ * z + q;
  last_.status = LcpStatus::Solved;
  last_.ray.clear();
  ++stats_.polished;
}

// The active set active_ (one cached LU of S_JJ): y_J from it, accepted when y_J >= -tol and
// w >= -tol off J (see the file's header). Fills last_ when it is accepted.
bool LcpWarmSolver::solve_on_active_set(const Eigen::VectorXd& q) {
  const int n = static_cast<int>(M_.rows());
  Impl::Mode& m = impl_->mode(active_, n);
  if (!m.usable) return false;
  const lcp_detail::Equilibration& eq = impl_->engine.equilibration();
  double qn = 0.0;
  for (int i = 0; i < n; ++i) qn = std::max(qn, std::abs(eq.row(i) * q(i)));
  if (!(qn > 0)) qn = 1.0;
  const int k = static_cast<int>(m.J.size());
  double tol = options_.feas_tol;
  if (k > 0) {
    for (int a = 0; a < k; ++a) m.rhs(a) = -eq.row(m.J[a]) * q(m.J[a]) / qn;
    m.y.noalias() = m.lu.solve(m.rhs);
    double ymax = 0.0;
    for (int a = 0; a < k; ++a) ymax = std::max(ymax, std::abs(m.y(a)));
    tol *= std::max(1.0, ymax);
    for (int a = 0; a < k; ++a)
      if (!(m.y(a) >= -tol)) return false;  // false for NaN too
  }
  last_.z.setZero();
  last_.w = q;
  for (int a = 0; a < k; ++a) {
    const int j = m.J[a];
    const double zj = m.y(a) > 0.0 ? eq.col(j) * m.y(a) * qn : 0.0;
    last_.z(j) = zj;
    if (zj != 0.0) last_.w += M_.col(j) * zj;
  }
  for (int i : m.rest)
    if (!(eq.row(i) * last_.w(i) / qn >= -tol)) return false;
  last_.status = LcpStatus::Solved;
  last_.pivots = 0;
  return true;
}

const LcpSolution& LcpWarmSolver::solve_once(const Eigen::VectorXd& q) {
  const int n = static_cast<int>(M_.rows());
  lcp_detail::check_square(M_, q, "LcpWarmSolver::solve");
  ++stats_.solves;

  if (solve_on_active_set(q)) {
    // Keep the basis that worked, zero-level z_j included: at a degenerate vertex (a
    // continuum of solutions, e.g. the potential of a sub-circuit that no conducting diode
    // ties down) the support {z > 0} alone has a singular block.
    ++stats_.warm_hits;
    // The engine's basis, if it is this one, is feasible for this q too.
    if (!engine_basis_.empty() && active_ == engine_basis_) engine_q_ = q;
    else engine_basis_.clear();
    return last_;
  }

  // The warm hit missed: the step's q has moved past the last answer's basis. Where the Lemke
  // engine holds that basis, follow q from the last one to this one by principal pivots (a few
  // where a few pairs switch, each O(n^2) like one of Lemke's, against Lemke's hundreds from
  // the all-w basis on a TTL adder's 466 pairs); where that path folds (a regenerative
  // switching) or runs long, Lemke decides as before. The basis it ends on is solved
  // afresh as a warm hit is (its LU, cached for the next steps, not the pivoted inverse, which
  // drifts: on a TTL adder's step the pivoted w was 6e-9 below 0 where Lemke's polish has 4e-9).
  if (n >= kMinPivotedPairs && !engine_basis_.empty() && active_ == engine_basis_ &&
      impl_->engine.solve_from_basis(M_, q, engine_q_, options_, n, last_)) {
    const int pivots = last_.pivots;
    previous_active_ = active_;
    impl_->engine.basic_z(active_);
    if (solve_on_active_set(q)) {
      ++stats_.pivoted;
      stats_.pivoted_pivots += pivots;
      last_.pivots = pivots;
      last_.basic_z.clear();  // (from the warm solver: empty, lcp.h)
      engine_basis_ = active_;
      engine_q_ = q;
      return last_;
    }
    active_ = previous_active_;  // the last answer's set stays the next guess if Lemke fails
  }
  engine_basis_.clear();

  impl_->engine.solve(M_, q, options_, last_);
  ++stats_.lemke_calls;
  stats_.lemke_pivots += last_.pivots;
  stats_.lemke_restarts += last_.restarts;
  const bool lemke_solved = last_.status == LcpStatus::Solved;
  const bool lemke_basis = lemke_solved || last_.status == LcpStatus::NumericalFailure;
  if (last_.status == LcpStatus::NumericalFailure) {
    polish_by_principal_pivoting(q, last_.z);  // from the complementary basis Lemke reached
  } else if (!lemke_solved && n <= kMaxPolishedAfterRay) {
    Eigen::VectorXd previous(n);  // from the mode the warm start tried (Lemke's z is no basis)
    for (int i = 0; i < n; ++i) previous(i) = active_[i] ? 1.0 : 0.0;
    polish_by_principal_pivoting(q, previous);
  }
  if (last_.status == LcpStatus::Solved) {
    // The final complementary basis, not the support of z (see the warm-hit branch); after a
    // ray the engine holds no complementary basis, and the support is the next guess.
    if (lemke_basis) impl_->engine.basic_z(active_);
    else active_.assign(n, 0);
    for (int i = 0; i < n; ++i)
      if (last_.z(i) > 0.0) active_[i] = 1;
    if (lemke_solved) {  // (a polished answer is not the engine's basis)
      impl_->engine.basic_z(engine_basis_);
      if (engine_basis_ == active_) engine_q_ = q;
      else engine_basis_.clear();
    }
  }
  return last_;
}

}  // namespace lcs
