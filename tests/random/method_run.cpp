#include "tests/random/method_run.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "graph/topology.h"
#include "netlist/netlist.h"
#include "netlist/source_location.h"
#include "solver/integrators/transient.h"
#include "solver/model/circuit_model.h"
#include "solver/model/numerical_failure.h"
#include "solver/model/smooth_netlist.h"

namespace lcs::random_circuit {

namespace {

constexpr const char* kFile = "random.cir";

CircuitModel build(const Netlist& netlist) {
  ModelOptions mo;
  mo.t1 = netlist.tran ? netlist.tran->tstop : 0;
  return CircuitModel::build(netlist, mo);
}

}  // namespace

std::string formation_error(const std::string& text) {
  try {
    const Netlist netlist = parse_netlist_string(text, kFile);
    if (!netlist.tran) return "no .tran card";
    build(netlist);
    build(smooth_netlist(netlist, SmoothingOptions{}));
    return "";
  } catch (const NetlistError& e) {
    return e.what();
  } catch (const TopologyError& e) {
    return e.what();
  }
}

MethodRun run_method(const std::string& text, const MethodEntry& entry, const RunSettings& settings) {
  Netlist netlist = parse_netlist_string(text, kFile);
  const TranSpec& tran = netlist.tran.value();
  MethodRun run;
  run.method = entry.name;
  run.tstop = tran.tstop;
  run.tstep = tran.tmax > 0 ? std::min(tran.tstep, tran.tmax) : tran.tstep;
  TransientOptions o;
  o.method = entry.name;
  o.step = settings.divisions > 0 ? tran.tstop / static_cast<double>(settings.divisions) : run.tstep;
  o.tstop = tran.tstop;
  o.tstart = tran.tstart;
  o.uic = tran.uic;
  run.step = o.step;
  if (entry.smooth_model) netlist = smooth_netlist(netlist, SmoothingOptions{});
  const CircuitModel model = build(netlist);
  std::vector<Probe> probes = netlist.probes;
  if (probes.empty() || settings.all_probes) {
    probes = model.default_probes();
    for (const Probe& p : netlist.probes)
      if (std::none_of(probes.begin(), probes.end(), [&](const Probe& q) { return q.name() == p.name(); }))
        probes.push_back(p);
  }
  const OutputMap outputs = model.output_map(probes);
  MemorySink sink;
  try {
    run_transient(model, outputs, o, sink);
  } catch (const NumericalFailure& e) {
    run.failure = e.what();
  }
  run.names = sink.names;
  run.times = std::move(sink.times);
  run.rows = std::move(sink.rows);
  return run;
}

std::string malformation(const MethodRun& run) {
  std::ostringstream why;
  if (run.times.empty()) return run.failure.empty() ? "no rows" : "";
  if (run.times.front() != 0) why << "first time " << run.times.front() << " is not 0; ";
  for (size_t k = 0; k < run.times.size(); ++k) {
    if (static_cast<size_t>(run.rows[k].size()) != run.names.size()) {
      why << "row " << k << " has " << run.rows[k].size() << " values for " << run.names.size()
          << " probes; ";
      break;
    }
    if (!std::isfinite(run.times[k]) || !run.rows[k].allFinite()) {
      why << "row " << k << " (t = " << run.times[k] << ") is not finite; ";
      break;
    }
    if (k > 0 && !(run.times[k] > run.times[k - 1])) {
      why << "time " << run.times[k] << " (row " << k << ") does not follow " << run.times[k - 1]
          << "; ";
      break;
    }
  }
  // The last row is TSTOP itself, to rounding (fixed steps: k h; event: the grid's k TSTEP).
  if (run.failure.empty() && std::abs(run.times.back() - run.tstop) > 1e-9 * run.tstop)
    why << "last time " << run.times.back() << " is not TSTOP " << run.tstop << "; ";
  return why.str();
}

}  // namespace lcs::random_circuit
