#include "cli/uniqueness_report.h"

#include <cstdio>

#include "solver/integrators/multistability.h"
#include "solver/model/empty_safe.h"
#include "solver/model/operating_point.h"

namespace lcs {

std::string UniquenessEntry::verdict() const {
  char buf[64];
  switch (report.verdict) {
    case PMatrixReport::Verdict::P:
      return size == 0 ? "no pairs" : "a P-matrix: one solution for every q";
    case PMatrixReport::Verdict::Unchecked:
      return report.symmetric_psd ? "symmetric positive semidefinite (a diode network): w is unique"
                                  : "not checked (" + std::to_string(size) + " pairs, more than " +
                                        std::to_string(kMaxCheckedPairs) + ")";
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

}  // namespace

std::vector<UniquenessEntry> uniqueness_report(const CircuitModel& model, double tstep) {
  std::vector<UniquenessEntry> out;
  out.push_back(entry(model, "operating point (D - C A^-1 B)", static_lcp_matrix(model)));
  if (tstep > 0) {
    const Lcs& s = model.lcs();
    const int n = s.states();
    Eigen::MatrixXd M = s.D;
    if (n > 0) {
      Eigen::PartialPivLU<Eigen::MatrixXd> W(Eigen::MatrixXd::Identity(n, n) - tstep * s.A);
      M += s.C * solve_or_empty(W, tstep * s.B);
    }
    char buf[96];
    std::snprintf(buf, sizeof buf, "implicit Euler step, h = TSTEP = %.6g s (D + h C (I - h A)^-1 B)", tstep);
    out.push_back(entry(model, buf, M));
  }
  return out;
}

}  // namespace lcs
