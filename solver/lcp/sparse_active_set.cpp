#include "solver/lcp/sparse_active_set.h"

#include <algorithm>
#include <cmath>
#include <list>
#include <string>
#include <unordered_map>

#include <klu.h>

#include "solver/lcp/lcp_internal.h"

namespace lcs {

namespace {
constexpr double kFeasTol = 1e-10;  // relative, as the dense solvers' feas_tol
constexpr int kPatience = 3;        // block flips allowed without the violating set shrinking
// A stalled block search first trims the mode: off go the pairs whose z is below kTrimLevel of
// the largest, at most kTrims times a solve (then Murty's single flips, finite as before).
// A multiplier's charging front: the block flip turns on every diode of a chain whose current
// is then tiny (1e-12 .. 1e-6 of the largest) and negative at the chain's far end, and single
// flips walked that end back one diode a solve (479 solves at one step of 500 stages).
constexpr double kTrimLevel = 1e-6;
constexpr int kTrims = 3;
// Trimmed pairs whose w turns negative go back on a span of their pre-trim currents at a time:
// those within this factor of the largest (see solve()).
constexpr double kUntrimSpan = 1e-3;
}  // namespace

// KLU (SuiteSparse; Davis and Palamadai Natarajan 2010), the sparse LU of circuit simulators.
// Every mode's matrix has pattern_'s pattern, so one symbolic analysis (block triangular form,
// AMD ordering) serves them all and a mode costs one numeric factorisation. Measured on the
// 1000-diode ladder's and rectifier bank's mode matrices: its triangular solves 1.5-2.4x faster
// than Eigen's supernodal SparseLU (whose supernodes are a column or two here), a factorisation
// 3-5x faster.
struct SparseActiveSetLcp::Symbolic {
  klu_common common;
  klu_symbolic* symbolic = nullptr;
  explicit Symbolic(Sparse& pattern) {
    klu_defaults(&common);
    symbolic = klu_analyze(static_cast<int>(pattern.rows()), pattern.outerIndexPtr(),
                           pattern.innerIndexPtr(), &common);
  }
  ~Symbolic() { klu_free_symbolic(&symbolic, &common); }
  Symbolic(const Symbolic&) = delete;
  Symbolic& operator=(const Symbolic&) = delete;
};

struct SparseActiveSetLcp::Factorisation {
  Symbolic* symbolic = nullptr;
  klu_numeric* numeric = nullptr;  // null: singular (the mode is not usable)
  bool usable = false;
  std::size_t bytes = 0;
  ~Factorisation() {
    if (numeric) klu_free_numeric(&numeric, &symbolic->common);
  }
};

struct SparseActiveSetLcp::Base {
  std::vector<char> mode;
  std::unique_ptr<Factorisation> f;
  std::unordered_map<int, Eigen::VectorXd> column;  // pair i -> M_0^-1 e_(n+i)
  // M_0^-1 r_0, r_0 the base mode's right-hand side for the data of solve() call `solution_of`
  // (-1: none yet). The modes a search tries differ from the base in a few pair rows, and so do
  // their right-hand sides: M_0^-1 r = s_0 + sum_i (r - r_0)_(n+i) M_0^-1 e_(n+i), the columns the
  // update has anyway, so a search solves with the base's factors once, not once per round.
  Eigen::VectorXd s0;
  long solution_of = -1;
};

struct SparseActiveSetLcp::Cache {
  struct Entry {
    std::unique_ptr<Factorisation> f;
    std::list<std::string>::iterator age;
  };
  std::unordered_map<std::string, Entry> entries;
  std::list<std::string> ages;  // most recently used first
};

SparseActiveSetLcp::SparseActiveSetLcp(const Sparse& K, const Sparse& L, const Sparse& P,
                                       const Sparse& Q, std::size_t cache_budget_bytes)
    : n_(static_cast<int>(K.rows())), m_(static_cast<int>(Q.rows())), budget_(cache_budget_bytes),
      cache_(std::make_unique<Cache>()) {
  const int size = n_ + m_;
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(K.nonZeros() + L.nonZeros() + P.nonZeros() + Q.nonZeros() + m_);
  auto add = [&](const Sparse& S, int r0, int c0) {
    for (int k = 0; k < S.outerSize(); ++k)
      for (Sparse::InnerIterator it(S, k); it; ++it)
        t.emplace_back(r0 + it.row(), c0 + it.col(), it.value());
  };
  add(K, 0, 0);
  add(L, 0, n_);
  add(P, n_, 0);
  add(Q, n_, n_);
  for (int i = 0; i < m_; ++i) t.emplace_back(n_ + i, n_ + i, 0.0);  // the unit rows' slot
  pattern_.resize(size, size);
  pattern_.setFromTriplets(t.begin(), t.end());
  pattern_.makeCompressed();
  pair_entries_.assign(m_, {});
  diagonal_slot_.assign(m_, -1);
  const double* base = pattern_.valuePtr();
  for (int c = 0; c < size; ++c)
    for (Sparse::InnerIterator it(pattern_, c); it; ++it) {
      if (it.row() < n_) continue;
      const int i = static_cast<int>(it.row()) - n_;
      const int slot = static_cast<int>(&it.valueRef() - base);
      pair_entries_[i].push_back({c, slot});
      if (c == n_ + i) diagonal_slot_[i] = slot;
    }
  Eigen::SparseMatrix<double, Eigen::RowMajor> pq(m_, size);
  std::vector<Eigen::Triplet<double>> tp;
  for (int k = 0; k < P.outerSize(); ++k)
    for (Sparse::InnerIterator it(P, k); it; ++it) tp.emplace_back(it.row(), it.col(), it.value());
  for (int k = 0; k < Q.outerSize(); ++k)
    for (Sparse::InnerIterator it(Q, k); it; ++it) tp.emplace_back(it.row(), n_ + it.col(), it.value());
  pq.setFromTriplets(tp.begin(), tp.end());
  PQ_ = std::move(pq);
  top_ = pattern_.topRows(n_);
  symbolic_ = std::make_unique<Symbolic>(pattern_);
  mode_.assign(m_, 0);
  rhs_.resize(size);
  sol_.resize(size);
}

SparseActiveSetLcp::~SparseActiveSetLcp() = default;

void SparseActiveSetLcp::prefer(const Eigen::VectorXd& z) {
  if (z.size() != m_) return;
  for (int i = 0; i < m_; ++i) mode_[i] = z(i) > 0.0;
}

// Rows of pairs outside the mode are unit rows (z_i = 0), kept in the common pattern.
SparseActiveSetLcp::Sparse SparseActiveSetLcp::mode_matrix(const std::vector<char>& mode) const {
  Sparse M = pattern_;
  double* values = M.valuePtr();
  for (int i = 0; i < m_; ++i) {
    if (mode[i]) continue;
    for (const auto& [column, slot] : pair_entries_[i]) values[slot] = 0.0;
    values[diagonal_slot_[i]] = 1.0;
  }
  return M;
}

std::unique_ptr<SparseActiveSetLcp::Factorisation> SparseActiveSetLcp::factorise(const std::vector<char>& mode) {
  Sparse M = mode_matrix(mode);
  auto f = std::make_unique<Factorisation>();
  f->symbolic = symbolic_.get();
  if (symbolic_->symbolic)
    f->numeric = klu_factor(M.outerIndexPtr(), M.innerIndexPtr(), M.valuePtr(), symbolic_->symbolic,
                            &symbolic_->common);
  f->usable = f->numeric != nullptr;
  ++stats_.factorisations;
  return f;
}

double SparseActiveSetLcp::mode_reciprocal_condition(const std::vector<char>& on) {
  const std::unique_ptr<Factorisation> f = factorise(on);
  if (!f->usable) return 0.0;
  Sparse M = mode_matrix(on);  // klu_condest reads the matrix's values as well as its factors
  if (!klu_condest(M.outerIndexPtr(), M.valuePtr(), symbolic_->symbolic, f->numeric, &symbolic_->common))
    return 0.0;
  const double condest = symbolic_->common.condest;
  return condest > 0 && std::isfinite(condest) ? 1.0 / condest : 0.0;
}

bool SparseActiveSetLcp::mode_null_space(const std::vector<char>& on, const std::vector<char>& regular,
                                         int max_changed, int max_dimension, Eigen::MatrixXd& basis) {
  std::vector<int> changed;
  for (int i = 0; i < m_; ++i)
    if (on[i] != regular[i]) changed.push_back(i);
  const int k = static_cast<int>(changed.size());
  if (k > max_changed) return false;
  const std::unique_ptr<Factorisation> f = factorise(regular);
  if (!f->usable) return false;
  const int size = n_ + m_;
  Eigen::MatrixXd G(size, k);  // M_reg^-1 E_S
  for (int a = 0; a < k; ++a) {
    Eigen::VectorXd column = Eigen::VectorXd::Unit(size, n_ + changed[a]);
    if (!lu_solve(*f, column)) return false;
    G.col(a) = column;
  }
  Eigen::MatrixXd small = Eigen::MatrixXd::Identity(k, k);  // I + D_S G_S
  for (int b = 0; b < k; ++b) {
    const Eigen::VectorXd g = G.col(b);
    for (int a = 0; a < k; ++a) {
      const int i = changed[a];
      small(a, b) += pair_row_dot(i, on[i], g) - pair_row_dot(i, regular[i], g);
    }
  }
  basis.resize(size, 0);
  if (k == 0) return true;
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(small, Eigen::ComputeFullV);
  const Eigen::VectorXd& sigma = svd.singularValues();  // decreasing
  int nullity = 0;
  for (int j = 0; j < k; ++j)
    if (!(sigma(j) > 1e-10 * sigma(0))) ++nullity;
  if (nullity > max_dimension) return false;
  if (nullity == 0) return true;
  const Eigen::MatrixXd V = -G * svd.matrixV().rightCols(nullity);
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(V);
  basis = qr.householderQ() * Eigen::MatrixXd::Identity(size, nullity);
  return true;
}

double SparseActiveSetLcp::pair_row_dot(int i, bool on, const Eigen::VectorXd& v) const {
  if (!on) return v(n_ + i);
  double sum = 0;
  for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(PQ_, i); it; ++it) sum += it.value() * v(it.col());
  return sum;
}

