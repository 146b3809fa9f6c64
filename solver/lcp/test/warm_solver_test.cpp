// LcpWarmSolver: same answers as Lemke on slowly varying q, exact warm-hit accounting,
// fallback on active-set changes, no heap allocation on steady-state warm hits.
#include "tests/support/sanitizers.h"
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <random>
#include <vector>

#include "solver/lcp/lcp.h"
#include "solver/lcp/test/test_util.h"

// Count heap allocations by interposing malloc/calloc/realloc (forwarded to glibc's allocator,
// so glibc's free stays valid). operator new and Eigen both go through malloc.
#if defined(__GLIBC__) && !LCS_UNDER_ASAN
#define LCS_COUNT_ALLOCS 1
extern "C" void* __libc_malloc(std::size_t);
extern "C" void* __libc_calloc(std::size_t, std::size_t);
extern "C" void* __libc_realloc(void*, std::size_t);
namespace {
std::atomic<long> g_allocs{0};
std::atomic<bool> g_counting{false};
}  // namespace
extern "C" void* malloc(std::size_t n) {
  if (g_counting.load(std::memory_order_relaxed)) g_allocs.fetch_add(1, std::memory_order_relaxed);
  return __libc_malloc(n);
}
extern "C" void* calloc(std::size_t a, std::size_t b) {
  if (g_counting.load(std::memory_order_relaxed)) g_allocs.fetch_add(1, std::memory_order_relaxed);
  return __libc_calloc(a, b);
}
extern "C" void* realloc(void* p, std::size_t n) {
  if (g_counting.load(std::memory_order_relaxed)) g_allocs.fetch_add(1, std::memory_order_relaxed);
  return __libc_realloc(p, n);
}
#endif

