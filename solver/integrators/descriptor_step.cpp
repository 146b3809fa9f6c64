#include "solver/integrators/descriptor_step.h"

#include <Eigen/SparseLU>

namespace lcs {

namespace {
// Modes up to this many pairs from the factorised base are solved by a low-rank update
// (sparse_active_set.h). Measured on the 500-stage multiplier (1000 diodes, 1000 steps of 100 us,
// 11384 pairs flipped): a factorisation per mode 7.5 s; updates up to rank 16 / 32 / 64: 1.67 /
// 1.50 / 1.73 s (fewer factorisations against longer updates), the same answers to 1e-12.
// After the search's trim (sparse_active_set.h; one run each on the shared machine, before the
// warm-start rebase): a factorisation per mode 0.155 s but 93 MB of cached factors; rank 8 / 16
// / 32 / 64: 0.21 / 0.22 / 0.28 / 0.28 s. Kept at 32 (no cache) with the rebase: 0.20-0.29 s.
constexpr int kMaxRank = 32;
}  // namespace

struct DescriptorStep::Instant {
  Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> lu;
  bool usable = false;
};

DescriptorStep::DescriptorStep(const SparseDescriptor& d, double h, double theta)
    : d_(d), h_(h), theta_(theta) {
  using Sparse = SparseActiveSetLcp::Sparse;
  Sparse K = d.K0 + (h * theta) * d.K1;
  const int ny = d.unknowns();
  scale_ = Eigen::VectorXd::Zero(ny);
  for (int c = 0; c < K.outerSize(); ++c)
    for (Sparse::InnerIterator it(K, c); it; ++it) scale_(it.row()) = std::max(scale_(it.row()), std::abs(it.value()));
  for (int c = 0; c < d.Lz.outerSize(); ++c)
    for (Sparse::InnerIterator it(d.Lz, c); it; ++it) scale_(it.row()) = std::max(scale_(it.row()), std::abs(it.value()));
  for (int r = 0; r < ny; ++r) scale_(r) = scale_(r) > 0 ? 1.0 / scale_(r) : 1.0;
  const Sparse Ks = scale_.asDiagonal() * K, Ls = scale_.asDiagonal() * d.Lz;
  const Sparse Q(d.P.rows(), d.P.rows());
  lcp_ = std::make_unique<SparseActiveSetLcp>(Ks, Ls, d.P, Q);
  lcp_->set_low_rank(kMaxRank);
}

DescriptorStep::~DescriptorStep() = default;

bool DescriptorStep::start_values(const LcsProblem& model, double t, const Eigen::VectorXd& x,
                                  const Eigen::VectorXd& z) {
  // The last step's (sizes first: Eigen's == asserts on vectors of different sizes, and x_last_
  // is empty until a step has ended; a fuzz finding in the instrumented build).
  if (y_.size() == d_.unknowns() && x.size() == x_last_.size() && z.size() == z_last_.size() && x == x_last_ &&
      z == z_last_)
    return true;
  if (!instant_) {
    instant_ = std::make_unique<Instant>();
    instant_->lu.compute(d_.Kst);
    instant_->usable = instant_->lu.info() == Eigen::Success;
  }
  if (!instant_->usable) return false;
  u_ = model.input_values(t);
  a_ = d_.Xst * x + d_.Uin * u_;
  a_ -= d_.Lz * z;
  y_ = instant_->lu.solve(a_);
  return y_.allFinite();
}

bool DescriptorStep::step(const LcsProblem& model, double t, Eigen::VectorXd& x, Eigen::VectorXd& z) {
  return advance(model, t, t + h_, x, z);
}

bool DescriptorStep::step_ending_at(const LcsProblem& model, double t_end, Eigen::VectorXd& x, Eigen::VectorXd& z) {
  return advance(model, t_end - h_, t_end, x, z);
}

bool DescriptorStep::advance(const LcsProblem& model, double t, double t_end, Eigen::VectorXd& x,
                             Eigen::VectorXd& z) {
  if (fresh_) lcp_->prefer(z);
  fresh_ = false;
  const bool explicit_part = theta_ != 1.0;
  if (explicit_part && !start_values(model, t, x, z)) return false;
  u_ = model.input_values(t_end);
  a_ = d_.Sx * x + d_.Uin * u_;
  if (explicit_part) a_ += (h_ * (1 - theta_)) * (d_.Sy * y_);
  a_ = a_.cwiseProduct(scale_);
  b_.noalias() = d_.Fw * u_;
  if (!lcp_->solve(a_, b_, y_next_, z_next_, w_)) return false;
  x = d_.X * y_next_;
  z = z_next_;
  if (explicit_part) {
    y_.swap(y_next_);
    x_last_ = x;
    z_last_ = z;
  }
  return true;
}

}  // namespace lcs
