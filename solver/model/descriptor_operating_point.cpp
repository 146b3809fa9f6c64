#include "solver/model/descriptor_operating_point.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "solver/integrators/descriptor_step.h"

namespace lcs {

namespace {

// The step length whose leaks are 1e-9 of the circuit's largest conductance (capacitors: C / H)
// and of its smallest resistance (inductors: L / H).
double leak_step(const CircuitModel& model) {
  double g_max = 0, c_max = 0, l_max = 0;
  for (const Element& e : model.netlist().elements)
    if (e.kind == ElementKind::Resistor && e.value > 0) g_max = std::max(g_max, 1.0 / e.value);
  for (const PairInfo& p : model.pairs())
    if (p.law.ron > 0) g_max = std::max(g_max, 1.0 / p.law.ron);
  for (const StateInfo& s : model.states()) {
    const std::optional<StorageInfo>& st = model.storage()[s.branch];
    if (!st) continue;
    (s.capacitor ? c_max : l_max) = std::max(s.capacitor ? c_max : l_max, std::abs(st->value));
  }
  if (!(g_max > 0)) g_max = 1.0;
  constexpr double kLeak = 1e-9;
  return std::max({c_max / (kLeak * g_max), l_max * g_max / kLeak, 1.0});
}

// Off: no current. A link (current-type) pair's z is its current and w its margin to the
// threshold; a tree (voltage-type) pair's z is the margin and w the current. `margin`: the least.
bool every_pair_strictly_off(const CircuitModel& model, const Eigen::VectorXd& z, const Eigen::VectorXd& w,
                             double& margin) {
  for (int i = 0; i < static_cast<int>(z.size()); ++i) {
    const bool tree = model.pairs()[i].voltage_type;
    const double current = tree ? w(i) : z(i), slack = tree ? z(i) : w(i);
    // A tree pair off has w = 0 as an equation of its mode: rounding (1e-19 A) remains.
    if (!(std::abs(current) <= (tree ? 1e-15 : 0.0)) || !(slack > 0)) return false;
    margin = std::min(margin, slack);
  }
  return true;
}

// One step of length H from (x, z) ending at t, or false.
bool leak_step_from(const CircuitModel& model, double H, double t, Eigen::VectorXd& x, Eigen::VectorXd& z,
                    Eigen::VectorXd& w) {
  DescriptorStep step(*model.sparse_descriptor(), H, 1.0);
  if (!step.step_ending_at(model, t, x, z) || !x.allFinite()) return false;
  w = step.last_w();
  return true;
}

}  // namespace

bool descriptor_operating_point(const CircuitModel& model, double t, OperatingPoint& op) {
  if (model.sparse_descriptor() == nullptr || model.has_transfer_pairs() || model.has_history()) return false;
  const int n = model.state_count(), m = model.pair_count();
  // The mode tried first is every pair off: a link pair's z (its current) zero, a tree pair's z
  // (its margin) free, so its current w is zero (DescriptorStep: the pairs with z > 0 are free).
  Eigen::VectorXd all_off = Eigen::VectorXd::Zero(m);
  for (int i = 0; i < m; ++i) all_off(i) = model.pairs()[i].voltage_type ? 1.0 : 0.0;
  // The leaks' error in a state a resistive path holds is about G_leak / G_path of it, which the
  // largest conductance alone does not bound (1 Mohm paths beside RON = 1 ohm: 1e-3): the step
  // grows tenfold until the states move by less than 1e-9 of their size (the error is then about
  // a tenth of that), and the dense path decides if they never settle.
  double H = leak_step(model);
  Eigen::VectorXd x, z, w, previous;
  bool settled = false;
  for (int k = 0; k < 8 && !settled; ++k, H *= 10) {
    x = Eigen::VectorXd::Zero(n);
    z = all_off;
    if (!leak_step_from(model, H, t, x, z, w)) return false;
    double ignored = std::numeric_limits<double>::infinity();
    if (!every_pair_strictly_off(model, z, w, ignored)) return false;  // below
    const double scale = std::max(1.0, n > 0 ? x.cwiseAbs().maxCoeff() : 0.0);
    settled = k > 0 && (n == 0 || (x - previous).cwiseAbs().maxCoeff() <= 1e-9 * scale);
    previous = x;
  }
  if (!settled) return false;
  H /= 10;  // the step that settled
  // Only with every pair off and strictly so: then the leaks' limit is the dense path's answer
  // (the linear circuit's, least energy on its free states). With a pair on, or at its threshold,
  // the dense path decides which pairs conduct exactly (a degenerate DC problem, several pairs at
  // zero current on their threshold, made the mode search cycle).
  double margin = std::numeric_limits<double>::infinity();
  const double volts = std::max(1.0, n > 0 ? x.cwiseAbs().maxCoeff() : 0.0);
  if (!every_pair_strictly_off(model, z, w, margin) || !(margin > 1e-9 * volts)) return false;
  // The states DC leaves free: from a random start inside those margins, a free state follows
  // the start by the same amount whatever the step (only leaks, all scaled by 1 / H, hold it);
  // a determined one moves by about G_leak / G_path of it, ten times less at a tenfold step.
  const double size = m > 0 ? 1e-3 * margin : 1.0;
  std::mt19937 random(20261127);
  std::uniform_real_distribution<double> magnitude(0.5, 1.0);
  Eigen::VectorXd start(n);
  for (int j = 0; j < n; ++j) start(j) = (random() % 2 ? size : -size) * magnitude(random);
  Eigen::VectorXd move[2];
  for (int k = 0; k < 2; ++k) {
    Eigen::VectorXd moved = start, z_moved = all_off, w_moved;
    if (!leak_step_from(model, k == 0 ? H : 10 * H, t, moved, z_moved, w_moved)) return false;
    double ignored = 0;
    if (!every_pair_strictly_off(model, z_moved, w_moved, ignored)) return false;
    move[k] = (moved - x).cwiseAbs();
  }
  op.x = x;
  op.z = z;
  op.undetermined.clear();
  for (int j = 0; j < n; ++j)
    if (move[1](j) > 0.5 * move[0](j) && move[1](j) > 1e-6 * std::abs(start(j)))
      op.undetermined.push_back(model.states()[j].label);
  return true;
}

}  // namespace lcs
