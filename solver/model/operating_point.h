// DC operating point (SPEC §1 `op`): capacitors open, inductors shorted, sources at time t.
// With dx/dt = 0 the LCS becomes the static problem 0 = A x + B z + E u, w = C x + D z + F u,
// i.e. LCP(q, D - C A^-1 B) with q = (F - C A^-1 E) u.
#pragma once

#include <map>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "solver/model/circuit_model.h"

namespace lcs {

struct OperatingPoint {
  Eigen::VectorXd x;  // LCS state
  Eigen::VectorXd z;
  // A smoothed circuit's ideal start with several points: the others (x, z), from which the
  // smooth method seeks the Shockley operating point too, to tell a tie of the start's lines
  // (parallel junctions at VON = 0) from several operating points of the circuit itself.
  std::vector<std::pair<Eigen::VectorXd, Eigen::VectorXd>> other_starts;
  // Lines: the waves they carry at DC (their history inputs), in DelayHistory order. Solving
  // makes them the lines' past (LcsProblem::begin_history): values read at t are this point's.
  std::vector<double> history;
  int pivots = 0;
  // States DC leaves free (a loop of inductors, capacitors with no DC path, not even through a
  // conducting diode): they take the values of least stored energy. Labels listed.
  std::vector<std::string> undetermined;
  // Nodes whose .ic/.nodeset value chose this point among several (multistable circuits).
  std::vector<std::string> chosen_by;
  // Said once to the user: several operating points, one chosen by .ic/.nodeset; or uniqueness
  // that could not be checked (a transistor circuit with more than kMaxCheckedPairs pairs).
  std::vector<std::string> warnings;
};

// Transistor circuits (a non-symmetric static LCP) are checked for several operating points by
// enumerating active sets up to this many complementarity pairs.
constexpr int kMaxCheckedPairs = 16;

// Throws NumericalFailure when the static LCP has no solution, and when it has several (a
// multistable transistor circuit, Stewart 5.4.7) and no .ic/.nodeset value chooses one: the
// message names the transistors, the number of solutions and the ways to choose. With values
// given, the solution nearest to them (least squares over the given nodes) is taken, as ngspice's
// .nodeset does.
OperatingPoint solve_operating_point(const CircuitModel& model, double t = 0.0);

// Every solution of the static LCP (multistable circuits; diode-only circuits have one). With
// lines, call model.begin_history(point.history) before evaluating a point other than the last.
std::vector<OperatingPoint> enumerate_operating_points(const CircuitModel& model, double t = 0.0);

// .ic and .nodeset node voltages (.ic wins where both name a node): what chooses among several
// solutions, and the squared distance of a solution's node voltages from them.
std::map<std::string, double> node_hints(const Netlist& netlist);
double hint_distance(const CircuitModel& model, const std::map<std::string, double>& hints,
                     const Eigen::VectorXd& x, const Eigen::VectorXd& z, double t);

// The static problem's matrix D - C A^-1 B (A regularised where singular), for `analyze`.
Eigen::MatrixXd static_lcp_matrix(const CircuitModel& model, double t = 0.0);

// The warning `op` and `run` print for OperatingPoint::undetermined.
std::string undetermined_state_warning(const std::vector<std::string>& labels);

}  // namespace lcs
