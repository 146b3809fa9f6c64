#include "cli/load_circuit.h"

#include <iostream>

#include "cli/exit_codes.h"

namespace lcs {

void warn(const std::string& text) { std::cerr << "lcspice: warning: " << text << "\n"; }

Netlist load_netlist(const std::string& path) {
  try {
    Netlist netlist = parse_netlist_file(path);
    for (const std::string& w : netlist.warnings) std::cerr << w << "\n";
    return netlist;
  } catch (const FileError& e) {
    throw CliError(kExitUsage, std::string("error: ") + e.what());
  } catch (const NetlistError& e) {
    throw CliError(kExitNetlist, e.formatted());
  }
}

CircuitModel build_model(const Netlist& netlist, double t0, double t1) {
  try {
    ModelOptions options;
    options.t0 = t0;
    options.t1 = t1;
    return CircuitModel::build(netlist, options);
  } catch (const TopologyError& e) {
    throw CliError(kExitNetlist, e.formatted(netlist));
  } catch (const NetlistError& e) {
    throw CliError(kExitNetlist, e.formatted());
  }
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
  if (!cli_list.empty()) return parse_probe_list(cli_list);
  if (!netlist.probes.empty()) return netlist.probes;
  return model.default_probes();
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
