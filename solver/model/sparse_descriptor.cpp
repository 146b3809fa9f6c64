#include "solver/model/sparse_descriptor.h"

#include <cmath>

#include "solver/model/sparse_lcs.h"

namespace lcs {

namespace {

using Triplets = std::vector<Eigen::Triplet<double>>;

// The entries that are not exactly zero: what the dense matrix would hold.
long exact_nonzeros(const Eigen::SparseMatrix<double>& M) {
  long count = 0;
  for (int c = 0; c < M.outerSize(); ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(M, c); it; ++it) count += it.value() != 0;
  return count;
}

// Rows over y = [e | i]: a branch voltage is e(n+) - e(n-), ground (node 0) has no unknown.
struct RowWriter {
  const CircuitGraph& g;
  int nodes;
  void voltage(Triplets& t, int row, int b, double coeff) const {
    if (coeff == 0) return;
    const Branch& br = g.branches[b];
    if (br.from != 0) t.emplace_back(row, br.from - 1, coeff);
    if (br.to != 0) t.emplace_back(row, br.to - 1, -coeff);
  }
  void current(Triplets& t, int row, int b, double coeff) const {
    if (coeff != 0) t.emplace_back(row, nodes + b, coeff);
  }
};

Eigen::SparseMatrix<double> sparse(int rows, int cols, const Triplets& t) {
  Eigen::SparseMatrix<double> s(rows, cols);
  s.setFromTriplets(t.begin(), t.end());
  s.prune(0.0);
  return s;
}

}  // namespace

long lcs_nonzeros(const SparseLcs& lcs) {
  return exact_nonzeros(lcs.A) + exact_nonzeros(lcs.B) + exact_nonzeros(lcs.C) + exact_nonzeros(lcs.D);
}

// The rule. Per step that keeps its mode (most steps), the dense path costs about (n + m)^2
// multiply-adds (q = C Phi x, x+ = Phi x + W^-1 B z: dense n x n and n x m products) and the
// descriptor about 2 nnz(LU) + nnz(P), where nnz(LU) grows like its unknowns (nodes + branches
// + m) for circuits whose graph is a chain or a ladder; a mode change costs the dense path Lemke
// pivots of O(m^2) each and the descriptor a low-rank update (O(k) triangular solves, k the
// pairs changed) or a sparse refactorisation. So the descriptor is formed where the dense path
// would be taken for a large circuit:
//   - the circuit has at least kSparsePairs pairs, and
//   - the LCS is dense (sparse_lcs_if_worth declined it: nonzeros of A, B, C, D above
//     kSparseDensity (n + m)^2), and
//   - the descriptor holds fewer nonzeros than the dense LCS.
// The θ-method steps on it from kDescriptorPairs pairs on (sparse_descriptor.h: the measured
// crossover; the descriptor's constant is larger).
std::unique_ptr<SparseDescriptor> sparse_descriptor_if_worth(
    const CircuitGraph& g, const Stamps& stamps,
    const std::vector<StateInfo>& states, const std::vector<PairInfo>& pairs, int inputs, long lcs_nonzeros,
    bool shift_free, bool has_history) {
  const int n = static_cast<int>(states.size()), m = static_cast<int>(pairs.size()), nu = inputs;
  if (m < kSparsePairs || has_history) return nullptr;
  for (const PairInfo& p : pairs)
    if (p.transfer) return nullptr;
  if (!shift_free) return nullptr;
  const int nb = static_cast<int>(g.branches.size());
  std::vector<int> state_of(nb, -1);
  for (int j = 0; j < n; ++j) {
    if (!states[j].windings.empty()) return nullptr;  // perfect coupling: magnetising states
    state_of[states[j].branch] = j;
  }
  std::vector<const Stamps::Storage*> storage(nb, nullptr);
  for (const Stamps::Storage& s : stamps.storage) {
    storage[s.branch] = &s;
    if (state_of[s.branch] < 0) return nullptr;  // a dependent capacitor or inductor
  }
  if (lcs_nonzeros <= kSparseDensity * static_cast<double>(n + m) * static_cast<double>(n + m))
    return nullptr;  // sparse enough for the sparse LCS step (sparse_lcs.h)

  auto d = std::make_unique<SparseDescriptor>();
  d->nodes = static_cast<int>(g.nodes.size()) - 1;
  d->branches = nb;
  const int ny = d->unknowns();
  const RowWriter w{g, d->nodes};
  auto branch_row = [&](int b) { return d->nodes + b; };
  Triplets k0, k1, lz, sx, sy, x, p, kst, xst;
  d->Uin = Eigen::MatrixXd::Zero(ny, nu);
  d->Fw = Eigen::MatrixXd::Zero(m, nu);

  // KCL at every node but ground: the currents leaving it.
  for (int b = 0; b < nb; ++b) {
    const Branch& br = g.branches[b];
    if (br.from != 0) k0.emplace_back(br.from - 1, d->nodes + b, 1.0);
    if (br.to != 0) k0.emplace_back(br.to - 1, d->nodes + b, -1.0);
  }
  // Pairs: the swap of 5.4.4, as formation writes it.
  std::vector<bool> done(nb, false);
  for (int k = 0; k < m; ++k) {
    const PairInfo& pr = pairs[k];
    const int b = pr.branch, r = branch_row(b);
    const double ron = pr.law.ron, von = pr.law.von;
    done[b] = true;
    if (pr.voltage_type) {  // v - RON i + z = VON;  w = i
      w.voltage(k0, r, b, 1.0);
      w.current(k0, r, b, -ron);
      lz.emplace_back(r, k, 1.0);
      d->Uin(r, 0) += von;
      w.current(p, k, b, 1.0);
    } else {                // i - z = 0;  w = VON + RON i - v
      w.current(k0, r, b, 1.0);
      lz.emplace_back(r, k, -1.0);
      w.current(p, k, b, ron);
      w.voltage(p, k, b, -1.0);
      d->Fw(k, 0) += von;
    }
  }
  for (const Stamps::Relation& rel : stamps.relations) {
    if (done[rel.branch]) continue;  // a pair's law stands for it (as in formation)
    const int r = branch_row(rel.branch);
    done[rel.branch] = true;
    for (const Term& term : rel.terms) {
      switch (term.of) {
        case Term::Of::Voltage: w.voltage(k0, r, term.index, term.coeff); break;
        case Term::Of::Current: w.current(k0, r, term.index, term.coeff); break;
        case Term::Of::Input: d->Uin(r, term.index) -= term.coeff; break;
      }
    }
  }
  // Storage. Inductances with their mutual terms M = k sqrt(La Lb).
  std::vector<Triplets> lf(nb);
  for (const Stamps::Coupling& c : stamps.couplings) {
    const double mutual = c.k * std::sqrt(storage[c.branch_a]->value * storage[c.branch_b]->value);
    lf[c.branch_a].emplace_back(c.branch_a, c.branch_b, mutual);
    lf[c.branch_b].emplace_back(c.branch_b, c.branch_a, mutual);
  }
  for (int b = 0; b < nb; ++b) {
    if (!storage[b]) continue;
    if (done[b]) return nullptr;  // storage with a relation: not a plain capacitor or inductor
    done[b] = true;
    const int r = branch_row(b), j = state_of[b];
    const double value = storage[b]->value;
    if (states[j].capacitor) {  // C v - hθ i;  x_j = v
      w.voltage(k0, r, b, value);
      w.current(k1, r, b, -1.0);
      sx.emplace_back(r, j, value);
      w.current(sy, r, b, 1.0);
      w.voltage(x, j, b, 1.0);
      w.voltage(kst, r, b, 1.0);
    } else {                    // Lf i - hθ v;  x_j = i
      w.current(k0, r, b, value);
      sx.emplace_back(r, j, value);
      for (const Eigen::Triplet<double>& e : lf[b]) {
        w.current(k0, r, e.col(), e.value());
        if (state_of[e.col()] < 0) return nullptr;
        sx.emplace_back(r, state_of[e.col()], e.value());
      }
      w.voltage(k1, r, b, -1.0);
      w.voltage(sy, r, b, 1.0);
      w.current(x, j, b, 1.0);
      w.current(kst, r, b, 1.0);
    }
    xst.emplace_back(r, j, 1.0);
  }
  for (int b = 0; b < nb; ++b)
    if (!done[b]) return nullptr;  // a branch without a law: formation would have refused it
  d->K0 = sparse(ny, ny, k0);
  d->K1 = sparse(ny, ny, k1);
  d->Lz = sparse(ny, m, lz);
  d->Sx = sparse(ny, n, sx);
  d->Sy = sparse(ny, ny, sy);
  d->X = sparse(n, ny, x);
  d->P = sparse(m, ny, p);
  // Kst: K0's KCL, relation and pair rows; the storage rows say v_b = x_j or i_b = x_j.
  for (int c = 0; c < d->K0.outerSize(); ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(d->K0, c); it; ++it) {
      const int row = static_cast<int>(it.row());
      if (row >= d->nodes && storage[row - d->nodes]) continue;
      kst.emplace_back(row, c, it.value());
    }
  d->Kst = sparse(ny, ny, kst);
  d->Xst = sparse(ny, n, xst);
  if (d->nonzeros() >= lcs_nonzeros) return nullptr;
  return d;
}

}  // namespace lcs
