// The fixed-step aliasing guard (issue 13, SPEC §1 `--step`): a fixed step must resolve the
// sources it samples. `.tran 1m 1.5` with a 1 kHz sine stepped at h = TSTEP samples the source at
// its zero crossings, and implicit Euler then reports 0 V for the whole run without a word.
#pragma once

#include <optional>
#include <string>

#include "netlist/netlist.h"
#include "solver/integrators/transient.h"

namespace lcs {

// The finest feature of one independent source a fixed step must resolve, and the longest step
// that does (`max_step`).
struct SourceFeature {
  std::string element;   // "v1"
  std::string what;      // "period 1 ms" / "pulse width 2 us" / "PWL segment 1 us"
  double max_step = 0;   // a step above this misrepresents the source
  // How long it oscillates (a sine, its NCYCLES, SFFM, AM): the event method's steps are bounded
  // there too, by 0.5/omega (4 pi a period); 0: the event method takes it exactly (edges, PWL).
  double oscillates_for = 0;
};

// Rules (the fractions are choices, stated here and in README): a periodic source (SIN, PULSE
// period) needs 50 steps per period, so implicit Euler's phase lag per step ω·h stays near
// 0.13 rad (SFFM: at its highest instantaneous frequency FC + MDI·FS; AM: at FC + FM); a pulse
// width 5 steps, a written EXP time constant 5; a written PULSE edge and a PWL segment along
// which the value changes one step each (defaulted edges follow TSTEP and are not features).
// nullopt: no source constrains the step (DC only).
std::optional<SourceFeature> finest_source_feature(const Netlist& netlist);

// The guard for a fixed-step run of `options.method` at `options.step`. A step the user chose
// (step_given: --step) is kept, with a warning; otherwise the step is the output step
// (`step_name`: "TSTEP" for run, "output step" for validate) and the method takes
// options.substeps steps per output step, with a note, or the run is refused (CliError, exit 2
// located at the .tran card) when that needs more than 1e7 steps.
void guard_source_sampling(const Netlist& netlist, bool step_given, const std::string& step_name,
                           TransientOptions& options);
// `options` with the fixed-step default method (euler) in place of its method, as `run` falls
// back to it when the default method stops: at `step`, with the substeps the guard asks of it
// unless the step was given (--step); nullopt where the guard would refuse it. Nothing is printed.
std::optional<TransientOptions> fixed_step_fallback(const Netlist& netlist, TransientOptions options, double step,
                                                    bool step_given);

}  // namespace lcs
