// Lemke's complementary pivoting method with lexicographic degeneracy resolution (Stewart 2.2.1).
//
// Tableau view: I w - S y - s d = qt with d = (1, ..., 1), where S = diag(r) M diag(c) is the
// equilibrated matrix and qt = diag(r) q / |diag(r) q|_inf (see lcp_internal.h). The tableau is
// kept in revised form: the basis inverse Binv (n x n) and the basic values b = Binv qt; the
// column of an entering variable is computed on demand (a = Binv * column). Since the initial
// basis is w = I, the rows [b_k, Binv_k] are exactly the rows [b_k, a_k1 .. a_kn] of the book's
// lexicographic rule restricted to the initial-basis columns, which already decide every tie
// (Binv is non-singular), so the rule never cycles (Lemma 2.9).
//
// In exact arithmetic. In floating point the rule's first component compares basic values that
// are zero at a degenerate vertex with a tolerance, and an ill-conditioned basis carries rounding
// noise above it: then rounding, not the rule, picks the leaving row, the picks are not
// consistent from one pivot to the next, and the path can return to a basis it has left (the
// 466-pair TTL adders' step LCPs did, with a period of 72 pivots, until the iteration limit).
// A revisited basis is impossible on the exact path, so it proves this failure: it is detected
// (a hash of the basis, updated per pivot) and the path restarted on q moved by a small generic
// vector, which makes the degenerate values differ by far more than their noise (the perturbation
// the lexicographic rule stands for, Stewart 2.2.1, made finite).
#include <algorithm>
#include <cstdint>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <unordered_set>
#include <vector>

#include "solver/lcp/lcp.h"
#include "solver/lcp/lcp_internal.h"

