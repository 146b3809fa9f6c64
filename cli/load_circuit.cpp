#include "cli/load_circuit.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <set>

#include "cli/exit_codes.h"
#include "solver/model/numerical_failure.h"
#include "solver/model/switch_family.h"
#include "solver/integrators/transient.h"
#include "solver/model/netlist_options.h"
#include "solver/model/operating_point.h"

namespace lcs {

void warn(const std::string& text) { std::cerr << "lcspice: warning: " << text << "\n"; }

Netlist load_netlist(const std::string& path, bool require_transient) {
  try {
    ReadOptions options;
    options.require_transient = require_transient;
    Netlist netlist = parse_netlist_file(path, options);
    for (const std::string& w : netlist.warnings) std::cerr << w << "\n";
    // ngspice refuses an empty circuit too: an analysis or a run of nothing would pass for a result.
    if (netlist.elements.empty())
      throw CliError(kExitNetlist, path + ": error: the netlist has no elements: nothing to simulate or analyze");
    return netlist;
  } catch (const FileError& e) {
    throw CliError(kExitUsage, std::string("error: ") + e.what());
  } catch (const NetlistError& e) {
    throw CliError(kExitNetlist, e.formatted());
  }
}

CircuitModel build_model(const Netlist& netlist, double t0, double t1,
                         const std::map<std::string, DiodeCurrentRanges>& diode_ranges) {
  try {
    ModelOptions options;
    options.t0 = t0;
    options.t1 = t1;
    options.diode_ranges = diode_ranges;
    CircuitModel model = CircuitModel::build(netlist, options);
    // Switches: the configuration at t = 0 (ON/OFF, else the controls at the operating point).
    SwitchFamily switches(model);
    if (switches.empty()) return model;
    const SwitchConfig start = switches.config_of(model);
    const SwitchConfig config = initial_configuration(switches, start, netlist.tran && netlist.tran->uic);
    if (config == start) return model;
    for (size_t k = 0; k < config.size(); ++k) options.switch_on[switches.switches()[k].name] = config[k] != 0;
    return CircuitModel::build(netlist, options);
  } catch (const NumericalFailure& e) {
    throw CliError(kExitNumerical, std::string("lcspice: error: numerical failure ") + e.what());
  } catch (const TopologyError& e) {
    throw CliError(kExitNetlist, e.formatted(netlist));
  } catch (const NetlistError& e) {
    throw CliError(kExitNetlist, e.formatted());
  }
}

const Element* first_switch(const Netlist& netlist) {
  for (const Element& el : netlist.elements)
    if (el.kind == ElementKind::VSwitch || el.kind == ElementKind::CSwitch) return &el;
  return nullptr;
}

std::vector<Probe> parse_probe_list(const std::string& list) {
  std::vector<Probe> probes;
  int depth = 0;
  size_t start = 0;
  for (size_t k = 0; k <= list.size(); ++k) {
    const char c = k < list.size() ? list[k] : ',';
    if (c == '(') ++depth;
    if (c == ')') --depth;
    if (k < list.size() && (c != ',' || depth > 0)) continue;  // an unclosed '(' ends at the end
    std::string text = list.substr(start, k - start);
    const size_t a = text.find_first_not_of(" \t"), b = text.find_last_not_of(" \t");
    if (a != std::string::npos) {
      SourceLocation loc;
      loc.file = "--probe";
      loc.line = 1;
      loc.column = static_cast<int>(start + a + 1);
      loc.length = static_cast<int>(b - a + 1);
      loc.line_text = list;
      try {
        probes.push_back(parse_probe(text.substr(a, b - a + 1), loc));
      } catch (const NetlistError& e) {
        throw CliError(kExitUsage, e.formatted());
      }
    }
    start = k + 1;
  }
  return probes;
}

std::vector<Probe> probes_for(const Netlist& netlist, const CircuitModel& model,
                              const std::string& cli_list) {
  if (!cli_list.empty()) {
    std::vector<Probe> probes = parse_probe_list(cli_list);
    if (probes.empty()) throw CliError(kExitUsage, "error: --probe '" + cli_list + "' names no probe");
    return probes;
  }
  if (!netlist.every_probe && !netlist.probes.empty()) return netlist.probes;
  std::vector<Probe> probes = model.default_probes();
  std::set<std::string> names;
  for (const Probe& p : probes) names.insert(p.name());
  for (const Probe& p : netlist.probes)
    if (names.insert(p.name()).second) probes.push_back(p);
  return probes;
}

OutputMap output_map_or_exit(const CircuitModel& model, const std::vector<Probe>& probes) {
  try {
    return model.output_map(probes);
  } catch (const NetlistError& e) {
    const bool from_cli = e.location().file == "--probe";
    throw CliError(from_cli ? kExitUsage : kExitNetlist, e.formatted());
  }
}

}  // namespace lcs

