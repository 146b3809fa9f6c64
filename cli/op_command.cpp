#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <iostream>

#include "cli/commands.h"
#include "cli/deck_transient.h"
#include "cli/exit_codes.h"
#include "cli/load_circuit.h"
#include "solver/model/numerical_failure.h"
#include "solver/devices/device.h"
#include "solver/lcp/lcp.h"
#include "solver/devices/switch.h"
#include "solver/model/line_dc_loops.h"
#include "solver/integrators/diode_refit.h"
#include "solver/model/operating_point.h"

namespace lcs {

namespace {

void print_point(const CircuitModel& model, const OperatingPoint& op) {
  const CircuitGraph& g = model.graph();
  model.begin_history(op.history);  // lines: their DC waves are this point's
  auto line = [](const std::string& name, double value, const char* note = "") {
    std::printf("  %-16s = %22.14e%s\n", name.c_str(), value, note);
  };
  // Nodes and branches inside a device ("o1#y1_0": a lossy line's states) are not printed; a
  // line's port 2 ("t1#2") is printed as i2(t1).
  auto internal = [](const std::string& name) { return name.find('#') != std::string::npos; };
  for (size_t n = 1; n < g.nodes.size(); ++n)
    if (!internal(g.nodes[n]))
      line("v(" + g.nodes[n] + ")", model.evaluate_dc(model.node_voltage(n), op.x, op.z, 0.0));
  std::vector<double> current(g.branches.size());
  double largest = 0;
  for (size_t b = 0; b < g.branches.size(); ++b) {
    current[b] = model.evaluate_dc(model.branch_current(b), op.x, op.z, 0.0);
    largest = std::max(largest, std::abs(current[b]));
  }
  // A diode conducts when its current stands out of the rounding of the solve.
  const double on_threshold = std::max(1e-9 * largest, 1e-15);
  // A transistor shows its junctions (on/off) and its terminal currents, not its transfer sources.
  const std::vector<std::shared_ptr<Device>>& devices = model.devices();
  for (size_t b = 0; b < g.branches.size(); ++b) {
    const bool terminals = !devices[g.branches[b].element]->terminals_probed_by_default().empty();
    if (terminals && g.branches[b].cls != BranchClass::Diode) continue;
    const std::string& name = g.branches[b].name;
    if (internal(name)) {
      if (name.size() > 2 && name.compare(name.size() - 2, 2, "#2") == 0)
        line("i2(" + name.substr(0, name.size() - 2) + ")", current[b]);
      continue;
    }
    const char* note = "";
    if (g.branches[b].cls == BranchClass::Diode) note = current[b] > on_threshold ? "   (on)" : "   (off)";
    if (const auto* s = dynamic_cast<const Switch*>(devices[g.branches[b].element].get()))
      note = s->on() ? "   (switch on)" : "   (switch off)";
    line("i(" + g.branches[b].name + ")", current[b], note);
  }
  for (const std::shared_ptr<Device>& d : devices)
    for (char terminal : d->terminals_probed_by_default()) {
      Probe p{Probe::Kind::TerminalCurrent, d->name(), "", {}};
      p.terminal = terminal;
      line(p.name(), model.evaluate_dc(model.terminal_current(p), op.x, op.z, 0.0));
    }
}

}  // namespace

int op_command(const OpArgs& args) {
  Netlist netlist = load_netlist(args.netlist);
  CircuitModel model = build_model(netlist, 0.0, 0.0);
  // Enumeration is exponential (enumerate_lcp_solutions): bounded at 24 pairs. Checked here, not
  // inferred from an exception, which other failures raise too.
  constexpr size_t kMaxEnumeratedPairs = 24;
  if (args.all && model.pairs().size() > kMaxEnumeratedPairs)
    throw CliError(kExitUsage, "error: op --all enumerates circuits of at most 24 diodes; this one has " +
                                   std::to_string(model.pairs().size()));
  try {
    if (netlist.tran && netlist.tran->uic) check_line_dc_loops(netlist);  // build_model did not
  } catch (const TopologyError& e) {
    throw CliError(kExitNetlist, e.formatted(netlist));
  }
  // Cards without VON/RON: their lines fitted as run fits them (SPEC 2: run starts at op's
  // point), over the deck's transient (deck_transient.h); without a .tran (or one run would
  // refuse), over the currents of the operating point itself: the refit's passes over one
  // 1e-15 s implicit Euler step, which stays there. Op used to print the 1 mA - 100 mA chord's
  // answer: a diode at 9.5 uA at 0.654 V against run's (and the Shockley curve's) 0.535 V.
  if (!args.all) {
    DiodeRefitOptions refit_options;
    std::optional<TransientOptions> transient;
    try {
      transient = deck_transient(netlist, model, refit_options);
    } catch (const std::exception&) {
    }
    if (!transient) {
      transient.emplace();
      transient->method = fixed_step_default_method().name;
      transient->step = 1e-15;
      transient->tstop = 1e-15;
      refit_options = DiodeRefitOptions{};
    }
    ModelOptions mo;
    mo.t1 = transient->tstop;
    try {
      const DiodeRefitResult refit = refit_diodes(netlist, mo, *transient, refit_options);
      if (refit.passes > 0) model = build_model(netlist, 0.0, 0.0, refit.ranges);
      if (!refit.failure.empty())
        warn("fitting the diodes' lines to the currents they carry stopped at pass " + std::to_string(refit.passes) +
             " (" + refit.failure + "); the lines of the last pass that reached TSTOP are used");
    } catch (const NumericalFailure&) {
      // The operating point itself fails below, with its own message.
    }
    if (const std::string poor = poor_fit_message(model); !poor.empty()) warn(poor);
  }
  std::vector<OperatingPoint> points;
  try {
    if (args.all) points = enumerate_operating_points(model, 0.0);
    else points.push_back(solve_operating_point(model, 0.0));
  } catch (const NumericalFailure& e) {
    throw CliError(kExitNumerical, std::string("lcspice: error: ") + e.what());
  }
  if (points.empty())
    throw CliError(kExitNumerical, "lcspice: error: the operating point has no solution");
  if (!points.front().undetermined.empty())
    warn(undetermined_state_warning(points.front().undetermined));
  if (!args.all)
    for (const std::string& w : points.front().warnings) warn(w);
  std::printf("* operating point at t = 0: %s\n", netlist.title.c_str());
  if (args.all) std::printf("* %zu solution%s\n", points.size(), points.size() == 1 ? "" : "s");
  // Stability of a static solution: its index sign(det M_JJ) (lcp_solution_index). Index -1 is a
  // saddle of the fast dynamics any small charge storage adds (a flip-flop's balanced state).
  const Eigen::MatrixXd M = args.all && points.size() > 1 ? static_lcp_matrix(model) : Eigen::MatrixXd();
  for (size_t k = 0; k < points.size(); ++k) {
    if (args.all && points.size() > 1) {
      const int index = lcp_solution_index(M, points[k].z);
      std::printf("solution %zu (%s):\n", k + 1,
                  index > 0 ? "stable" : index < 0 ? "unstable: a saddle, index -1" : "stability undetermined");
    } else if (args.all) {
      std::printf("solution %zu:\n", k + 1);
    }
    print_point(model, points[k]);
  }
  return kExitOk;
}

}  // namespace lcs