namespace lcs {

const char* lcp_status_name(LcpStatus s) {
  switch (s) {
    case LcpStatus::Solved: return "solved";
    case LcpStatus::RayTermination: return "ray termination";
    case LcpStatus::IterationLimit: return "iteration limit";
    case LcpStatus::NumericalFailure: return "numerical failure";
    case LcpStatus::Cycling: return "cycling: rounding decides the ratio test at a degenerate vertex";
    case LcpStatus::NotUnique: return "several solutions, none continuous with the previous one";
  }
  return "unknown";
}

namespace lcp_detail {

namespace {

// Two ratios b_k / a_k are "tied" when pivoting on the smaller one would leave the other row's
// basic variable within this (normalised) distance of zero. Data is equilibrated and q has
// max-norm 1, so this is relative to the scale of the problem.
constexpr double kTieTol = 1e-12;
// Basic values |y_i| below kClampTol * max(1, |y|_inf) are set to exactly 0 (if the residual
// does not get worse by it).
constexpr double kClampTol = 1e-12;
// Shift of the normalised q (max-norm 1) along the covering vector after a ray: a hundred times
// below LemkeOptions::feas_tol's default, far above the rounding of the circuit's elimination.
constexpr double kRoundingShift = 1e-12;
// Sizes of the generic shift of the normalised q after a broken path, tried in turn: a thousand times
// above the rounding noise of the bases seen (1e-12 .. 1e-11 on the adders), below the accepted
// residual's scale once finish() re-solves the final basis on the q as given (1e-6 was too far
// on the adders: that basis missed feas_tol).
constexpr double kDegenerateShifts[] = {1e-9, 1e-7};

// Zobrist key of a tableau variable: the basis hash is the XOR of its variables' keys.
std::uint64_t basis_key(int var) {
  std::uint64_t x = static_cast<std::uint64_t>(var) + 0x9E3779B97F4A7C15ull;  // splitmix64
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

// Component i of the generic shift: 1 + frac((i + 1) * golden ratio), in [1, 2), all distinct.
double generic_shift(int i) { return 1.0 + std::fmod(0.6180339887498949 * (i + 1), 1.0); }

}  // namespace

void LemkeEngine::set_matrix(const Eigen::MatrixXd& M) {
  eq_ = equilibrate(M);
  n_ = static_cast<int>(M.rows());
  Binv_.setIdentity(n_, n_);
  b_.resize(n_);
  a_.resize(n_);
  qt_.resize(n_);
  y_.resize(n_);
  y2_.resize(n_);
  v_.resize(n_);
  dq_.resize(n_);
  bd_.resize(n_);
  prow_.resize(n_);
  basis_.assign(n_, 0);
  keep_.reserve(n_);
  keep2_.reserve(n_);
}

// a = Binv * (tableau column of var): w_i -> e_i, y_j -> -S(:, j), s -> -d = -1.
void LemkeEngine::entering_column(int var) {
  if (var < n_) {
    a_ = Binv_.col(var);
  } else if (var < 2 * n_) {
    a_.noalias() = Binv_ * eq_.S.col(var - n_);
    a_ = -a_;
  } else {
    a_ = -Binv_.rowwise().sum();
  }
}

void LemkeEngine::pivot(int r, int entering) {
  const double p = a_(r);
  prow_ = Binv_.row(r) / p;
  const double br = b_(r) / p;
  // Row i -= a_i * (row r / p) for every i; row r itself becomes 0 and is then replaced.
  Binv_.noalias() -= a_ * prow_;
  b_ -= a_ * br;
  Binv_.row(r) = prow_;
  b_(r) = br;
  basis_[r] = entering;
}

// Basis matrix B = [column(basis_[0]) ... column(basis_[n-1])]; Binv = B^{-1}, b = Binv qt.
// Limits the drift of the product-form updates on long pivot sequences.
void LemkeEngine::refactor() {
  Eigen::MatrixXd B = Eigen::MatrixXd::Zero(n_, n_);
  for (int i = 0; i < n_; ++i) {
    int v = basis_[i];
    if (v < n_) B(v, i) = 1.0;
    else if (v < 2 * n_) B.col(i) = -eq_.S.col(v - n_);
    else B.col(i).setConstant(-1.0);
  }
  Eigen::PartialPivLU<Eigen::MatrixXd> lu(B);
  Eigen::MatrixXd inv = lu.inverse();
  if (!inv.allFinite()) return;  // keep the updated inverse
  Binv_ = inv;
  b_.noalias() = Binv_ * qt_;
  since_refactor_ = 0;
}

// Lexicographic minimum ratio test over rows with a_k > pivot_tol * max(1, |a|_inf):
// minimise [b_k, Binv(k, 0), ..., Binv(k, n-1)] / a_k. A row holding the artificial variable s
// that ties in the first component is preferred (then s leaves and Lemke stops with a solution).
// Returns -1 if no row qualifies (ray termination).
int LemkeEngine::lexicographic_leaving_row(double pivot_tol) {
  const double amax = a_.cwiseAbs().maxCoeff();
  const double ptol = pivot_tol * std::max(1.0, amax);
  keep_.clear();
  double tmin = std::numeric_limits<double>::infinity();
  for (int k = 0; k < n_; ++k) {
    if (a_(k) > ptol) {
      keep_.push_back(k);
      tmin = std::min(tmin, std::max(b_(k), 0.0) / a_(k));
    }
  }
  if (keep_.empty()) return -1;
  if (keep_.size() > 1) {
    // First component: rows whose basic variable would reach zero (within tolerance).
    const double btol = kTieTol * std::max(1.0, b_.cwiseAbs().maxCoeff());
    keep2_.clear();
    for (int k : keep_)
      if (std::max(b_(k), 0.0) - tmin * a_(k) <= btol) keep2_.push_back(k);
    if (!keep2_.empty()) keep_.swap(keep2_);  // empty only with NaN (broken basis)
  }
  if (keep_.size() > 1) {
    for (int k : keep_)
      if (basis_[k] == 2 * n_) return k;
  }
  for (int j = 0; j < n_ && keep_.size() > 1; ++j) {
    double rmin = std::numeric_limits<double>::infinity();
    for (int k : keep_) rmin = std::min(rmin, Binv_(k, j) / a_(k));
    const double ctol = kTieTol * std::max(1.0, Binv_.col(j).cwiseAbs().maxCoeff());
    keep2_.clear();
    for (int k : keep_)
      if (Binv_(k, j) - rmin * a_(k) <= ctol) keep2_.push_back(k);
    if (keep2_.empty()) break;  // NaN
    keep_.swap(keep2_);
  }
  // Exact lexicographic ties are impossible (Binv non-singular); if rounding leaves several
  // rows, take the numerically safest pivot.
  int best = keep_.front();
  for (int k : keep_)
    if (a_(k) > a_(best)) best = k;
  return best;
}

void LemkeEngine::basic_z(std::string& set) const {
  set.assign(n_, 0);
  for (int i = 0; i < n_; ++i)
    if (basis_[i] >= n_ && basis_[i] < 2 * n_) set[basis_[i] - n_] = 1;
}

// out's basic_z, z and w from the current basis and y_ (normalised units, qn the scale of q).
void LemkeEngine::answer_from_basis(const Eigen::MatrixXd& M, const Eigen::VectorXd& q, double qn,
                                    LcpSolution& out) const {
  out.basic_z.clear();
  for (int i = 0; i < n_; ++i)
    if (basis_[i] >= n_ && basis_[i] < 2 * n_) out.basic_z.push_back(basis_[i] - n_);
  std::sort(out.basic_z.begin(), out.basic_z.end());
  out.z = eq_.col.cwiseProduct(y_) * qn;
  out.w = q;
  out.w.noalias() += M * out.z;
}

void LemkeEngine::finish(const Eigen::MatrixXd& M, const Eigen::VectorXd& q, double qn,
                         const LemkeOptions& options, bool solved, LcpSolution& out) {
  y_.setZero();
  for (int i = 0; i < n_; ++i)
    if (basis_[i] >= n_ && basis_[i] < 2 * n_) y_(basis_[i] - n_) = b_(i);

  if (solved) {
    double res = scaled_residual(eq_.S, qt_, y_, v_);
    // Polish: re-solve S_JJ y_J = -qt_J on the final complementary basis.
    std::vector<int> J;
    for (int i = 0; i < n_; ++i)
      if (basis_[i] >= n_ && basis_[i] < 2 * n_) J.push_back(basis_[i] - n_);
    if (!J.empty()) {
      const int k = static_cast<int>(J.size());
      Eigen::MatrixXd SJ(k, k);
      Eigen::VectorXd rhs(k);
      for (int a = 0; a < k; ++a) {
        rhs(a) = -qt_(J[a]);
        for (int c = 0; c < k; ++c) SJ(a, c) = eq_.S(J[a], J[c]);
      }
      Eigen::VectorXd yJ = Eigen::PartialPivLU<Eigen::MatrixXd>(SJ).solve(rhs);
      if (yJ.allFinite()) {
        y2_.setZero();
        for (int a = 0; a < k; ++a) y2_(J[a]) = yJ(a);
        double res2 = scaled_residual(eq_.S, qt_, y2_, v_);
        if (res2 <= res) {
          y_ = y2_;
          res = res2;
        }
      }
    }
    // Clean tiny values (degenerate basic variables at zero level, rounding negatives).
    const double ymax = y_.cwiseAbs().maxCoeff();
    const double accept = options.feas_tol * std::max(1.0, ymax);
    const double thr = kClampTol * std::max(1.0, ymax);
    y2_ = y_;
    bool changed = false;
    for (int i = 0; i < n_; ++i)
      if (y2_(i) != 0.0 && std::abs(y2_(i)) < thr) {
        y2_(i) = 0.0;
        changed = true;
      }
    if (changed) {
      double res2 = scaled_residual(eq_.S, qt_, y2_, v_);
      if (res2 <= std::max(res, accept)) {
        y_ = y2_;
        res = res2;
      }
    }
    out.status = res <= accept ? LcpStatus::Solved : LcpStatus::NumericalFailure;
  }
  answer_from_basis(M, q, qn, out);
}

// Complementary pivoting on the normalised data qt_ from the all-w basis until the artificial
// variable leaves (Solved), a ray, a revisited basis (Cycling) or the pivot limit (per path;
// `pivots` counts all paths). Leaves the final basis in basis_/b_.
LcpStatus LemkeEngine::pivot_to_end(const LemkeOptions& options, int& pivots) {
  const int max_pivots = (options.max_pivots > 0 ? options.max_pivots : 50 * (n_ + 1)) + pivots;
  const int s = 2 * n_;
  Binv_.setIdentity();
  b_ = qt_;
  for (int i = 0; i < n_; ++i) basis_[i] = i;
  since_refactor_ = 0;
  if ((qt_.array() >= 0.0).all()) return LcpStatus::Solved;  // z = 0: the all-w basis

  // First pivot: s enters at the level making qt + s d >= 0; w_r leaves for the most negative
  // qt_r. Ties: the lexicographic rule on [qt_i, e_i] picks the largest index.
  const double qmin = qt_.minCoeff();
  const double qtol = kTieTol * std::max(1.0, std::abs(qmin));
  int r = 0;
  for (int i = 0; i < n_; ++i)
    if (qt_(i) <= qmin + qtol) r = i;
  a_.setConstant(-1.0);
  int leaving = basis_[r];
  pivot(r, s);
  ++pivots;
  std::uint64_t hash = 0;
  for (int i = 0; i < n_; ++i) hash ^= basis_key(basis_[i]);
  visited_.clear();
  visited_.insert(hash);

  const int refactor_every = std::max(64, n_);
  for (;;) {
    if (leaving == s) return LcpStatus::Solved;
    if (pivots >= max_pivots) return LcpStatus::IterationLimit;
    const int entering = leaving < n_ ? leaving + n_ : leaving - n_;
    entering_column(entering);
    r = lexicographic_leaving_row(options.pivot_tol);
    if (r < 0) {
      ray_.clear();
      if (entering >= n_ && entering < 2 * n_) ray_.push_back(entering - n_);
      for (int i = 0; i < n_; ++i)
        if (basis_[i] >= n_ && basis_[i] < 2 * n_ && a_(i) < -options.pivot_tol) ray_.push_back(basis_[i] - n_);
      std::sort(ray_.begin(), ray_.end());
      return LcpStatus::RayTermination;
    }
    leaving = basis_[r];
    pivot(r, entering);
    ++pivots;
    hash ^= basis_key(leaving) ^ basis_key(entering);
    if (!visited_.insert(hash).second) return LcpStatus::Cycling;
    if (++since_refactor_ >= refactor_every) refactor();
  }
}

void LemkeEngine::solve(const Eigen::MatrixXd& M, const Eigen::VectorXd& q,
                        const LemkeOptions& options, LcpSolution& out) {
  check_square(M, q, "solve_lemke");
  if (M.rows() != n_) throw std::invalid_argument("LemkeEngine: matrix size changed");
  out.pivots = 0;
  out.restarts = 0;
  out.status = LcpStatus::Solved;
  if ((q.array() >= 0.0).all()) {
    // The all-w basis, its inverse with it (solve_from_basis may start from it).
    for (int i = 0; i < n_; ++i) basis_[i] = i;
    Binv_.setIdentity();
    since_refactor_ = 0;
    out.z.setZero(n_);
    out.w = q;
    return;
  }
  const double qn = normalise_q(eq_, q, qt_);
  solve_path(M, q, qn, options, 0.0, out);
  // Rounding broke the lexicographic rule: the path came back to a basis. Restart on a
  // generically shifted q. (Not after a NumericalFailure: its callers repair that basis on
  // the problem as given -- the warm solver by principal pivoting, the operating point on the
  // unreduced DC equations -- and a restart there ends on another solution of a regularised
  // problem: rca3040's operating point lost its symmetry.)
  LcpSolution retry;
  for (double shift : kDegenerateShifts) {
    if (out.status != LcpStatus::Cycling) break;
    retry.pivots = out.pivots;
    solve_path(M, q, qn, options, shift, retry);
    const bool better = retry.status == LcpStatus::Solved || out.status == LcpStatus::Cycling;
    retry.restarts = out.restarts + 1;
    if (better) std::swap(out, retry);
    else out.pivots = retry.pivots, out.restarts = retry.restarts;
  }
}

// One complementary path on qt_ + shift * generic_shift (qt_ itself is left as it was), then the
// answer for the q as given.
void LemkeEngine::solve_path(const Eigen::MatrixXd& M, const Eigen::VectorXd& q, double qn,
                             const LemkeOptions& options, double shift, LcpSolution& out) {
  const Eigen::VectorXd qt_given = qt_;
  auto path_on = [&](double uniform) {
    for (int i = 0; i < n_; ++i) qt_(i) = qt_given(i) + shift * generic_shift(i) + uniform;
    const LcpStatus status = pivot_to_end(options, out.pivots);
    qt_ = qt_given;
    if (status == LcpStatus::Solved && (shift != 0.0 || uniform != 0.0)) b_.noalias() = Binv_ * qt_;
    return status;
  };
  LcpStatus status = path_on(0.0);
  if (status == LcpStatus::RayTermination) {
    // For copositive-plus M a ray means the LCP is infeasible (Stewart 2.2.1, Theorem 2.10) —
    // but circuit data can be infeasible by rounding alone: where KCL ties a pair's w to the
    // others' z exactly (w_1 = -z_2: a node reached only through diodes), a q_1 that should be 0
    // and comes out of the elimination as -1e-17 leaves no solution. Solve the neighbouring LCP
    // with q moved along the covering vector by far less than the accepted residual; finish()
    // accepts its z only if it solves the LCP as given within feas_tol.
    status = path_on(kRoundingShift);
  }
  out.status = status;
  out.ray.clear();
  if (status == LcpStatus::RayTermination) out.ray = ray_;
  finish(M, q, qn, options, status == LcpStatus::Solved, out);
}

bool LemkeEngine::solve_from_basis(const Eigen::MatrixXd& M, const Eigen::VectorXd& q,
                                   const Eigen::VectorXd& from_q, const LemkeOptions& options, int max_pivots,
                                   LcpSolution& out) {
  check_square(M, q, "solve_from_basis");
  if (M.rows() != n_ || from_q.size() != n_ || n_ == 0) return false;
  for (int i = 0; i < n_; ++i)
    if (basis_[i] == 2 * n_) return false;  // the artificial variable is basic: no solved basis
  const double qn = normalise_q(eq_, q, qt_);
  dq_ = eq_.row.cwiseProduct(from_q) / qn - qt_;
  int pivots = 0;
  double s_now = 1.0;
  const int refactor_every = std::max(64, n_);
  for (;;) {
    // Basic values along the path: y_B(s) = b + s bd, feasible at s_now.
    b_.noalias() = Binv_ * qt_;
    bd_.noalias() = Binv_ * dq_;
    const double scale = std::max(1.0, b_.cwiseAbs().maxCoeff() + bd_.cwiseAbs().maxCoeff());
    int r = -1;
    double s_block = 0.0;
    auto blocks_at = [&](int i) {  // where y_i reaches 0 as s falls; -1 if it stays >= 0 to s = 0
      return bd_(i) > kTieTol * scale && b_(i) < 0.0 ? -b_(i) / bd_(i) : -1.0;
    };
    for (int i = 0; i < n_; ++i)
      if (const double si = blocks_at(i); si > s_block) s_block = si, r = i;
    if (r < 0) break;  // feasible down to s = 0
    if (s_block > s_now * (1 + 1e-9) + 1e-12 || pivots >= max_pivots) return false;
    // Rows reaching 0 together (a degenerate vertex: junctions that switch as one): the first
    // whose principal pivot continues the path (a_r < 0, below) leaves.
    tied_.clear();
    for (int i = 0; i < n_; ++i)
      if (std::abs(blocks_at(i) - s_block) <= 1e-9 * s_block) tied_.push_back(i);
    if (tied_.size() > 1) {
      for (int i : tied_) {
        const int leaving = basis_[i];
        entering_column(leaving < n_ ? leaving + n_ : leaving - n_);
        if (a_(i) < -options.pivot_tol * std::max(1.0, a_.cwiseAbs().maxCoeff())) {
          r = i;
          break;
        }
      }
    }
    s_now = std::min(s_now, s_block);
    const int leaving = basis_[r];
    const int entering = leaving < n_ ? leaving + n_ : leaving - n_;
    entering_column(entering);
    // The entering variable grows from 0 as s falls below s_now only if a_r < 0 (row r reads
    // y_r = b_r + s bd_r - a_r x_e = 0); otherwise the path turns back here.
    const double amax = std::max(1.0, a_.cwiseAbs().maxCoeff());
    if (!(a_(r) < -options.pivot_tol * amax)) return false;
    pivot(r, entering);
    ++pivots;
    if (++since_refactor_ >= refactor_every) refactor();
  }
  y_.setZero();
  for (int i = 0; i < n_; ++i)
    if (basis_[i] >= n_ && basis_[i] < 2 * n_) y_(basis_[i] - n_) = std::max(0.0, b_(i));
  const double accept = options.feas_tol * std::max(1.0, y_.cwiseAbs().maxCoeff());
  if (!(scaled_residual(eq_.S, qt_, y_, v_) <= accept)) return false;
  out.status = LcpStatus::Solved;
  out.pivots = pivots;
  out.restarts = 0;
  out.ray.clear();
  answer_from_basis(M, q, qn, out);
  return true;
}

}  // namespace lcp_detail

LcpSolution solve_lemke(const Eigen::MatrixXd& M, const Eigen::VectorXd& q,
                        const LemkeOptions& options) {
  lcp_detail::check_square(M, q, "solve_lemke");
  LcpSolution out;
  if ((q.array() >= 0.0).all()) {
    out.z = Eigen::VectorXd::Zero(q.size());
    out.w = q;
    return out;
  }
  lcp_detail::LemkeEngine engine(M);
  engine.solve(M, q, options, out);
  return out;
}

}  // namespace lcs
