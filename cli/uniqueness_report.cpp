#include "cli/uniqueness_report.h"

#include <algorithm>
#include <cstdio>
#include <optional>

#include "solver/integrators/multistability.h"
#include "solver/model/empty_safe.h"
#include "solver/model/operating_point.h"
#include "solver/model/pair_blocks.h"
#include "solver/model/dense_budget.h"
#include "solver/model/sparse_lcs.h"

namespace lcs {

std::string UniquenessEntry::verdict() const {
  char buf[64];
  switch (report.verdict) {
    case PMatrixReport::Verdict::P:
      return size == 0 ? "no pairs" : "a P-matrix: one solution for every q";
    case PMatrixReport::Verdict::Unchecked:
      if (!not_formed.empty()) return "not checked (" + not_formed + ")";
      if (!not_tested.empty()) return "not checked (" + not_tested + ")";
      if (report.symmetric_psd) return "symmetric positive semidefinite (a diode network): w is unique";
      if (unchecked_block > 0)
        return "not checked (a block of " + std::to_string(unchecked_block) + " coupled pairs, more than " +
               std::to_string(kMaxCheckedPairs) + ", and no sufficient test holds)";
      return "not checked (" + std::to_string(size) + " pairs, more than " + std::to_string(kMaxCheckedPairs) + ")";
    case PMatrixReport::Verdict::NotP: {
      if (report.symmetric_psd)
        return "symmetric positive semidefinite, not P (a diode network): w is unique, z may not be";
      std::string pairs;
      for (size_t k = 0; k < failing_pairs.size(); ++k) pairs += (k ? ", " : "") + failing_pairs[k];
      std::snprintf(buf, sizeof buf, "%.3g", report.minor);
      return "not a P-matrix: the principal minor of {" + pairs + "} is " + buf + " (" + owners +
             "): several solutions are possible";
    }
  }
  return "";
}

std::string UniquenessEntry::json_verdict() const {
  if (size == 0) return "empty";
  switch (report.verdict) {
    case PMatrixReport::Verdict::P: return "P";
    case PMatrixReport::Verdict::Unchecked: return report.symmetric_psd ? "semidefinite" : "unchecked";
    case PMatrixReport::Verdict::NotP: return report.symmetric_psd ? "semidefinite" : "not P";
  }
  return "";
}

namespace {

UniquenessEntry entry(const CircuitModel& model, const std::string& what, const Eigen::MatrixXd& M) {
  UniquenessEntry e;
  e.what = what;
  e.size = static_cast<int>(M.rows());
  e.report = p_matrix_report(M, kMaxCheckedPairs);
  for (int i : e.report.failing) e.failing_pairs.push_back(model.pairs()[i].name);
  if (!e.report.failing.empty()) e.owners = pair_owners(model, e.report.failing);
  return e;
}

using Sparse = Eigen::SparseMatrix<double>;

// M = Q - P K^-1 L of a sparse circuit, block by block (pair_blocks.h): P when every block is,
// not P at the first block with a failing minor (its pairs), else unchecked. Nullopt when K is
// singular (the dense matrix decides).
std::optional<UniquenessEntry> sparse_entry(const CircuitModel& model, const std::string& what,
                                            const Sparse& K, const Sparse& L, const Sparse& P,
                                            const Sparse& Q) {
  const std::optional<SchurBlocks> schur = SchurBlocks::make(K, L, P, Q);
  if (!schur) return std::nullopt;
  UniquenessEntry e;
  e.what = what;
  e.size = static_cast<int>(Q.rows());
  e.report.symmetric_psd = true;
  const std::vector<std::vector<int>> blocks = coupled_pair_blocks(K, L, P, Q);
  e.blocks = static_cast<int>(blocks.size());
  for (const std::vector<int>& block : blocks) {
    const int b = static_cast<int>(block.size());
    PMatrixReport r;
    const double work = b > kMaxCheckedPairs ? schur->dominance_work(block) : 0.0;
    if (work > kDominanceWork) {
      r.verdict = PMatrixReport::Verdict::Unchecked;
      r.symmetric_psd = false;
      char buf[200];
      std::snprintf(buf, sizeof buf,
                    "a block of %d coupled pairs: its diagonal-dominance test needs %d sparse solves, "
                    "%.2g entry operations, over analyze's bound of %.2g",
                    b, b, work, kDominanceWork);
      if (e.not_tested.empty()) e.not_tested = buf;
    } else if (b > kMaxCheckedPairs && schur->symmetric_part_dominant(block)) {
      r.verdict = PMatrixReport::Verdict::P;  // symmetric_psd: not examined (P says more)
    } else if (b <= kDenseBlockPairs) {
      r = p_matrix_report(schur->block(block), kMaxCheckedPairs);
    } else {
      r.verdict = PMatrixReport::Verdict::Unchecked;
    }
    e.report.symmetric_psd = e.report.symmetric_psd && r.symmetric_psd;
    if (r.verdict == PMatrixReport::Verdict::NotP) {
      e.report.verdict = r.verdict;
      e.report.minor = r.minor;
      for (int k : r.failing) e.report.failing.push_back(block[k]);
      e.unchecked_block = 0;
      break;
    }
    if (r.verdict == PMatrixReport::Verdict::Unchecked) {
      e.report.verdict = r.verdict;
      e.unchecked_block = std::max(e.unchecked_block, b);
    }
  }
  for (int i : e.report.failing) e.failing_pairs.push_back(model.pairs()[i].name);
  if (!e.report.failing.empty()) e.owners = pair_owners(model, e.report.failing);
  return e;
}

std::string step_matrix_what(double tstep) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "implicit Euler step, h = TSTEP = %.6g s (D + h C (I - h A)^-1 B)", tstep);
  return buf;
}

}  // namespace

