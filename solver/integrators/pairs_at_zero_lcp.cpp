#include "solver/integrators/pairs_at_zero_lcp.h"

#include <algorithm>

#include "solver/lcp/lcp.h"

namespace lcs {

std::vector<int> undetermined_held_pairs(const Eigen::MatrixXd& M, const std::vector<bool>& active,
                                         const std::vector<int>& at_zero) {
  const int m = static_cast<int>(active.size());
  std::vector<char> open(m, 0);
  for (int i : at_zero) open[i] = 1;
  std::vector<int> on;
  for (int i = 0; i < m; ++i)
    if (active[i] && !open[i]) on.push_back(i);
  const int a = static_cast<int>(on.size());
  std::vector<int> out;
  if (a == 0) return out;
  Eigen::MatrixXd Maa(a, a);
  for (int r = 0; r < a; ++r)
    for (int c = 0; c < a; ++c) Maa(r, c) = M(on[r], on[c]);
  if (Eigen::FullPivLU<Eigen::MatrixXd>(Maa).isInvertible()) return out;
  std::vector<int> kept;
  for (int r = 0; r < a; ++r) {
    kept.push_back(r);
    Eigen::MatrixXd S(kept.size(), kept.size());
    for (size_t i = 0; i < kept.size(); ++i)
      for (size_t j = 0; j < kept.size(); ++j) S(i, j) = Maa(kept[i], kept[j]);
    if (!Eigen::FullPivLU<Eigen::MatrixXd>(S).isInvertible()) {
      kept.pop_back();
      out.push_back(on[r]);
    }
  }
  return out;
}

std::optional<std::vector<bool>> pairs_at_zero_lcp(const Eigen::MatrixXd& M, const Eigen::VectorXd& q,
                                                   const std::vector<bool>& active,
                                                   const std::vector<int>& at_zero,
                                                   const Eigen::VectorXd* derivatives) {
  const int m = static_cast<int>(q.size());
  std::vector<char> open(m, 0);
  for (int i : at_zero) open[i] = 1;
  std::vector<int> on;  // α: held on
  for (int i = 0; i < m; ++i)
    if (active[i] && !open[i]) on.push_back(i);
  const int k = static_cast<int>(at_zero.size()), a = static_cast<int>(on.size());
  if (k == 0) return active;
  Eigen::MatrixXd MII(k, k), MIa(k, a), MaI(a, k), Maa(a, a);
  Eigen::VectorXd qI(k), qa(a);
  for (int r = 0; r < k; ++r) {
    qI(r) = q(at_zero[r]);
    for (int c = 0; c < k; ++c) MII(r, c) = M(at_zero[r], at_zero[c]);
    for (int c = 0; c < a; ++c) MIa(r, c) = M(at_zero[r], on[c]);
  }
  for (int r = 0; r < a; ++r) {
    qa(r) = q(on[r]);
    for (int c = 0; c < k; ++c) MaI(r, c) = M(on[r], at_zero[c]);
    for (int c = 0; c < a; ++c) Maa(r, c) = M(on[r], on[c]);
  }
  Eigen::MatrixXd Mr = MII;
  Eigen::VectorXd qr = qI;
  if (a > 0) {
    Eigen::FullPivLU<Eigen::MatrixXd> lu(Maa);
    if (!lu.isInvertible()) return std::nullopt;
    Mr -= MIa * lu.solve(MaI);
    qr -= MIa * lu.solve(qa);
  }
  if (derivatives) qr = *derivatives;
  const LcpSolution sol = solve_lemke(Mr, qr);
  if (sol.status != LcpStatus::Solved && sol.status != LcpStatus::NumericalFailure) return std::nullopt;
  std::vector<bool> result = active;
  for (int r = 0; r < k; ++r) result[at_zero[r]] = sol.z(r) > 0;
  for (int r : sol.basic_z) result[at_zero[r]] = true;
  return result;
}

}  // namespace lcs
