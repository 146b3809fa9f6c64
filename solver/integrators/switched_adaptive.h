// Ideal switches (S, W) with the adaptive methods (issue 13). A configuration of the switches is
// a discrete mode of the circuit, like a diode's active set: inside it the method integrates that
// configuration's model, with each switch's control a guard (SwitchGuards, guarded_method.h)
// whose zero, where the control crosses VT + VH (an off switch) or VT - VH (an on one), the
// method locates as it locates its own events (event: the bisection of a mode change, to --rtol
// x TSTEP; smooth: IDA's root finder). There the run continues in the next configuration's model
// (SwitchFamily) from the same x, its complementarity mode (or diode currents) chosen afresh.
// Configurations that ask at once for another are passed through at the same instant; more than
// 64 changes there are chattering (NumericalFailure), as with fixed steps.
#pragma once

#include <Eigen/Dense>

#include "solver/integrators/method_registry.h"
#include "solver/integrators/output_sink.h"
#include "solver/integrators/transient.h"
#include "solver/model/initial_state.h"
#include "solver/model/switch_family.h"

namespace lcs {

// From configuration `config` and state init.x at t = 0 to options.tstop, rows of the probes named
// in `outputs` (each configuration writes them through its own output map). `entry` makes the
// guarded method of each configuration (MethodEntry::make_guarded); without UIC the first starts
// at the operating point (a smoothed circuit's own). Throws NumericalFailure; `summary` then holds
// the statistics so far. The methods' notes are added to summary.warnings.
void run_switched_adaptive(SwitchFamily& family, const SwitchConfig& config, const OutputMap& outputs,
                           const TransientOptions& options, const MethodEntry& entry, const InitialState& init,
                           OutputSink& sink, TransientSummary& summary, double cpu0);

}  // namespace lcs
