// `analyze`'s answer to "is the solution unique?" (issue 10): whether the LCP matrices lcspice
// solves are P-matrices -- one solution for every q (Stewart 2.2) -- and, where not, which
// transistors make them fail (5.4.7: feedback between transistors; alone, alpha < 1 keeps each
// one's block P). Two matrices: the operating point's D - C A^-1 B, and implicit Euler's step
// matrix D + h C (I - h A)^-1 B at h = TSTEP. A large sparse circuit's are examined block by
// block (solver/model/pair_blocks.h), never formed whole: a block of up to kMaxCheckedPairs
// pairs exactly; a larger one is a P-matrix if its symmetric part is diagonally dominant
// (O(b) memory), else, up to kDenseBlockPairs pairs, if the dense block passes "M + M^T
// positive definite" (O(b^2) memory, O(b^3) time: 0.01 s at 400); else it is not checked.
// The dominance test itself is skipped, and says so, where its work passes kDominanceWork.
#pragma once

#include <string>
#include <vector>

#include "solver/lcp/p_matrix.h"
#include "solver/model/circuit_model.h"

namespace lcs {

struct UniquenessEntry {
  std::string what;          // "operating point (D - C A^-1 B)"
  int size = 0;              // m
  PMatrixReport report;
  std::vector<std::string> failing_pairs;  // names of the pairs of the failing minor
  std::string owners;        // "transistors q1 and q2"
  // Large sparse circuits (pair_blocks.h): M examined by the blocks of pairs it couples; an
  // unchecked verdict names the size of its largest unchecked block (0: M was one block).
  int blocks = 0;
  int unchecked_block = 0;
  // Why M was not formed (its dense LCS over analyze's budget, dense_budget.h); empty when it was.
  std::string not_formed;
  // Why a block's sufficient test was not run (its work over kDominanceWork); empty when it was.
  std::string not_tested;
  std::string verdict() const;  // one line of text
  std::string json_verdict() const;  // "P", "not P", "semidefinite", "unchecked", "empty"
};

constexpr int kDenseBlockPairs = 400;
// The diagonal-dominance test of one block is b sparse solves (SchurBlocks::dominance_work): a
// block coupled end to end costs O(b^2). Measured on clamped ladders (`lcspice analyze`, one
// block of b pairs per matrix): 1.1e7 at 1000 sections, 2.75e8 at 5000 (0.6 s a matrix), 1.1e9
// at 10,000 (2.3 s), 6.9e9 at 25,000 (15 s): above this bound the block is not checked.
constexpr double kDominanceWork = 1e9;

// tstep <= 0: the step matrix is left out (no .tran).
std::vector<UniquenessEntry> uniqueness_report(const CircuitModel& model, double tstep);

}  // namespace lcs
