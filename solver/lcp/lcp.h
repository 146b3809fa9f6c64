// Linear complementarity problems: find z with 0 <= z  ⟂  w = M z + q >= 0   (Stewart 2.2).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Dense>

namespace lcs {

enum class LcpStatus {
  Solved,
  RayTermination,   // Lemke ended on an unbounded ray: no solution (M copositive-plus) or M outside
                    // the classes Lemke handles
  IterationLimit,
  NotUnique,        // LcpWarmSolver: several solutions, no previous one to continue and no single
                    // stable one (index +1); z is Lemke's pick
  NumericalFailure, // Lemke reached a complementary basis (the artificial variable left) but the
                    // solution recomputed from it misses feas_tol: basis too ill-conditioned.
                    // z, w are the best available (residual-minimal) point; do not trust them.
  Cycling,          // Lemke's path returned to a basis it had left (impossible in exact arithmetic:
                    // rounding decided a degenerate ratio test), also on q shifted to break the
                    // degeneracy. Nothing is known about solutions; z is not one.
};
const char* lcp_status_name(LcpStatus s);

struct LemkeOptions {
  int max_pivots = 0;          // 0: 50 * (n + 1)
  double pivot_tol = 1e-12;    // |entry| below this (relative to the column's scale) is not a pivot
  double feas_tol = 1e-10;     // accepted complementarity residual (relative to |q|, |M|), see residual
};

struct LcpSolution {
  LcpStatus status = LcpStatus::Solved;
  Eigen::VectorXd z, w;        // w = M z + q
  int pivots = 0;              // Lemke pivots spent (0 for the warm path), over all paths
  int restarts = 0;            // Lemke paths restarted on a shifted q (after Cycling)
  // RayTermination: the pairs whose z grows along the unbounded ray (the certificate's support:
  // what the data drives against its constraints). Empty otherwise.
  std::vector<int> ray;
  // solve_lemke, Solved or NumericalFailure: the pairs whose z is basic in the final complementary
  // basis (ascending), a superset of {z > 0} with M_JJ nonsingular. A degenerate pair (z = w = 0)
  // is in it when the basis needs its w = 0 row to fix the others' z (a node that floats unless
  // that diode conducts). Empty for q >= 0 (no pivot) and from the warm solver.
  std::vector<int> basic_z;
};

// Lemke's complementary pivoting with covering vector d = (1,...,1) and lexicographic
// degeneracy resolution (2.2.1): never cycles in exact arithmetic; where rounding makes the path
// revisit a basis (Cycling), it restarts on q shifted by a small generic vector (lemke.cpp).
// For q >= 0 returns z = 0 without pivoting.
// Implementation notes (lemke.cpp): M is first equilibrated by exact power-of-two row/column
// scaling (an equivalent LCP; d = 1 refers to the scaled problem) and q normalised, so the
// tolerances are relative to the data; on a complementary basis z is re-solved from M_JJ,
// values below ~1e-12 relative are set to 0, and the status is Solved only if the recomputed
// residual meets feas_tol (else NumericalFailure). On RayTermination / IterationLimit, z is the
// last basic point (not a solution). w is always M z + q recomputed from the returned z, so it
// may carry rounding-level negatives (~1e-16 relative to |q| + |M||z|).
LcpSolution solve_lemke(const Eigen::MatrixXd& M, const Eigen::VectorXd& q,
                        const LemkeOptions& options = {});

// Natural residual max_i |min(z_i, w_i)| together with max(0, -z_i, -w_i): zero iff z solves
// LCP(q, M) exactly; the number every test and debug check compares against a tolerance.
double lcp_residual(const Eigen::MatrixXd& M, const Eigen::VectorXd& q, const Eigen::VectorXd& z);

// Whether z solves LCP(q, M) to rounding, with w = M z + q: every z_i >= -t, w_i >= -t_i and
// one of them within its tolerance of 0, where t = tol max(1, |q|_inf, |z|_inf) and
// t_i = max(t, 64 eps (|q_i| + sum_j |M_ij z_j|)), eps the machine epsilon: the rounding that
// computing w_i leaves, whatever z is. A loop through 1 TOhm beside 0.05 Ohm carries 2e12 x 0.014 A
// in its row, so w_i is known to ~1e-6 V there. Where no row's products are that large this is
// lcp_residual(M, q, z) <= t.
bool lcp_solved_to_rounding(const Eigen::MatrixXd& M, const Eigen::VectorXd& q, const Eigen::VectorXd& z,
                            double tol);

// Every solution of LCP(q, M), by enumerating active sets (n <= 24). Distinct solutions only
// (within a relative 1e-9), sorted lexicographically by z. Used by `op --all`.
// Only vertex solutions (from non-singular M_JJ) are found: where the solution set contains a
// continuum (degenerate M, e.g. M = [[1,1],[1,1]], q = [-1,-1]) just its vertices are returned.
// Cost 2^n LU factorisations; throws std::invalid_argument for n > 24. n = 0 gives {empty}.
std::vector<Eigen::VectorXd> enumerate_lcp_solutions(const Eigen::MatrixXd& M,
                                                     const Eigen::VectorXd& q);

// The index of a solution, sign(det M_JJ) over J = {z > 0} (+1 for J empty): +1 where the
// solution is stable under the fast dynamics small charge storage adds, -1 at a saddle (a
// flip-flop's balanced state); 0 when M_JJ is singular.
int lcp_solution_index(const Eigen::MatrixXd& M, const Eigen::VectorXd& z);

// Solutions with different w = M z + q (relative 1e-9), the first of each kept. A diode network's
// LCP has a unique w even where z is not (a continuum of currents, e.g. a bridge at rest): only
// different w are different states of the circuit (several operating points).
std::vector<Eigen::VectorXd> distinct_in_w(const Eigen::MatrixXd& M, const Eigen::VectorXd& q,
                                           const std::vector<Eigen::VectorXd>& solutions);

struct LcpWarmStats {
  long solves = 0;             // calls to solve()
  long warm_hits = 0;          // answered by the previous active set (one solve + sign check)
  long lemke_calls = 0;
  long lemke_pivots = 0;
  long polished = 0;           // Lemke's failures repaired by principal pivoting
  long lemke_restarts = 0;     // Lemke paths restarted on a shifted q (see solve_lemke)
  long pivoted = 0;            // answered by parametric pivoting from the last basis (LcpWarmSolver)
  long pivoted_pivots = 0;