// x -= G_S (I + D_S G_S)^-1 D_S x, with `small` the factorised I + D_S G_S.
void SparseActiveSetLcp::apply_updated(const std::vector<int>& changed,
                                       const Eigen::PartialPivLU<Eigen::MatrixXd>& small, Eigen::VectorXd& x) {
  const int k = static_cast<int>(changed.size());
  const std::vector<char>& base = base_->mode;
  Eigen::VectorXd t(k);
  for (int a = 0; a < k; ++a) {
    const int i = changed[a];
    t(a) = pair_row_dot(i, !base[i], x) - pair_row_dot(i, base[i], x);
  }
  const Eigen::VectorXd c = small.solve(t);
  for (int b = 0; b < k; ++b) x -= c(b) * base_->column.at(changed[b]);
}

// M_J x = r by a low-rank update of the base's factors; a mode too far from the base (or no usable
// base) is factorised and becomes the base. r is mode's right-hand side for the current solve()'s
// data (b its pairs' constants). False when M_J is singular.
bool SparseActiveSetLcp::solve_updated(const std::vector<char>& mode, const Eigen::VectorXd& r,
                                       const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  std::vector<int> changed;
  updated_ = false;
  if (base_ && base_->f->usable)
    for (int i = 0; i < m_; ++i)
      if (mode[i] != base_->mode[i]) changed.push_back(i);
  if (!base_ || !base_->f->usable || static_cast<int>(changed.size()) > max_rank_) {
    base_ = std::make_unique<Base>();
    base_->mode = mode;
    base_->f = factorise(mode);
    changed.clear();
  }
  if (!base_->f->usable) return false;
  if (base_->column.size() > static_cast<std::size_t>(4 * max_rank_ + 16)) base_->column.clear();
  // The base's right-hand side r_0 differs from r in the changed pairs' rows only.
  const std::vector<char>& base_mode = base_->mode;
  auto base_rhs_row = [&](int i) { return base_mode[i] ? -b(i) : 0.0; };
  // s_0 and the columns not yet solved, in one multi-right-hand-side solve: KLU traverses L and
  // U once for up to four of them (memory-bound here, so each costs less than alone).
  std::vector<int> missing;
  for (int j : changed)
    if (!base_->column.count(j)) missing.push_back(j);
  const bool need_s0 = base_->solution_of != solve_count_;
  if (need_s0 || !missing.empty()) {
    const int first = need_s0 ? 1 : 0;
    Eigen::MatrixXd block = Eigen::MatrixXd::Zero(n_ + m_, first + static_cast<Eigen::Index>(missing.size()));
    if (need_s0) {
      block.col(0) = r;
      for (int i : changed) block(n_ + i, 0) = base_rhs_row(i);
    }
    for (std::size_t c = 0; c < missing.size(); ++c) block(n_ + missing[c], first + c) = 1.0;
    if (!lu_solve_block(*base_->f, block)) return false;
    if (need_s0) {
      base_->s0 = block.col(0);
      base_->solution_of = solve_count_;
    }
    for (std::size_t c = 0; c < missing.size(); ++c) base_->column.emplace(missing[c], block.col(first + c));
  }
  x = base_->s0;
  for (int i : changed) {
    const double delta = r(n_ + i) - base_rhs_row(i);
    if (delta != 0.0) x += delta * base_->column.at(i);
  }
  if (changed.empty()) return true;
  ++stats_.updates;
  const int k = static_cast<int>(changed.size());
  Eigen::MatrixXd small = Eigen::MatrixXd::Identity(k, k);
  for (int a = 0; a < k; ++a) {
    const int i = changed[a];
    for (int c = 0; c < k; ++c) {
      const Eigen::VectorXd& g = base_->column.at(changed[c]);
      small(a, c) += pair_row_dot(i, !base_->mode[i], g) - pair_row_dot(i, base_->mode[i], g);
    }
  }
  small_lu_.compute(small);
  if (!(small_lu_.rcond() > 1e-12)) {  // M_J singular or nearly: its own factors decide
    Factorisation* f = factorisation(mode);
    if (!f->usable) return false;
    x = r;
    return lu_solve(*f, x);
  }
  apply_updated(changed, small_lu_, x);
  changed_ = std::move(changed);
  updated_ = true;
  return x.allFinite();
}