#include "graph/components.h"

namespace lcs {

namespace {

std::string floating_message(const CircuitModel& model, const NodePartition& h, int component) {
  const CircuitGraph& g = model.graph();
  std::vector<std::string> nodes, diodes;
  for (size_t n = 0; n < g.nodes.size(); ++n)
    if (h.component[n] == component) nodes.push_back(g.nodes[n]);
  for (const Branch& b : g.branches)
    if (b.cls == BranchClass::Diode && (h.component[b.from] == component) != (h.component[b.to] == component))
      diodes.push_back(b.name);
  std::vector<std::string> quoted;
  for (const std::string& n : nodes) quoted.push_back("'" + n + "'");
  return (nodes.size() == 1 ? "node " + quoted[0] + " reaches" : "nodes " + join_names(quoted) + " reach") +
         " ground only through diodes (" + join_names(diodes) +
         ") or current sources: while none of those diodes conducts, their potential is not "
         "unique and lcspice reports one valid value (a diode at its threshold); currents and "
         "voltages between these nodes are unique";
}

}  // namespace

std::vector<std::string> floating_potential_warnings(const CircuitModel& model) {
  NodePartition h = h_components(model.graph());
  std::vector<std::string> out;
  for (int c = 0; c < h.count; ++c)
    if (c != h.component[0]) out.push_back(floating_message(model, h, c));
  return out;
}

std::vector<std::string> floating_probe_warnings(const CircuitModel& model,
                                                 const std::vector<Probe>& probes) {
  NodePartition h = h_components(model.graph());
  std::vector<bool> probed(h.count, false);
  for (const Probe& p : probes) {
    if (p.kind != Probe::Kind::NodeVoltage) continue;
    const int n = model.graph().node_index(p.a);
    if (n >= 0) probed[h.component[n]] = true;
  }
  std::vector<std::string> out;
  for (int c = 0; c < h.count; ++c)
    if (c != h.component[0] && probed[c]) out.push_back(floating_message(model, h, c));
  return out;
}

std::vector<std::string> floating_potential_probes(const CircuitModel& model, const std::vector<Probe>& probes) {
  const NodePartition h = h_components(model.graph());
  std::vector<std::string> out;
  for (const Probe& p : probes) {
    const int n = p.kind == Probe::Kind::NodeVoltage && p.b.empty() ? model.graph().node_index(p.a) : -1;
    if (n >= 0 && h.component[n] != h.component[0]) out.push_back(p.name());
  }
  return out;
}

bool has_floating_potential(const CircuitModel& model, const std::string& node) {
  const NodePartition h = h_components(model.graph());
  const int n = model.graph().node_index(node);
  return n >= 0 && h.component[n] != h.component[0];
}

std::vector<std::string> dc_floating_start_warnings(const CircuitModel& model, const Netlist& netlist,
                                                    const std::vector<Probe>* probes) {
  const CircuitGraph& g = model.graph();
  const NodePartition h = h_components(g);
  const NodePartition dc = components(g, [](const Branch& b) {
    return b.cls != BranchClass::Diode && b.cls != BranchClass::CurrentSource && b.cls != BranchClass::Capacitor;
  });
  // A component of `dc` apart from ground's, inside ground's component of H (the others are
  // floating_potential_warnings').
  std::vector<bool> candidate(dc.count, false);
  for (size_t n = 0; n < g.nodes.size(); ++n)
    candidate[dc.component[n]] = dc.component[n] != dc.component[0] && h.same(static_cast<int>(n), 0);
  for (const NodeIc& ic : netlist.node_ics) {
    const int n = g.node_index(ic.node);
    if (n >= 0) candidate[dc.component[n]] = false;
  }
  for (size_t b = 0; b < g.branches.size(); ++b)
    if (g.branches[b].cls == BranchClass::Capacitor && model.storage()[b] && model.storage()[b]->ic) {
      candidate[dc.component[g.branches[b].from]] = false;
      candidate[dc.component[g.branches[b].to]] = false;
    }
  if (probes) {
    std::vector<bool> probed(dc.count, false);
    for (const Probe& p : *probes) {
      const int n = p.kind == Probe::Kind::NodeVoltage && p.b.empty() ? g.node_index(p.a) : -1;
      if (n >= 0) probed[dc.component[n]] = true;
    }
    for (int c = 0; c < dc.count; ++c) candidate[c] = candidate[c] && probed[c];
  }
  std::vector<std::string> out;
  if (std::none_of(candidate.begin(), candidate.end(), [](bool c) { return c; })) return out;
  // Where a diode at its boundary conducts at the operating point (a differential pair's emitters,
  // reached at DC only through its junctions), that diode pins the potential.
  OperatingPoint op;
  try {
    op = solve_operating_point(model, 0.0);
  } catch (const NumericalFailure&) {
    return out;  // the run reports it
  }
  std::vector<double> current(g.branches.size(), 0.0);
  double largest = 0;
  for (size_t b = 0; b < g.branches.size(); ++b) {
    current[b] = model.evaluate_dc(model.branch_current(static_cast<int>(b)), op.x, op.z, 0.0);
    largest = std::max(largest, std::abs(current[b]));
  }
  const double on_threshold = std::max(1e-9 * largest, 1e-15);  // as `op` tells on from off
  for (size_t b = 0; b < g.branches.size(); ++b) {
    const Branch& br = g.branches[b];
    if (br.cls == BranchClass::Diode && dc.component[br.from] != dc.component[br.to] &&
        current[b] > on_threshold) {
      candidate[dc.component[br.from]] = false;
      candidate[dc.component[br.to]] = false;
    }
  }
  for (int c = 0; c < dc.count; ++c) {
    if (!candidate[c]) continue;
    std::vector<std::string> nodes, diodes, capacitors;
    for (size_t n = 0; n < g.nodes.size(); ++n)
      if (dc.component[n] == c) nodes.push_back("'" + g.nodes[n] + "'");
    for (const Branch& b : g.branches) {
      if ((dc.component[b.from] == c) == (dc.component[b.to] == c)) continue;
      if (b.cls == BranchClass::Diode) diodes.push_back(b.name);
      if (b.cls == BranchClass::Capacitor) capacitors.push_back(b.name);
    }
    out.push_back((nodes.size() == 1 ? "node " + nodes[0] + " reaches" : "nodes " + join_names(nodes) + " reach") +
                  " ground at DC only through diodes (" + join_names(diodes) + ") and capacitors (" +
                  join_names(capacitors) +
                  "): the operating point leaves " + (nodes.size() == 1 ? "its potential" : "their potentials") +
                  " free while none of those diodes conducts, and the run starts from one valid value, where a "
                  "real circuit's start (and ngspice's) is set by the diodes' leakage; give .ic, IC= on the "
                  "capacitors, or UIC to choose it");
  }
  return out;
}

bool apply_netlist_options(const Netlist& netlist, TransientOptions& options) {
  NetlistOptions read;
  try {
    read = read_netlist_options(netlist);
  } catch (const NetlistError& e) {
    throw CliError(kExitNetlist, e.formatted());
  }
  if (!read.method.empty()) options.method = read.method;
  if (read.gear) warn(".options method=gear: lcspice has no Gear method; using the default method");
  if (read.theta) options.method_options.theta = *read.theta;
  return !read.method.empty();
}

}  // namespace lcs
