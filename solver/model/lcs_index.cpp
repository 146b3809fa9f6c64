#include "solver/model/lcs_index.h"

#include <Eigen/SVD>

#include "solver/model/klu_factor.h"
#include "solver/model/dense_budget.h"
#include "solver/model/sparse_lcs.h"

namespace lcs {

namespace {

double max_abs(const Eigen::SparseMatrix<double>& S) {
  double out = 0;
  for (int k = 0; k < S.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(S, k); it; ++it) out = std::max(out, std::abs(it.value()));
  return out;
}

// Whether a sparse m x m matrix is nonsingular: KLU factorises it and a probe solve is accurate
// and not huge (the dense test's relative margin 1e-10 on the singular values, from below).
bool sparse_nonsingular(const Eigen::SparseMatrix<double>& S, int m) {
  const KluFactor lu(S);
  if (!lu.ok()) return false;
  const Eigen::VectorXd probe = Eigen::VectorXd::LinSpaced(m, 1.0, 2.0);
  const Eigen::VectorXd x = lu.solve(probe);
  const double d = max_abs(S);
  return x.allFinite() && (S * x - probe).cwiseAbs().maxCoeff() <= 1e-9 * 2 &&
         x.cwiseAbs().maxCoeff() * d <= 1e10 * 2;
}

// The index of a large sparse LCS as the dense test below finds it, on sparse matrices: the
// Markov parameters G_0 = D, G_k = C A^(k-1) B as sparse products (O(nnz) each for a circuit's
// few-entry rows, where the dense ones cost O(n^2 m)), their sum D + G_1/s + ... + G_k/s^k at a
// large s tested for singularity by a sparse LU instead of an SVD, and the pairs' indices from
// the diagonals. Only as far as needed: up to the first nonsingular sum and the last pair's
// index, at most G_8. False when that is not enough (the dense test decides).
bool sparse_index(const SparseLcs& s, int m, LcsIndex& r) {
  double a_norm = 0;
  {
    Eigen::VectorXd row_sum = Eigen::VectorXd::Zero(s.A.rows());
    for (int k = 0; k < s.A.outerSize(); ++k)
      for (Eigen::SparseMatrix<double>::InnerIterator it(s.A, k); it; ++it) row_sum(it.row()) += std::abs(it.value());
    if (row_sum.size() > 0) a_norm = row_sum.maxCoeff();
  }
  const double big_s = 1e4 * std::max(1.0, a_norm);
  Eigen::SparseMatrix<double> AkB = s.B, G = s.D, sum(m, m);
  double power = 1.0;
  int unresolved = m;
  for (int k = 0; k <= 8 && (r.index < 0 || unresolved > 0); ++k) {
    if (k > 0) {
      G = s.C * AkB;
      AkB = s.A * AkB;
    }
    const double scale = max_abs(G);
    for (int i = 0; i < m; ++i)
      if (r.pair_index[i] < 0 && scale > 0 && std::abs(G.coeff(i, i)) > 1e-12 * scale) {
        r.pair_index[i] = k;
        --unresolved;
      }
    if (r.index < 0) {
      sum += power * G;
      power /= big_s;
      if (sparse_nonsingular(sum, m)) r.index = k;
    }
  }
  return r.index >= 0;
}

}  // namespace

LcsIndex lcs_index(const LcsProblem& model) {
  const int m = model.pair_count();
  if (m > kPrintedMarkovPairs && model.sparse_lcs()) {
    LcsIndex r;
    r.pair_index.assign(m, -1);
    if (sparse_index(*model.sparse_lcs(), m, r)) return r;
  }
  if (!dense_within_budget(model.state_count(), m, 1, kAnalyzeDenseBytes)) {
    LcsIndex r;
    r.pair_index.assign(m, -1);
    r.not_computed = dense_budget_reason(model.state_count(), m, 1, kAnalyzeDenseBytes);
    return r;
  }
  return lcs_index(model.lcs());
}

LcsIndex lcs_index(const Lcs& s) {
  LcsIndex r;
  const int m = s.pairs(), n = s.states();
  r.pair_index.assign(m, -1);
  if (m == 0) {
    r.index = 0;
    return r;
  }
  if (m > kPrintedMarkovPairs) {
    const std::unique_ptr<SparseLcs> sparse = sparse_lcs_if_worth(s);
    if (sparse && sparse_index(*sparse, m, r)) return r;
    r.pair_index.assign(m, -1);
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
    if (k < 3 && m <= kPrintedMarkovPairs) r.markov.push_back(G);
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
    // Three are printed for small systems; a large one stops as soon as nothing is left to find
    // (a multiplier's 1000 pairs: G_1 and G_2 were two products of 1e9 multiply-adds each).
    if (r.index >= 0 && unresolved == 0 && (k >= 2 || m > kPrintedMarkovPairs)) break;
  }
  return r;
}

}  // namespace lcs