// One step of iterative refinement of the last solve_updated's x against M_J itself: the
// update's own rounding (measured ~5e-11 relative on a 500-stage multiplier) is enough to read
// signs, so the search refines only the solution it accepts (then ~1e-12, as a factorisation).
void SparseActiveSetLcp::refine_updated(const std::vector<char>& mode, const Eigen::VectorXd& r,
                                        Eigen::VectorXd& x) {
  Eigen::VectorXd residual = r;
  residual.head(n_).noalias() -= top_ * x;
  for (int i = 0; i < m_; ++i) residual(n_ + i) -= pair_row_dot(i, mode[i], x);
  Eigen::VectorXd dx = residual;
  if (!lu_solve(*base_->f, dx)) return;
  apply_updated(changed_, small_lu_, dx);
  x += dx;
}

bool SparseActiveSetLcp::lu_solve(const Factorisation& f, Eigen::VectorXd& x) const {
  return f.usable && klu_solve(symbolic_->symbolic, f.numeric, n_ + m_, 1, x.data(), &symbolic_->common) &&
         x.allFinite();
}

bool SparseActiveSetLcp::lu_solve_block(const Factorisation& f, Eigen::MatrixXd& x) const {
  return f.usable &&
         klu_solve(symbolic_->symbolic, f.numeric, n_ + m_, static_cast<int>(x.cols()), x.data(), &symbolic_->common) &&
         x.allFinite();
}

