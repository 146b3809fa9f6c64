// Micro-benchmarks: warm-hit time of LcpWarmSolver (n = 8) and cold Lemke (n = 8, 32, 128).
//   cmake --build build --target lcp_bench && build/solver/lcp_bench
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "solver/lcp/lcp.h"

namespace {

Eigen::MatrixXd p_matrix(std::mt19937& rng, int n) {
  std::normal_distribution<double> g;
  Eigen::MatrixXd A(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) A(i, j) = g(rng);
  for (int i = 0; i < n; ++i) {
    A(i, i) = 0;
    A(i, i) = A.row(i).cwiseAbs().sum() + 0.5;
  }
  return A;
}

// q with a planted solution: about half the indices active.
Eigen::VectorXd planted_q(std::mt19937& rng, const Eigen::MatrixXd& M) {
  std::uniform_real_distribution<double> u(0.1, 1.0);
  const int n = static_cast<int>(M.rows());
  Eigen::VectorXd z = Eigen::VectorXd::Zero(n), w = Eigen::VectorXd::Zero(n);
  for (int i = 0; i < n; ++i) (i % 2 ? z(i) : w(i)) = u(rng);
  return w - M * z;
}

void BM_WarmHit(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  std::mt19937 rng(1);
  Eigen::MatrixXd M = p_matrix(rng, n);
  Eigen::VectorXd q = planted_q(rng, M);
  // Tiny perturbations keep the active set: every call is a warm hit.
  std::vector<Eigen::VectorXd> qs;
  for (int k = 0; k < 64; ++k) qs.push_back(q * (1.0 + 1e-3 * (k % 7)));
  lcs::LcpWarmSolver warm(M);
  warm.solve(q);
  size_t k = 0;
  for (auto _ : state) {
    const lcs::LcpSolution& s = warm.solve(qs[k++ & 63]);
    benchmark::DoNotOptimize(s.z.data());
  }
  if (warm.stats().lemke_calls != 1) state.SkipWithError("not all warm hits");
  state.counters["warm_hits"] = static_cast<double>(warm.stats().warm_hits);
}
BENCHMARK(BM_WarmHit)->Arg(8)->Arg(16)->Arg(32);

void BM_Lemke(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  std::mt19937 rng(2);
  Eigen::MatrixXd M = p_matrix(rng, n);
  Eigen::VectorXd q = planted_q(rng, M);
  int pivots = 0;
  for (auto _ : state) {
    lcs::LcpSolution s = lcs::solve_lemke(M, q);
    pivots = s.pivots;
    benchmark::DoNotOptimize(s.z.data());
  }
  state.counters["pivots"] = pivots;
}
BENCHMARK(BM_Lemke)->Arg(8)->Arg(32)->Arg(128);

// Warm solver whose previous active set is wrong every time (alternating q): miss + Lemke.
void BM_WarmMiss(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  std::mt19937 rng(3);
  Eigen::MatrixXd M = p_matrix(rng, n);
  Eigen::VectorXd q1 = planted_q(rng, M), q2 = -q1;
  lcs::LcpWarmSolver warm(M);
  bool flip = false;
  for (auto _ : state) {
    const lcs::LcpSolution& s = warm.solve((flip = !flip) ? q1 : q2);
    benchmark::DoNotOptimize(s.z.data());
  }
  state.counters["lemke_fraction"] =
      static_cast<double>(warm.stats().lemke_calls) / static_cast<double>(warm.stats().solves);
}
BENCHMARK(BM_WarmMiss)->Arg(8)->Arg(32);

}  // namespace

BENCHMARK_MAIN();
