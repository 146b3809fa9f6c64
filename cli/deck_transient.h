// The transient `run` would make of a deck (its .tran and .options method), for the fit of its
// diodes to the currents they carry (`analyze`, `op`); none without a .tran card.
#pragma once

#include <optional>

#include "netlist/netlist.h"
#include "solver/integrators/diode_refit.h"
#include "solver/integrators/transient.h"
#include "solver/model/circuit_model.h"

namespace lcs {

// The deck's transient as `run` integrates it, for the refit's passes: the method the deck names,
// else the default (event where it applies), with run's steps (TMAX the fixed-step methods' step,
// event's rows at TSTEP) and, for the default event, run's euler fallback for a pass it fails
// (into refit_options.fallback). nullopt without a .tran, or where run would refuse the method.
std::optional<TransientOptions> deck_transient(const Netlist& netlist, const CircuitModel& model,
                                               DiodeRefitOptions& refit_options);

}  // namespace lcs