SparseActiveSetLcp::Factorisation* SparseActiveSetLcp::factorisation(const std::vector<char>& mode) {
  if (last_ && mode == last_mode_) return last_;  // the warm start: no key to build and hash
  Factorisation* f = cached_factorisation(mode);
  last_mode_ = mode;
  last_ = f;
  return f;
}

SparseActiveSetLcp::Factorisation* SparseActiveSetLcp::cached_factorisation(const std::vector<char>& mode) {
  const std::string key(mode.begin(), mode.end());
  Cache& c = *cache_;
  auto found = c.entries.find(key);
  if (found != c.entries.end()) {
    c.ages.splice(c.ages.begin(), c.ages, found->second.age);
    return found->second.f.get();
  }
  std::unique_ptr<Factorisation> f = factorise(mode);
  // L and U entries with their row indices, plus KLU's per-unknown pivots, scales and workspace.
  f->bytes = static_cast<std::size_t>(f->usable ? f->numeric->lnz + f->numeric->unz : 0) * 16 +
             static_cast<std::size_t>(n_ + m_) * 64 + key.size();
  while (!c.ages.empty() && stats_.cache_bytes + f->bytes > budget_) {
    auto oldest = c.entries.find(c.ages.back());
    stats_.cache_bytes -= oldest->second.f->bytes;
    c.entries.erase(oldest);
    c.ages.pop_back();
    ++stats_.evictions;
  }
  c.ages.push_front(key);
  stats_.cache_bytes += f->bytes;
  Factorisation* out = f.get();
  c.entries.emplace(key, Cache::Entry{std::move(f), c.ages.begin()});
  return out;
}

