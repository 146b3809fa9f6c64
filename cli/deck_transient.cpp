#include "cli/deck_transient.h"

#include "cli/source_sampling.h"
#include "solver/integrators/method_registry.h"
#include "solver/model/netlist_options.h"

namespace lcs {

std::optional<TransientOptions> deck_transient(const Netlist& netlist, const CircuitModel& model,
                                               DiodeRefitOptions& refit_options) {
  if (!netlist.tran) return std::nullopt;
  TransientOptions o;
  const TranSpec& tran = *netlist.tran;
  o.tstop = tran.tstop;
  o.tstart = tran.tstart;
  o.uic = tran.uic;
  bool named = false;
  try {
    const NetlistOptions read = read_netlist_options(netlist);
    if (!read.method.empty() && find_method(read.method)) o.method = read.method, named = true;
    if (read.theta) o.method_options.theta = *read.theta;
  } catch (const NetlistError&) {
  }
  if (!named) o.method = default_method_for(model, nullptr).name;
  const bool tmax_below = tran.tmax > 0 && tran.tmax < tran.tstep;
  const bool fixed = find_method(o.method)->fixed_step();
  o.step = tmax_below && fixed ? tran.tmax : tran.tstep;
  if (tmax_below && !fixed) o.method_options.max_step = tran.tmax;
  if (!o.IsValid(nullptr) || find_method(o.method)->smooth_model) return std::nullopt;
  if (!named && o.method == exact_reference_method().name)
    refit_options.fallback = fixed_step_fallback(netlist, o, tmax_below ? tran.tmax : o.step, false);
  if (!fixed) return o;
  // A fixed-step method at its guarded substeps, as `run` steps it (nullopt where run refuses it).
  const std::optional<TransientOptions> guarded = fixed_step_fallback(netlist, o, o.step, false);
  if (!guarded) return std::nullopt;
  o.substeps = guarded->substeps;
  return o;
}

}  // namespace lcs
