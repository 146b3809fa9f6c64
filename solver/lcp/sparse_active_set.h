// A mixed LCP on a sparse system, solved by active sets without forming its dense Schur
// complement: find y (free) and z with
//
//   K y + L z = a,     w = P y + Q z + b,     0 <= z ⟂ w >= 0.
//
// A time step of an LCS is one (Stewart 8.4: K = I - h theta A, L = -h theta B, P = C, Q = D).
// Eliminating y gives the LCP(q, M) with M = Q - P K^-1 L, which is dense even when the circuit
// is sparse: this solver never forms it. A mode J (the pairs with w = 0 and z free; the others
// have z = 0) turns the problem into one sparse linear system of n + m unknowns,
//
//   [ K     L   ] [y]   [ a  ]
//   [ P_J   Q_J ] [z] = [-b_J ]     and  z_i = 0 for i outside J,
//
// whose solution is accepted when z_J >= 0 and w_i >= 0 outside J. The first mode tried is the
// previous call's (a time step's mode rarely changes: the warm start). Otherwise the pairs that
// violate their sign conditions are flipped together (block principal pivoting, Judice and
// Pires 1994), falling back to flipping one pair at a time, the largest index (Murty's rule,
// finite for a P-matrix M) after three flips that did not shrink the violating set. Before
// Murty, a stalled search is trimmed (at most three times a solve): the violators flipped and
// every pair whose z is below 1e-6 of the largest taken off; a trimmed pair goes on again at any
// negative w, so no z below the feasibility tolerance is lost. On a 500-stage multiplier's
// charging front the block flip turns on a whole chain of diodes whose currents are then tiny
// and negative at its far end, and Murty's flips walked that end back one diode per solve: 5073
// rounds that found violators in 1000 steps (479 in one step), 213 with the trim.
//
// Cost model. Each mode's matrix has the same sparsity pattern (rows outside J are unit rows
// stored with explicit zeros), analysed once and factorised per mode by KLU (its block
// triangular form and AMD ordering; sparse_active_set.cpp): O(nnz(L+U)) per factorisation, and each warm hit costs one pair of triangular solves, O(nnz(L+U)), plus one
// product with [P Q], O(nnz). For a circuit whose graph is a ladder, a tree of rectifiers or a
// chain, nnz(L+U) grows like n + m, so a step costs O(n + m), not the O((n + m)^2) of a dense
// Schur complement. Factorisations are cached per mode under a byte budget (least recently used
// evicted), so a periodic circuit factorises each of its modes once.
//
// Low-rank updates (set_low_rank, off by default). A mode J that differs from a factorised base
// mode J0 in k pairs differs from it in k rows: M_J = M_0 + E_S D_S (E_S the unit columns of
// those rows, D_S their change), so by the Sherman–Morrison–Woodbury formula
//
//   M_J^-1 r = s - G_S (I + D_S G_S)^-1 D_S s,   s = M_0^-1 r,   G_S = M_0^-1 E_S,
//
// one pair of triangular solves with M_0's factors, the columns G_S (solved once per pair while
// the base stands), and a dense k x k system; one step of iterative refinement against M_J
// itself, on the mode the search accepts, keeps the answer at rounding. A mode more than `max_rank` pairs from the base is
// factorised and becomes the base, and so does a mode the update answered at the warm start
// (found twice running: likely to stay). Where modes wander (a multiplier charging, every step a new
// mode and each search several), this replaces a sparse factorisation per mode tried, O(nnz(L+U))
// with a large constant, by O(k nnz(L+U)) for the new columns and O(k (n + m) + k^3) per solve.
//
// Failure (a singular mode, or no answer within the pivot limit) is reported, not guessed: the
// caller falls back to Lemke on the dense M (time_stepper's dense path).
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

#include <Eigen/Dense>
#include <Eigen/Sparse>

namespace lcs {

struct SparseActiveSetStats {
  long solves = 0;
  long warm_hits = 0;          // the previous mode answered
  long flips = 0;              // pairs whose side changed, summed
  long factorisations = 0;     // numeric factorisations (cache misses)
  long failures = 0;           // solves that returned false
  long evictions = 0;          // cached factorisations dropped to stay within the budget
  long updates = 0;            // modes solved by a low-rank update of the base (set_low_rank)
  std::size_t cache_bytes = 0; // the cache's current estimate

  SparseActiveSetStats& operator+=(const SparseActiveSetStats& o) {
    solves += o.solves;
    warm_hits += o.warm_hits;
    flips += o.flips;
    factorisations += o.factorisations;
    failures += o.failures;
    evictions += o.evictions;
    updates += o.updates;
    cache_bytes += o.cache_bytes;
    return *this;
  }
};

class SparseActiveSetLcp {
 public:
  using Sparse = Eigen::SparseMatrix<double>;
  // K: n x n, L: n x m, P: m x n, Q: m x m. `cache_budget_bytes` bounds the cached factorisations.
  SparseActiveSetLcp(const Sparse& K, const Sparse& L, const Sparse& P, const Sparse& Q,
                     std::size_t cache_budget_bytes = std::size_t{128} << 20);
  ~SparseActiveSetLcp();
  SparseActiveSetLcp(const SparseActiveSetLcp&) = delete;
  SparseActiveSetLcp& operator=(const SparseActiveSetLcp&) = delete;