bool SparseActiveSetLcp::solve_mode(const std::vector<char>& mode, const Eigen::VectorXd& a,
                                    const Eigen::VectorXd& b, Eigen::VectorXd& y,
                                    Eigen::VectorXd& z, Eigen::VectorXd& w) {
  rhs_.head(n_) = a;
  for (int i = 0; i < m_; ++i) rhs_(n_ + i) = mode[i] ? -b(i) : 0.0;
  if (max_rank_ > 0) {
    if (!solve_updated(mode, rhs_, b, sol_)) return false;
  } else {
    Factorisation* f = factorisation(mode);
    sol_ = rhs_;
    if (!lu_solve(*f, sol_)) return false;
  }
  read_solution(mode, b, y, z, w);
  return true;
}

// y, z and w = [P Q] sol + b from sol_, with the z of pairs off in `mode` exactly zero.
void SparseActiveSetLcp::read_solution(const std::vector<char>& mode, const Eigen::VectorXd& b, Eigen::VectorXd& y,
                                       Eigen::VectorXd& z, Eigen::VectorXd& w) {
  for (int i = 0; i < m_; ++i)
    if (!mode[i]) sol_(n_ + i) = 0.0;
  y = sol_.head(n_);
  z = sol_.tail(m_);
  w.noalias() = PQ_ * sol_;
  w += b;
}