namespace lcs {
namespace {

std::uint64_t active_mask(const Eigen::VectorXd& z) {
  std::uint64_t m = 0;
  for (int i = 0; i < z.size(); ++i)
    if (z(i) > 0) m |= std::uint64_t{1} << i;
  return m;
}

Eigen::VectorXd vec(std::initializer_list<double> v) {
  Eigen::VectorXd x(v.size());
  int i = 0;
  for (double a : v) x(i++) = a;
  return x;
}

// q_i(t) = q0_i + a_i sin(omega_i t + phi_i): active sets change now and then.
std::vector<Eigen::VectorXd> slow_sequence(std::mt19937& rng, int n, int steps, double dt) {
  Eigen::VectorXd q0 = lcp_test::random_vector(rng, n), a(n), omega(n), phi(n);
  std::uniform_real_distribution<double> u(0.5, 2.0), ph(0, 6.28);
  for (int i = 0; i < n; ++i) a(i) = u(rng), omega(i) = u(rng), phi(i) = ph(rng);
  std::vector<Eigen::VectorXd> qs;
  for (int k = 0; k < steps; ++k) {
    Eigen::VectorXd q(n);
    for (int i = 0; i < n; ++i) q(i) = q0(i) + a(i) * std::sin(omega(i) * k * dt + phi(i));
    qs.push_back(q);
  }
  return qs;
}

void run_against_lemke(const Eigen::MatrixXd& M, const std::vector<Eigen::VectorXd>& qs) {
  LcpWarmSolver warm(M);
  long expected_hits = 0, lemke_pivots = 0;
  std::uint64_t prev = 0;  // the solver starts from the empty active set
  for (size_t k = 0; k < qs.size(); ++k) {
    const Eigen::VectorXd& q = qs[k];
    const LcpWarmStats before = warm.stats();
    const LcpSolution& s = warm.solve(q);
    LcpSolution ref = solve_lemke(M, q);
    ASSERT_EQ(ref.status, LcpStatus::Solved);
    ASSERT_EQ(s.status, LcpStatus::Solved) << "step " << k;
    EXPECT_LE((s.z - ref.z).cwiseAbs().maxCoeff(), 1e-9 * (1 + ref.z.norm())) << "step " << k;
    EXPECT_LE(lcp_residual(M, q, s.z), lcp_test::abs_tol(M, q, s.z));
    EXPECT_LE(lcp_test::w_mismatch(M, q, s.z, s.w), 1e-13);
    // Unique solutions and generic data: the previous active set works iff it is unchanged.
    const std::uint64_t now = active_mask(ref.z);
    const bool hit = now == prev;
    expected_hits += hit;
    EXPECT_EQ(warm.stats().warm_hits - before.warm_hits, hit ? 1 : 0) << "step " << k;
    EXPECT_EQ(s.pivots, hit ? 0 : ref.pivots);
    if (!hit) lemke_pivots += s.pivots;
    prev = now;
  }
  const LcpWarmStats& st = warm.stats();
  EXPECT_EQ(st.solves, static_cast<long>(qs.size()));
  EXPECT_EQ(st.warm_hits, expected_hits);
  EXPECT_EQ(st.warm_hits + st.lemke_calls, st.solves);
  EXPECT_EQ(st.lemke_pivots, lemke_pivots);
  EXPECT_GT(st.warm_hits, 0.9 * st.solves);  // slowly varying: mostly hits
  EXPECT_GT(st.lemke_calls, 3);               // and the active set did change
}

TEST(WarmSolver, SlowlyVaryingQMatchesLemkePMatrix) {
  std::mt19937 rng(41);
  for (int n : {1, 3, 8, 16}) {
    Eigen::MatrixXd M = lcp_test::random_p_matrix(rng, n);
    run_against_lemke(M, slow_sequence(rng, n, 3000, 0.01));
  }
}

TEST(WarmSolver, SlowlyVaryingQMatchesLemkeSpdBadlyScaled) {
  std::mt19937 rng(42);
  const int n = 12;
  Eigen::MatrixXd M = lcp_test::random_spd(rng, n);
  Eigen::VectorXd d(n);
  for (int i = 0; i < n; ++i) d(i) = std::pow(10.0, (i % 5 - 2) * 4.0);  // 1e-8 .. 1e8
  M = d.asDiagonal() * M * d.asDiagonal();  // still SPD, equivalent LCP after scaling
  std::vector<Eigen::VectorXd> qs = slow_sequence(rng, n, 2000, 0.01);
  for (Eigen::VectorXd& q : qs) q = d.cwiseProduct(q);
  run_against_lemke(M, qs);
}

// Hand-checked sequence on M = [[2,1],[1,2]].
TEST(WarmSolver, ChangedActiveSetFallsBackToLemke) {
  Eigen::MatrixXd M(2, 2);
  M << 2, 1, 1, 2;
  LcpWarmSolver warm(M);
  struct Step {
    Eigen::VectorXd q, z;
    bool hit;
  } steps[] = {
      {vec({-1, 1}), vec({0.5, 0}), false},         // {} fails (q1 < 0) -> Lemke
      {vec({-2, 1}), vec({1, 0}), true},            // {1}: z1 = 1, w2 = 2
      {vec({1, -1}), vec({0, 0.5}), false},         // {1}: z1 = -0.5 -> Lemke
      {vec({-1, -1}), vec({1.0 / 3, 1.0 / 3}), false},  // {2}: w1 = -0.5 -> Lemke
      {vec({-2, -2}), vec({2.0 / 3, 2.0 / 3}), true},   // {1,2}
      {vec({1, 1}), vec({0, 0}), false},            // {1,2}: z < 0 -> Lemke (q >= 0, 0 pivots)
      {vec({2, 3}), vec({0, 0}), true},             // {}
  };
  long hits = 0, calls = 0;
  for (const Step& st : steps) {
    const LcpSolution& s = warm.solve(st.q);
    ASSERT_EQ(s.status, LcpStatus::Solved);
    EXPECT_LE((s.z - st.z).cwiseAbs().maxCoeff(), 1e-15) << st.q.transpose();
    EXPECT_LE(lcp_residual(M, st.q, s.z), 1e-15);
    hits += st.hit;
    calls += !st.hit;
    EXPECT_EQ(warm.stats().warm_hits, hits) << st.q.transpose();
    EXPECT_EQ(warm.stats().lemke_calls, calls) << st.q.transpose();
  }
}

TEST(WarmSolver, FailuresArePropagatedAndRecovered) {
  Eigen::MatrixXd M(2, 2);
  M << 1, -1, -1, 1;  // PSD; q = (-1, -1) is infeasible
  LcpWarmSolver warm(M);
  EXPECT_EQ(warm.solve(vec({-1, 2})).status, LcpStatus::Solved);
  EXPECT_EQ(warm.solve(vec({-1, -1})).status, LcpStatus::RayTermination);
  const LcpSolution& s = warm.solve(vec({-2, 3}));  // the last good active set {1} still works
  EXPECT_EQ(s.status, LcpStatus::Solved);
  EXPECT_LE((s.z - vec({2, 0})).norm(), 1e-15);
  EXPECT_EQ(warm.stats().warm_hits, 1);
  EXPECT_EQ(warm.stats().lemke_calls, 2);
  EXPECT_THROW(warm.solve(vec({1, 2, 3})), std::invalid_argument);
}

// A bridge rectifier whose floating source and load are referenced by 1 TOhm each (implicit
// Euler, h = 0.1 us, C = 1 uF, RON = 0.05): M = 2e12 u u^T + S, u = (1, 1, -1, -1), positive
// definite, at the step where D1 and D4 start to conduct. Lemke's equilibrated tableau pivots on
// the 1e-14 that S is of the rank-one part and ends on a ray (every fixed-step method stopped
// with exit 3 there); principal pivoting from the previous mode solves it. Rows 0 and 3 summed:
// 0.15 z0 + 0.05 z3 = -(q0 + q3) with z0 = z3 to 1e-12, so z0 = z3 = 0.00279154 / 0.2; S's
// entries are stored beside 2e12 to 2.4e-4 (0.3 % of them).
TEST(WarmSolver, RayFromRoundingIsSolvedByPrincipalPivoting) {
  Eigen::VectorXd u = vec({1, 1, -1, -1});
  Eigen::MatrixXd S = Eigen::MatrixXd::Zero(4, 4);
  S << 0.15, 0.1, 0, 0, 0.1, 0.15, 0, 0, 0, 0, 0.05, 0, 0, 0, 0, 0.05;
  const Eigen::MatrixXd M = 2e12 * u * u.transpose() + S;
  const Eigen::VectorXd q = vec({-0.70279153955535811, 0.7000000000019615, 2.1027915395573196, 0.7});
  ASSERT_EQ(solve_lemke(M, q).status, LcpStatus::RayTermination) << "the case this test is for";
  LcpWarmSolver warm(M);
  const LcpSolution& s = warm.solve(q);
  ASSERT_EQ(s.status, LcpStatus::Solved);
  EXPECT_EQ(warm.stats().polished, 1);
  EXPECT_TRUE(lcp_solved_to_rounding(M, q, s.z, 1e-10));
  const double expected = 0.00279153955535815 / 0.2;
  EXPECT_NEAR(s.z(0), expected, 5e-3 * expected);
  EXPECT_NEAR(s.z(3), expected, 5e-3 * expected);
  EXPECT_EQ(s.z(1), 0.0);
  EXPECT_EQ(s.z(2), 0.0);
  EXPECT_GT(s.w(1), 1.0);  // D2 and D3 blocked by about the source's 1.4 V
  EXPECT_GT(s.w(2), 1.0);
  // The next step keeps the mode: answered by the warm start, not another ray.
  const LcpSolution& next = warm.solve(q + vec({-0.01, 0.01, 0.01, 0.01}));
  EXPECT_EQ(next.status, LcpStatus::Solved);
  EXPECT_TRUE(lcp_solved_to_rounding(M, q + vec({-0.01, 0.01, 0.01, 0.01}), next.z, 1e-10));
}

// Active sets of any size (issue 12: a 64-bit mask limited them, and above 64 pairs every step
// ran Lemke): a slowly moving q over 70 and 150 pairs is answered by the previous active set.
TEST(WarmSolver, LargeProblemsWarmStartToo) {
  std::mt19937 rng(43);
  for (int n : {70, 150}) {
    Eigen::MatrixXd M = lcp_test::random_spd(rng, n);
    LcpWarmSolver warm(M);
    std::vector<Eigen::VectorXd> qs = slow_sequence(rng, n, 10, 1e-4);
    for (const Eigen::VectorXd& q : qs) {
      const LcpSolution& s = warm.solve(q);
      ASSERT_EQ(s.status, LcpStatus::Solved);
      EXPECT_LE((s.z - solve_lemke(M, q).z).cwiseAbs().maxCoeff(), 1e-10 * (1 + s.z.norm()));
      EXPECT_LT(lcp_residual(M, q, s.z), 1e-10 * (1 + s.z.norm()));
    }
    EXPECT_GE(warm.stats().warm_hits, 7) << n;
    EXPECT_EQ(warm.stats().warm_hits + warm.stats().pivoted + warm.stats().lemke_calls, 10) << n;
  }
}

// From 32 pairs a step the warm hit misses pivots from the last answer's basis along the segment
// of q between the two steps (LemkeEngine::solve_from_basis) before Lemke: on P-matrices (one
// solution each) the same answers as Lemke's from scratch, the misses answered in a few pivots
// each where Lemke takes tens. A sine-driven q over 40 and 120 pairs, 400 steps. Measured: 82
// and 192 misses pivoted in 88 and 273 pivots, one Lemke call each (the first step), against
// 8491 and 27879 pivots for Lemke from scratch at every step.
TEST(WarmSolver, MissedHitsPivotFromTheLastBasis) {
  std::mt19937 rng(45);
  for (int n : {40, 120}) {
    SCOPED_TRACE(n);
    const Eigen::MatrixXd M = n == 40 ? lcp_test::random_p_matrix(rng, n) : lcp_test::random_spd(rng, n);
    LcpWarmSolver warm(M);
    long cold_pivots = 0;
    for (const Eigen::VectorXd& q : slow_sequence(rng, n, 400, 0.02)) {
      const LcpSolution& s = warm.solve(q);
      const LcpSolution ref = solve_lemke(M, q);
      ASSERT_EQ(ref.status, LcpStatus::Solved);
      ASSERT_EQ(s.status, LcpStatus::Solved);
      EXPECT_LE((s.z - ref.z).cwiseAbs().maxCoeff(), 1e-9 * (1 + ref.z.norm()));
      EXPECT_LE(lcp_residual(M, q, s.z), lcp_test::abs_tol(M, q, s.z));
      cold_pivots += ref.pivots;
    }
    const LcpWarmStats& st = warm.stats();
    EXPECT_EQ(st.warm_hits + st.pivoted + st.lemke_calls, 400);
    EXPECT_GT(st.pivoted, 20);
    EXPECT_GE(st.pivoted, 10 * st.lemke_calls);
    EXPECT_LT(st.pivoted_pivots, 3 * st.pivoted);            // a pair or two switch per miss
    EXPECT_LT(st.pivoted_pivots + st.lemke_pivots, cold_pivots / 10);
  }
}

// Pairs reaching zero together along the pivoted path (identical rows: junctions that switch as
// one, as in a TTL gate) leave one after the other at the same s; before, such a tie went to
// Lemke (846 of a TTL adder's 868 Lemke calls).
TEST(WarmSolver, TiedPairsArePivotedTogether) {
  const int n = 32;
  const Eigen::MatrixXd M = 2.0 * Eigen::MatrixXd::Identity(n, n);
  LcpWarmSolver warm(M);
  Eigen::VectorXd q = Eigen::VectorXd::Ones(n);
  q(5) = -1;
  ASSERT_EQ(warm.solve(q).status, LcpStatus::Solved);  // Lemke: its basis is the engine's
  ASSERT_EQ(warm.stats().lemke_calls, 1);
  q(0) = q(1) = -1;  // both reach w = 0 at the same point of the path
  const LcpSolution& s = warm.solve(q);
  ASSERT_EQ(s.status, LcpStatus::Solved);
  EXPECT_EQ(warm.stats().pivoted, 1);
  EXPECT_EQ(warm.stats().pivoted_pivots, 2);
  EXPECT_EQ(warm.stats().lemke_calls, 1);
  for (int i = 0; i < n; ++i) EXPECT_DOUBLE_EQ(s.z(i), i == 0 || i == 1 || i == 5 ? 0.5 : 0.0) << i;
}

// Lemke's answer z = 0 for q >= 0 takes no pivot; the engine's basis is then the all-w one and
// its inverse must be the identity, not the previous path's (review finding: a pivoted path
// started from that stale inverse). Here the next miss pivots from the all-w basis.
TEST(WarmSolver, PivotsFromTheAllWBasisAfterLemkesShortcut) {
  const int n = 32;
  Eigen::MatrixXd M = 2.0 * Eigen::MatrixXd::Identity(n, n);
  M(5, 7) = M(7, 5) = 0.5;  // so the stale inverse (basis z5) reaches pair 7's row
  LcpWarmSolver warm(M);
  Eigen::VectorXd q = Eigen::VectorXd::Ones(n);
  q(5) = -1;
  ASSERT_EQ(warm.solve(q).status, LcpStatus::Solved);  // Lemke's path: z5 basic
  Eigen::VectorXd other = Eigen::VectorXd::Zero(n);
  other(9) = 1;
  warm.prefer(other, /*always=*/true);  // a guess that is not the engine's basis
  q(5) = 1;
  ASSERT_EQ(warm.solve(q).status, LcpStatus::Solved);  // q >= 0: Lemke's shortcut, z = 0
  ASSERT_EQ(warm.stats().lemke_calls, 2);
  q(7) = -1;
  const LcpSolution& s = warm.solve(q);
  ASSERT_EQ(s.status, LcpStatus::Solved);
  EXPECT_EQ(warm.stats().pivoted, 1);
  EXPECT_EQ(warm.stats().lemke_calls, 2);
  for (int i = 0; i < n; ++i) EXPECT_DOUBLE_EQ(s.z(i), i == 7 ? 0.5 : 0.0) << i;
}

#ifdef LCS_COUNT_ALLOCS
// Periodic excitation: after the first period every mode's factorisation is cached, so a warm
// hit allocates nothing (the Lemke fallback may).
TEST(WarmSolver, WarmHitsDoNotAllocate) {
  std::mt19937 rng(44);
  const int n = 8;
  Eigen::MatrixXd M = lcp_test::random_p_matrix(rng, n);
  Eigen::VectorXd q0 = lcp_test::random_vector(rng, n), phase(n);
  for (int i = 0; i < n; ++i) phase(i) = 0.7 * i;
  const int period = 200;
  std::vector<Eigen::VectorXd> qs;
  for (int k = 0; k < 3 * period; ++k) {
    Eigen::VectorXd q(n);
    for (int i = 0; i < n; ++i) q(i) = q0(i) + 1.5 * std::sin(2 * M_PI * k / period + phase(i));
    qs.push_back(q);
  }
  LcpWarmSolver warm(M);
  for (int k = 0; k < period; ++k) warm.solve(qs[k]);  // learn the modes
  long hit_allocs = 0, hits = 0;
  for (int k = period; k < 3 * period; ++k) {
    const long h0 = warm.stats().warm_hits;
    g_allocs = 0;
    g_counting = true;
    const LcpSolution& s = warm.solve(qs[k]);
    g_counting = false;
    const long allocs = g_allocs;
    ASSERT_EQ(s.status, LcpStatus::Solved);
    if (warm.stats().warm_hits > h0) {
      ++hits;
      hit_allocs += allocs;
    }
  }
  EXPECT_GT(hits, period);
  EXPECT_EQ(hit_allocs, 0);
  // Sanity check of the counter itself.
  g_allocs = 0;
  g_counting = true;
  Eigen::VectorXd tmp = Eigen::VectorXd::Ones(100);
  g_counting = false;
  EXPECT_GE(g_allocs.load(), 1);
  EXPECT_EQ(tmp.sum(), 100.0);
}
#endif

}  // namespace
}  // namespace lcs

