// Reading a netlist and forming its model, with input errors turned into CLI errors.
#pragma once

#include <string>
#include <vector>

#include "netlist/netlist.h"
#include "solver/model/circuit_model.h"

namespace lcs {
struct TransientOptions;
}

namespace lcs {

// FileError -> exit 1; NetlistError -> exit 2. Prints the netlist's warnings to stderr.
// `require_transient`: see ReadOptions (run and validate).
Netlist load_netlist(const std::string& path, bool require_transient = false);
// TopologyError / NetlistError -> exit 2. [t0, t1] is the interval the sources are checked over;
// diode_ranges: the currents each fitted diode carries (diode_refit.h).
CircuitModel build_model(const Netlist& netlist, double t0, double t1,
                         const std::map<std::string, DiodeCurrentRanges>& diode_ranges = {});
// Probes from a `--probe` list ("v(a),v(p,n),i(d1)": commas inside parentheses belong to a probe).
std::vector<Probe> parse_probe_list(const std::string& list);
// The netlist's probes, else the model's defaults (after a .print's V(*): the defaults, then the
// netlist's probes not among them).
std::vector<Probe> probes_for(const Netlist& netlist, const CircuitModel& model,
                              const std::string& cli_list);
// The netlist's first S or W element; nullptr: none.
const Element* first_switch(const Netlist& netlist);
OutputMap output_map_or_exit(const CircuitModel& model, const std::vector<Probe>& probes);
void warn(const std::string& text);  // "lcspice: warning: ..." on stderr
// `.options method=` and `theta=` into `options` (read_netlist_options: registry names and
// ngspice's trap, theta 0.5; gear is accepted with a warning and the default method). Returns
// whether the deck names a method (`.options method=`, gear aside); a bad value exits 2.
bool apply_netlist_options(const Netlist& netlist, TransientOptions& options);

}  // namespace lcs

namespace lcs {
// Components of H (5.4.6) that reach ground only through diodes or current sources: while none
// of their diodes conducts, their potential is not unique (the LCP has a continuum of solutions
// in the tree diodes' voltage-type z). One message per such component; empty when there are none.
std::vector<std::string> floating_potential_warnings(const CircuitModel& model);
// The same, only for components holding a node whose absolute voltage is probed.
std::vector<std::string> floating_probe_warnings(const CircuitModel& model,
                                                 const std::vector<Probe>& probes);
// Whether `node` lies in such a component.
bool has_floating_potential(const CircuitModel& model, const std::string& node);
// The probes among `probes` that read such a potential: v(node) of a node reached only through
// diodes (one partition of the graph for all of them).
std::vector<std::string> floating_potential_probes(const CircuitModel& model, const std::vector<Probe>& probes);
// At DC capacitors are open: the nodes that reach ground only through diodes, current sources and
// capacitors (and not through diodes and current sources alone: those are above) have an
// operating point whose potential is not unique while none of their diodes conducts. Once the run
// starts their capacitors' charge holds it, so only the start is a choice: one message per such
// component, none where a .ic on one of its nodes or an IC= on one of its capacitors chooses it.
// `probes` non-null: only components holding a node whose absolute voltage is probed.
std::vector<std::string> dc_floating_start_warnings(const CircuitModel& model, const Netlist& netlist,
                                                    const std::vector<Probe>* probes = nullptr);
}  // namespace lcs