bool SparseActiveSetLcp::solve(const Eigen::VectorXd& a, const Eigen::VectorXd& b,
                               Eigen::VectorXd& y, Eigen::VectorXd& z, Eigen::VectorXd& w) {
  ++stats_.solves;
  ++solve_count_;
  std::vector<char> mode = mode_;
  std::vector<int> violating;
  std::vector<char> trimmed;  // pairs the last trim took off
  std::vector<double> trimmed_z;  // and the z each had then
  int best = m_ + 1, patience = kPatience, trims = 0;
  const int max_rounds = 4 * m_ + 50;
  for (int round = 0; round < max_rounds; ++round) {
    if (!solve_mode(mode, a, b, y, z, w)) break;
    // Tolerances relative to the sizes that meet in each quantity (rounding, not physics).
    const double z_scale = m_ > 0 ? z.cwiseAbs().maxCoeff() : 0.0;
    violating.clear();
    for (int i = 0; i < m_; ++i) {
      if (mode[i]) {
        if (!(z(i) >= -kFeasTol * z_scale)) violating.push_back(i);
      } else {
        double size = std::abs(b(i));
        for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(PQ_, i); it; ++it)
          size += std::abs(it.value() * sol_(it.col()));
        // A trimmed pair is on again at any w negative past rounding (lcp_detail::kRowRounding
        // of its sizes), not only past kFeasTol: its z may be positive below kFeasTol (measured:
        // complementarity 1e-11 of the sizes on 25-100 stage multipliers otherwise).
        const bool strict = trims > 0 && trimmed[i];
        if (!(w(i) >= -(strict ? lcp_detail::kRowRounding : kFeasTol) * size)) violating.push_back(i);
      }
    }
    if (violating.empty()) {
      if (updated_) {
        refine_updated(mode, rhs_, sol_);
        read_solution(mode, b, y, z, w);
      }
      if (round == 0) ++stats_.warm_hits;
      // A mode the update answered twice running (the warm start found it again) is likely to
      // stay: it becomes the base, factorised at the next solve, so the steps that keep it cost
      // one pair of triangular solves instead of the update's two, its k columns and residual.
      if (round == 0 && updated_) base_.reset();
      bool clamped = false;
      for (int i = 0; i < m_; ++i)
        if (z(i) < 0) { z(i) = 0; clamped = true; }
      if (clamped) {
        sol_.tail(m_) = z;
        w.noalias() = PQ_ * sol_;
        w += b;
      }
      mode_ = mode;  // zero-level z kept in the mode: the basis that worked (degenerate vertices)
      return true;
    }
    if (warm_only_) break;
    const int count = static_cast<int>(violating.size());
    if (count < best) {
      best = count;
      patience = kPatience;
    } else {
      --patience;
    }
    if (patience > 0) {
      // Trimmed pairs that want to be on again go on by decades of the current they carried
      // before the trim, largest first: a chain's currents decay geometrically along it, and
      // only its first few are needed (turning them on lifts the voltage of the rest).
      // (A pair trimmed at a z below zero, within kFeasTol, counts as zero: with no positive
      // z among them all go back on, as before the decades.)
      double untrim_above = 0.0;
      if (trims > 0)
        for (int i : violating)
          if (trimmed[i]) untrim_above = std::max(untrim_above, kUntrimSpan * trimmed_z[i]);
      int flipped = 0;
      for (int i : violating) {
        if (trims > 0 && trimmed[i]) {
          if (untrim_above > 0 && trimmed_z[i] < untrim_above) continue;
          trimmed[i] = 0;
        }
        mode[i] = !mode[i];
        ++flipped;
      }
      stats_.flips += flipped;
    } else if (trims < kTrims) {
      // The violating set stalls: flip it, and take off every pair whose z is a vanishing
      // fraction of the largest (see kTrimLevel).
      ++trims;
      trimmed.assign(m_, 0);
      trimmed_z.assign(m_, 0.0);
      for (int i : violating) mode[i] = !mode[i];
      stats_.flips += count;
      for (int i = 0; i < m_; ++i)
        if (mode[i] && z(i) >= -kFeasTol * z_scale && z(i) < kTrimLevel * z_scale &&
            !std::binary_search(violating.begin(), violating.end(), i)) {
          mode[i] = 0;
          trimmed[i] = 1;
          trimmed_z[i] = z(i);
          ++stats_.flips;
        }
      patience = kPatience;
    } else {
      mode[violating.back()] = !mode[violating.back()];  // Murty: the largest index
      if (trims > 0) trimmed[violating.back()] = 0;
      ++stats_.flips;
    }
  }
  ++stats_.failures;
  return false;
}

}  // namespace lcs