namespace lcs {
namespace {

// A continuum of solutions, as when no conducting diode ties down the potential of a
// sub-circuit: w0 = -z1 + 0, w1 = z0 - c. Every z0 >= c with z1 = 0 solves it, so the support
// {z0} has the singular block M_00 = 0; Lemke's vertex z0 = c sits on the basis {z0, z1} with
// z1 basic at zero level. The warm solver must keep that basis: one Lemke call, then warm hits.
TEST(LcpWarmSolverDegenerate, KeepsLemkesBasisAtAZeroLevelVariable) {
  Eigen::MatrixXd M(2, 2);
  M << 0, -1, 1, 0;
  LcpWarmSolver solver(M);
  for (int k = 0; k < 200; ++k) {
    const double c = 1.0 + 0.01 * k;
    Eigen::VectorXd q(2);
    q << 0, -c;
    const LcpSolution& sol = solver.solve(q);
    ASSERT_EQ(sol.status, LcpStatus::Solved);
    EXPECT_LE(lcp_residual(M, q, sol.z), 1e-12);
    EXPECT_NEAR(sol.z(0), c, 1e-12);  // the vertex, continuous from step to step
  }
  EXPECT_EQ(solver.stats().lemke_calls, 1);
  EXPECT_EQ(solver.stats().warm_hits, 199);
}

}  // namespace
}  // namespace lcs