  // The first mode tried next: the pairs with z_i > 0 (a previous solution).
  void prefer(const Eigen::VectorXd& z);
  // Only the previous mode is tried; a change of mode is left to the caller (Lemke's method).
  // For LCPs that may have several solutions (transistor feedback, 5.4.7), where the solution
  // Lemke's path reaches is the regenerative switching and the nearest mode is not.
  void set_warm_only(bool warm_only) { warm_only_ = warm_only; }
  // Modes within `max_rank` pairs of a factorised base are solved by a low-rank update of its
  // factors (see above); 0 (the default): every mode is factorised and cached.
  void set_low_rank(int max_rank) { max_rank_ = max_rank; }
  // Solves for (y, z); w = P y + Q z + b. False when the mode search fails (then y, z are
  // unspecified and the previous mode is kept).
  bool solve(const Eigen::VectorXd& a, const Eigen::VectorXd& b, Eigen::VectorXd& y,
             Eigen::VectorXd& z, Eigen::VectorXd& w);
  const SparseActiveSetStats& stats() const { return stats_; }
  // The reciprocal of the 1-norm condition number of a mode's matrix (KLU's condest, Hager's
  // estimate), 0 when it is singular; the mode is the pairs `on` that are nonzero. Factorised
  // for this and not cached.
  double mode_reciprocal_condition(const std::vector<char>& on);
  // An orthonormal basis (columns over [y | z]) of the null space of mode `on`'s matrix, from a
  // regular mode `regular` a few pairs away (at most `max_changed`): with M_on = M_reg + E_S D_S
  // (the rows of the pairs S that differ), M_on v = 0 exactly when v = -G_S c, G_S = M_reg^-1 E_S,
  // and (I + D_S G_S) c = 0, a k x k problem (k = |S|) solved by SVD (singular values below 1e-10
  // of the largest count as zero). False when `regular` is singular, too far, or the null space
  // has more than `max_dimension` vectors.
  bool mode_null_space(const std::vector<char>& on, const std::vector<char>& regular, int max_changed,
                       int max_dimension, Eigen::MatrixXd& basis);
  int states() const { return n_; }
  int pairs() const { return m_; }

 private:
  struct Symbolic;
  struct Factorisation;
  Sparse mode_matrix(const std::vector<char>& mode) const;
  std::unique_ptr<Factorisation> factorise(const std::vector<char>& mode);  // not cached
  bool lu_solve(const Factorisation& f, Eigen::VectorXd& x) const;           // in place
  bool lu_solve_block(const Factorisation& f, Eigen::MatrixXd& x) const;     // in place, column by column
  Factorisation* factorisation(const std::vector<char>& mode);               // cached
  Factorisation* cached_factorisation(const std::vector<char>& mode);
  bool solve_mode(const std::vector<char>& mode, const Eigen::VectorXd& a, const Eigen::VectorXd& b,
                  Eigen::VectorXd& y, Eigen::VectorXd& z, Eigen::VectorXd& w);
  void read_solution(const std::vector<char>& mode, const Eigen::VectorXd& b, Eigen::VectorXd& y,
                     Eigen::VectorXd& z, Eigen::VectorXd& w);

  struct Base;  // set_low_rank: the factorised base mode and its solved columns
  bool solve_updated(const std::vector<char>& mode, const Eigen::VectorXd& r, const Eigen::VectorXd& b,
                     Eigen::VectorXd& x);
  void apply_updated(const std::vector<int>& changed, const Eigen::PartialPivLU<Eigen::MatrixXd>& small,
                     Eigen::VectorXd& x);
  double pair_row_dot(int i, bool on, const Eigen::VectorXd& v) const;  // row n + i of a mode, times v
  void refine_updated(const std::vector<char>& mode, const Eigen::VectorXd& r, Eigen::VectorXd& x);

  int n_ = 0, m_ = 0;
  int max_rank_ = 0;
  bool updated_ = false;           // the last mode solved was an update: its pairs and small LU
  long solve_count_ = 0;           // solve() calls so far: which data a base's s_0 was solved for
  std::vector<int> changed_;
  Eigen::PartialPivLU<Eigen::MatrixXd> small_lu_;
  Eigen::SparseMatrix<double, Eigen::RowMajor> top_;  // [K L], for residuals
  Sparse pattern_;                 // [K L; P Q] plus the pair diagonal, column-major
  std::vector<std::vector<std::pair<int, int>>> pair_entries_;  // per pair row: (column, slot)
  std::vector<int> diagonal_slot_; // per pair: the slot of its (n + i, n + i) entry
  Eigen::SparseMatrix<double, Eigen::RowMajor> PQ_;  // [P Q], for w
  std::vector<char> mode_;         // the last accepted mode (1: z free, w = 0)
  bool warm_only_ = false;
  SparseActiveSetStats stats_;
  std::size_t budget_;
  std::unique_ptr<Symbolic> symbolic_;  // declared before base_ and cache_: they free through it
  std::unique_ptr<Base> base_;
  struct Cache;
  std::unique_ptr<Cache> cache_;
  std::vector<char> last_mode_;    // the last mode factorisation() answered, and its entry
  Factorisation* last_ = nullptr;
  Eigen::VectorXd rhs_, sol_;
};

}  // namespace lcs
