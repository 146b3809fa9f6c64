#include "solver/model/lcs_index.h"

#include <Eigen/SVD>

namespace lcs {

LcsIndex lcs_index(const Lcs& s) {
  LcsIndex r;
  const int m = s.pairs(), n = s.states();
  r.pair_index.assign(m, -1);
  if (m == 0) {
    r.index = 0;
    return r;
  }
  // G_0 = D, G_k = C A^(k-1) B, generated one at a time and only as far as needed: the
  // index and every pair's index are found within the first few (k <= 2 for the circuits
  // here); all n + 2 of them cost O(n^3 m) and made `analyze` take minutes at 1000 states.
  const double a_norm = s.A.size() > 0 ? s.A.cwiseAbs().rowwise().sum().maxCoeff() : 0.0;
  const double big_s = 1e4 * std::max(1.0, a_norm);
  Eigen::MatrixXd G = s.D, AkB = s.B;
  Eigen::MatrixXd sum = Eigen::MatrixXd::Zero(m, m);
  double power = 1.0;
  int unresolved = m;
  for (int k = 0; k <= n + 1; ++k) {
    if (k > 0) {
      G = s.C * AkB;
      AkB = s.A * AkB;
    }
    if (k < 3) r.markov.push_back(G);
    const double scale = G.size() > 0 ? G.cwiseAbs().maxCoeff() : 0.0;
    for (int i = 0; i < m; ++i)
      if (r.pair_index[i] < 0 && scale > 0 && std::abs(G(i, i)) > 1e-12 * scale) {
        r.pair_index[i] = k;
        --unresolved;
      }
    if (r.index < 0) {
      sum += G * power;
      power /= big_s;
      Eigen::JacobiSVD<Eigen::MatrixXd> svd(sum);
      const auto& sv = svd.singularValues();
      if (sv(0) > 0 && sv(m - 1) > 1e-10 * sv(0)) r.index = k;
    }
    if (r.index >= 0 && unresolved == 0 && k >= 2) break;
  }
  return r;
}

}  // namespace lcs
