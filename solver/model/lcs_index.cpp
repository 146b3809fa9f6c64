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
  std::vector<Eigen::MatrixXd> G{s.D};
  Eigen::MatrixXd AkB = s.B;
  for (int k = 1; k <= n + 1; ++k) {
    G.push_back(s.C * AkB);
    AkB = s.A * AkB;
  }
  for (int k = 0; k < 3 && k < static_cast<int>(G.size()); ++k) r.markov.push_back(G[k]);

  for (int i = 0; i < m; ++i)
    for (int k = 0; k < static_cast<int>(G.size()) && r.pair_index[i] < 0; ++k) {
      const double scale = G[k].cwiseAbs().maxCoeff();
      if (scale > 0 && std::abs(G[k](i, i)) > 1e-12 * scale) r.pair_index[i] = k;
    }

  const double a_norm = s.A.size() > 0 ? s.A.cwiseAbs().rowwise().sum().maxCoeff() : 0.0;
  const double big_s = 1e4 * std::max(1.0, a_norm);
  Eigen::MatrixXd sum = Eigen::MatrixXd::Zero(m, m);
  double power = 1.0;
  for (int k = 0; k < static_cast<int>(G.size()); ++k) {
    sum += G[k] * power;
    power /= big_s;
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(sum);
    const auto& sv = svd.singularValues();
    if (sv(0) > 0 && sv(m - 1) > 1e-10 * sv(0)) {
      r.index = k;
      break;
    }
  }
  return r;
}

}  // namespace lcs