std::vector<UniquenessEntry> uniqueness_report(const CircuitModel& model, double tstep) {
  std::vector<UniquenessEntry> out;
  const SparseLcs* sparse = model.has_history() ? nullptr : model.sparse_lcs().get();
  const std::string op_what = "operating point (D - C A^-1 B)";
  std::optional<UniquenessEntry> op;
  if (sparse) op = sparse_entry(model, op_what, sparse->A, sparse->B, sparse->C, sparse->D);
  const int n = model.state_count(), m = model.pair_count();
  if (!op && !dense_within_budget(n, m, 1, kAnalyzeDenseBytes)) {
    // A dense M of a large circuit: forming it is O((n + m)^3); each step's LCP is still solved
    // and checked on the sparse circuit.
    auto not_formed = [&](const std::string& what) {
      UniquenessEntry e;
      e.what = what;
      e.size = m;
      e.report.verdict = PMatrixReport::Verdict::Unchecked;
      e.report.symmetric_psd = false;
      e.not_formed = dense_budget_reason(n, m, 1, kAnalyzeDenseBytes);
      out.push_back(e);
    };
    not_formed(op_what);
    if (tstep > 0) not_formed(step_matrix_what(tstep));
    return out;
  }
  out.push_back(op ? *op : entry(model, op_what, static_lcp_matrix(model)));
  if (tstep > 0 && sparse) {
    const std::string buf = step_matrix_what(tstep);
    Sparse K(sparse->A.rows(), sparse->A.cols());
    K.setIdentity();
    K -= tstep * sparse->A;
    std::optional<UniquenessEntry> step = sparse_entry(model, buf, K, Sparse(-tstep * sparse->B), sparse->C, sparse->D);
    if (step) {
      out.push_back(*step);
      return out;
    }
  }
  if (tstep > 0) {
    const Lcs& s = model.lcs();
    const int n = s.states();
    Eigen::MatrixXd M = s.D;
    if (n > 0) {
      Eigen::PartialPivLU<Eigen::MatrixXd> W(Eigen::MatrixXd::Identity(n, n) - tstep * s.A);
      M += s.C * solve_or_empty(W, tstep * s.B);
    }
    out.push_back(entry(model, step_matrix_what(tstep), M));
  }
  return out;
}

}  // namespace lcs
