#include "solver/integrators/descriptor_start.h"

#include <algorithm>
#include <cmath>

#include "solver/lcp/sparse_active_set.h"

namespace lcs {

namespace {

// The mode with the pairs at z = w = 0 held on counts as regular above this reciprocal condition
// number (rows scaled to unit size; a floating node's diode makes it singular, 0).
constexpr double kRegularMode = 1e-13;

// A singular held mode's free directions at most this many (a floating node per direction), found
// from the solution's own mode at most this many pairs away (the pairs at z = w = 0).
constexpr int kMaxFreeDirections = 16;
constexpr int kMaxDegenerate = 64;

// True when every direction in which the instant's solution is not determined (the null space of
// the held mode's matrix) leaves what a step reads of y unchanged: the storage rows' explicit part
// Sy y (θ < 1; the states themselves are fixed at the instant). Then the solution found is as good
// as any other, the dense start's included (its tiny-step LCP has the same free directions: no
// storage meets them), and only unknowns no step reads — the potential of a node reached through
// off diodes alone, such a diode's margin z — are left at the value found.
bool free_directions_unread(SparseActiveSetLcp& lcp, const std::vector<char>& held, const std::vector<char>& found,
                            const SparseDescriptor& d) {
  Eigen::MatrixXd basis;
  if (!lcp.mode_null_space(held, found, kMaxDegenerate, kMaxFreeDirections, basis)) return false;
  const int ny = d.unknowns();
  double sy_largest = 0;
  for (int c = 0; c < d.Sy.outerSize(); ++c)
    for (SparseActiveSetLcp::Sparse::InnerIterator it(d.Sy, c); it; ++it) sy_largest = std::max(sy_largest, std::abs(it.value()));
  for (int k = 0; k < basis.cols(); ++k) {  // unit columns: rounding leaves ~1e-16 on the others
    const Eigen::VectorXd dy = basis.col(k).head(ny);
    const Eigen::VectorXd moved = d.Sy * dy;
    if (moved.size() > 0 && moved.cwiseAbs().maxCoeff() > 1e-9 * sy_largest) return false;
  }
  return true;
}

}  // namespace

bool descriptor_start_z(const LcsProblem& model, const SparseDescriptor& d, double t0,
                        const Eigen::VectorXd& x, StepperStats& stats, Eigen::VectorXd& z) {
  using Sparse = SparseActiveSetLcp::Sparse;
  const int ny = d.unknowns(), m = static_cast<int>(d.P.rows());
  // Rows scaled to unit size, as the step's (descriptor_step.cpp): no solution changes.
  Eigen::VectorXd scale = Eigen::VectorXd::Zero(ny);
  for (const Sparse* S : {&d.Kst, &d.Lz})
    for (int c = 0; c < S->outerSize(); ++c)
      for (Sparse::InnerIterator it(*S, c); it; ++it)
        scale(it.row()) = std::max(scale(it.row()), std::abs(it.value()));
  for (int r = 0; r < ny; ++r) scale(r) = scale(r) > 0 ? 1.0 / scale(r) : 1.0;
  const Sparse K = scale.asDiagonal() * d.Kst, L = scale.asDiagonal() * d.Lz;
  SparseActiveSetLcp lcp(K, L, d.P, Sparse(m, m));
  if (z.size() == m) lcp.prefer(z);
  const Eigen::VectorXd u = model.input_values(t0);
  Eigen::VectorXd a = d.Xst * x + d.Uin * u;
  a = a.cwiseProduct(scale);
  const Eigen::VectorXd b = d.Fw * u;
  Eigen::VectorXd y, zs, w;
  const bool solved = lcp.solve(a, b, y, zs, w);
  SparseActiveSetStats own = lcp.stats();
  own.cache_bytes = 0;  // freed on return: only the steppers' caches stay
  stats.sparse += own;
  ++stats.factorisations;
  if (!solved) return false;
  // Strict complementarity, relative to the sizes that meet in z and in each w_i; the pairs
  // at z = w = 0 are held on together with the conducting ones for the regularity test.
  const double z_size = m > 0 ? zs.cwiseAbs().maxCoeff() : 0.0;
  const Eigen::VectorXd w_terms = (d.P.cwiseAbs() * y.cwiseAbs()) + (d.Fw.cwiseAbs() * u.cwiseAbs());
  std::vector<char> held(m, 0), conducting(m, 0);
  bool strict = true;
  for (int i = 0; i < m; ++i) {
    const bool on = zs(i) > 1e-9 * z_size, off = w(i) > 1e-9 * w_terms(i);
    held[i] = on || !off;
    conducting[i] = on;
    strict = strict && (on || off);
  }
  if (!strict && !(lcp.mode_reciprocal_condition(held) > kRegularMode) &&
      !free_directions_unread(lcp, held, conducting, d))
    return false;
  z = zs;
  return true;
}

}  // namespace lcs