  LcpWarmStats& operator+=(const LcpWarmStats& o) {
    solves += o.solves;
    pivoted += o.pivoted;
    pivoted_pivots += o.pivoted_pivots;
    polished += o.polished;
    lemke_restarts += o.lemke_restarts;
    warm_hits += o.warm_hits;
    lemke_calls += o.lemke_calls;
    lemke_pivots += o.lemke_pivots;
    return *this;
  }
};

// For a fixed matrix M and a sequence of q (one per time step): first tries the previous
// solution's active set J = {i : z_i > 0} -- solve M_JJ z_J = -q_J, accept if z_J >= 0 and
// w >= 0 within tolerance -- and falls back to Lemke. Factorisations of M_JJ are cached per
// active set (any n; the cache is dropped when it would pass kWarmCacheBytes), so a periodic
// circuit factorises each mode once.
// Warm hits do not allocate once the active set's factorisation is cached. Copies of a solver
// share the cache and work vectors (shared_ptr): do not use copies from different threads.
class LcpWarmSolver {
 public:
  explicit LcpWarmSolver(Eigen::MatrixXd M, LemkeOptions options = {});
  const LcpSolution& solve(const Eigen::VectorXd& q);
  const LcpWarmStats& stats() const { return stats_; }
  const Eigen::MatrixXd& matrix() const { return M_; }
  // Before the first solve: the active set {z > 0} of a known previous solution (the operating
  // point, or the last step's z when a new step size gets its own solver) is the first guess.
  // `always`: also after solves (the next solve tries this active set first).
  void prefer(const Eigen::VectorXd& z, bool always = false);
  // M stacks `blocks` copies of the same pairs (a collocation step's stages). Makes the next
  // first guess the last block's active set in every block, where the last answer's blocks
  // differ: a step whose stages sit in different modes had a switching inside it, and the step
  // after it continues the mode of its end, not that pattern (several stage patterns can solve
  // one step's LCP, and a kept one is then kept for good: radau_iia.cpp).
  void continue_last_block(int blocks);

  // M may admit several solutions (neither symmetric positive semidefinite nor M + M^T
  // positive definite: transistor feedback). Then each solve reports what it found:
  enum class Multiplicity {
    Unknown,                 // not counted (not possible, or too large to enumerate)
    One,
    SeveralKeptContinuous,   // several; the previous active set still solves it and was kept
    SeveralTookLemke,        // several, the previous mode ended: Lemke's solution taken
    SeveralTookStable,       // several, no previous state, the only index +1 one taken
    SeveralNoneContinuous,   // several, no previous state, no single stable one: NotUnique
  };
  bool several_possible() const { return several_possible_; }
  // Off by default (a diode network's LCP has a unique w): turns the counting on for circuits
  // with transistors, where M is not P by the cheap tests.
  void watch_multiplicity();
  Multiplicity multiplicity() const { return multiplicity_; }
  int solutions() const { return solutions_; }                  // when several
  const std::vector<int>& differ() const { return differ_; }    // indices on in some, off in others

 private:
  const LcpSolution& solve_once(const Eigen::VectorXd& q);
  bool solve_on_active_set(const Eigen::VectorXd& q);
  void polish_by_principal_pivoting(const Eigen::VectorXd& q, const Eigen::VectorXd& start);
  bool several_possible_ = false, several_seen_ = false, preferred_ = false;
  Multiplicity multiplicity_ = Multiplicity::Unknown;
  int solutions_ = 0;
  std::vector<int> differ_;
  struct Impl;
  Eigen::MatrixXd M_;
  LemkeOptions options_;
  LcpWarmStats stats_;
  LcpSolution last_;
  std::string active_;         // the last active set: active_[i] = 1 for i in J (any n)
  // The Lemke engine's basis, when it is the last answer's (else empty), and the last q it is
  // feasible for: where they hold, a step the warm hit misses pivots from there.
  std::string engine_basis_;
  Eigen::VectorXd engine_q_;
  std::string previous_active_;  // scratch
  std::shared_ptr<Impl> impl_; // factorisation cache
};

}  // namespace lcs
