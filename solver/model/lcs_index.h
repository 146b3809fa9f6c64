// Index of an LCS from its Markov parameters (Stewart 4.5): G(s) = D + CB/s + CAB/s^2 + ...;
// the index is the smallest k such that D + ... + C A^(k-1) B / s^k is nonsingular for large s.
#pragma once

#include <string>
#include <vector>

#include "solver/model/circuit_model.h"

namespace lcs {

struct LcsIndex {
  int index = -1;               // -1: G(s) singular for large s (no unique solutions)
  std::vector<int> pair_index;  // per pair: first k with a nonzero diagonal (G_k)_ii, -1 if none
  std::vector<Eigen::MatrixXd> markov;  // G_0 = D, G_1 = CB, G_2 = CAB; up to kPrintedMarkovPairs
  // Why the index was not computed (a dense LCS over analyze's budget, dense_budget.h); empty
  // when it was.
  std::string not_computed;
};

// Above this many pairs the Markov parameters are not kept (nor printed by `analyze`).
constexpr int kPrintedMarkovPairs = 24;

LcsIndex lcs_index(const Lcs& lcs);
// The same for a model: a large sparse circuit's from its sparse LCS, without its dense A, B, C, D
// (sparse Markov parameters up to G_8 and a sparse LU for the singularity test; the dense test
// above only when that does not decide, and only within kAnalyzeDenseBytes).
LcsIndex lcs_index(const LcsProblem& model);

}  // namespace lcs
