// The waves a(r) = L X(r) that one mode of the event method sends into its lines over a segment,
// X(r) = exp(M r) X0 for r in [0, len], as Taylor polynomials about anchors r_i = i ρ, with
// ρ ||M||_1 <= 1/2 (so the terms fall at least as 2^-k / k! once M's nilpotent part is spent):
//
//   a(r_i + x ρ) = Σ_k W_ik x^k,   W_ik = L M^k X(r_i) ρ^k / k!,   x in [0, 1].
//
// The lines' history reads a segment 30-120 times (every fit of a later step at the other end,
// halvings included); each read was a product of up to 52 cached exponentials (Stewart 8.3's
// exact solution inside a mode), and those products were 80 % of a line deck's run. Built once
// at the segment's end, the reads are Horner sums. The anchors' states come from the exact
// product, so no error accumulates from piece to piece; a segment that would need more than
// kMaxPieces pieces (a stiff mode over a long segment) is left to the exact product.
#pragma once

#include <functional>
#include <optional>
#include <vector>

#include <Eigen/Dense>

namespace lcs {

class TaylorSegment {
 public:
  static constexpr int kMaxPieces = 8;
  // The last term kept is below kTermTol of the largest wave term (or of the waves' size).
  static constexpr double kTermTol = 1e-17;

  // exact_state(r): X(r) by the method's own exact product. Empty when len is not positive, the
  // segment needs more than kMaxPieces pieces or the series does not settle within q + 60 terms.
  static std::optional<TaylorSegment> build(const Eigen::MatrixXd& M, const Eigen::MatrixXd& L,
                                            const Eigen::VectorXd& X0, double len,
                                            const std::function<Eigen::VectorXd(double)>& exact_state);

  // The waves and their slopes at r (r below 0 read at 0; past len, the last piece's series).
  void eval(double r, std::vector<double>& values, std::vector<double>& slopes) const;

  int pieces() const { return static_cast<int>(terms_.size()); }
  int terms(int piece) const { return static_cast<int>(terms_[piece].cols()); }

 private:
  double len_ = 0, rho_ = 0;
  std::vector<Eigen::MatrixXd> terms_;  // per piece: waves x terms, W_ik in column k
};

}  // namespace lcs
