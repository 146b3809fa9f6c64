#include "solver/model/operating_point.h"

#include "solver/lcp/lcp.h"
#include "solver/model/numerical_failure.h"

namespace lcs {

namespace {

struct StaticProblem {
  Eigen::MatrixXd M;        // D - C A^-1 B
  Eigen::VectorXd q;        // (F - C A^-1 E) u
  Eigen::MatrixXd XofZ;     // x = XofZ z + x0
  Eigen::VectorXd x0;
  std::vector<std::string> undetermined;
};

StaticProblem static_problem(const CircuitModel& model, double t) {
  const Lcs& s = model.lcs();
  const int n = s.states();
  StaticProblem p;
  const Eigen::VectorXd u = model.input_values(t);
  Eigen::MatrixXd A = s.A;
  if (n > 0) {
    Eigen::FullPivLU<Eigen::MatrixXd> lu(A);
    if (!lu.isInvertible()) {
      Eigen::MatrixXd kernel = lu.kernel();
      for (int j = 0; j < n; ++j)
        if (kernel.row(j).cwiseAbs().maxCoeff() > 1e-9) p.undetermined.push_back(model.states()[j].label);
      const double scale = A.cwiseAbs().maxCoeff();
      A -= (scale > 0 ? 1e-9 * scale : 1e-9) * Eigen::MatrixXd::Identity(n, n);
    }
    Eigen::PartialPivLU<Eigen::MatrixXd> lu_reg(A);
    p.XofZ = -lu_reg.solve(s.B);
    p.x0 = -lu_reg.solve(s.E * u);
  } else {
    p.XofZ = Eigen::MatrixXd::Zero(0, s.pairs());
    p.x0 = Eigen::VectorXd::Zero(0);
  }
  p.M = s.D + s.C * p.XofZ;
  p.q = s.F * u + s.C * p.x0;
  return p;
}

OperatingPoint point_from(const StaticProblem& p, const Eigen::VectorXd& z) {
  OperatingPoint op;
  op.z = z;
  op.x = p.XofZ * z + p.x0;
  op.undetermined = p.undetermined;
  return op;
}

}  // namespace

OperatingPoint solve_operating_point(const CircuitModel& model, double t) {
  StaticProblem p = static_problem(model, t);
  LcpSolution sol = solve_lemke(p.M, p.q);
  if (sol.status != LcpStatus::Solved)
    throw NumericalFailure(t, std::string("the operating point has no solution (Lemke: ") +
                                  lcp_status_name(sol.status) + ")");
  OperatingPoint op = point_from(p, sol.z);
  op.pivots = sol.pivots;
  return op;
}

std::vector<OperatingPoint> enumerate_operating_points(const CircuitModel& model, double t) {
  StaticProblem p = static_problem(model, t);
  std::vector<OperatingPoint> out;
  for (const Eigen::VectorXd& z : enumerate_lcp_solutions(p.M, p.q)) out.push_back(point_from(p, z));
  return out;
}

}  // namespace lcs
