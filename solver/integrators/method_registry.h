// The named table of integration methods (`--method NAME`), sorted by name.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "solver/integrators/continuous_method.h"
#include "solver/integrators/time_stepper.h"

namespace lcs {

class GuardedMethod;

struct MethodOptions {
  double theta = 0.5;  // `--theta`, used by "theta"
  // `--euler-at-switching`: theta < 1 checks a stiff step whose mode changes against implicit
  // Euler's (euler_at_switching.h). Off by default: where it fires at an ordinary stiff switching
  // it makes theta first order there (a bridge into C and L-R: 4-13 times theta's own error).
  bool euler_at_switching = false;
  // `--rtol`, `--atol` of the adaptive methods; 0 means the method's default (event: rtol 1e-13
  // on event times; smooth: rtol 1e-6, atol 1e-9 as in SUNDIALS' weighted norm).
  double rtol = 0, atol = 0;
  // Large circuits step on the sparse system (theta_method.h) and the smooth method's IDA on a
  // sparse Jacobian with KLU (shockley_dae.h); false keeps the dense LCP and Jacobian, to compare.
  bool sparse = true;
  // The event method reads its line history as Taylor series (taylor_segment.h); false keeps the
  // exact product for every read, to compare the two.
  bool history_series = true;
  // The event method's budget for its modes, in bytes (event_driven.h); 0 keeps its default.
  std::size_t event_mode_cache_bytes = 0;
  // The deck's TMAX where it is below TSTEP: smooth's largest step (rows stay at TSTEP); 0: none.
  // (Event is exact between events; the fixed-step methods step at it instead.)
  double max_step = 0;
};

// What `bench` varies for a method: the fixed step h, or the tolerance --rtol.
enum class BenchSweep { StepSize, Tolerance };

// Exactly one of make_stepper (fixed-step time-stepping, one LCP per step) and make_continuous
// (methods that choose their own steps and output times) is set. The traits below are what the
// commands ask of a method; nothing outside method_registry.cpp compares method names.
struct MethodEntry {
  std::string name;
  std::string description;
  std::function<std::unique_ptr<TimeStepper>(const LcsProblem&, const MethodOptions&)>
      make_stepper;
  std::function<std::unique_ptr<ContinuousMethod>(const LcsProblem&, const MethodOptions&)>
      make_continuous;
  bool smooth_model = false;     // integrates the smoothed circuit (Shockley diodes, smooth_netlist)
                                 // instead of the ideal complementarity law
  bool uses_theta = false;       // reads MethodOptions::theta (`--theta`, `.options theta=`)
  // Steps large circuits on the sparse system or the descriptor form (theta_method.h); the
  // others keep the dense LCS at every size.
  bool large_circuit_steps = false;
  BenchSweep bench_sweep = BenchSweep::StepSize;
  bool exact_reference = false;  // bench's reference for the ideal circuit (exact: event)
  bool smooth_reference = false; // bench's reference for the smoothed circuit
  bool is_default = false;       // the method when none is given (`run`), where it applies
  // Where the default does not apply: the fixed-step method `run` takes instead (and the method
  // of a TransientOptions that names none).
  bool is_fixed_step_default = false;
  // Whether this method serves as the default for a circuit; unset: it serves every circuit.
  // On false, *why says what rules it out ("128 complementarity pairs, more than ...").
  std::function<bool(const LcsProblem&, std::string* why)> serves_as_default;
  // Degree of the polynomial through recorded steps that reads a line's past between them
  // (DelayHistory): the method's order less one, at least linear, so the history is as
  // accurate as the steps. (The event method reads its exact past instead.)
  int history_degree = 1;
  // Whether the method can integrate this circuit; null: every circuit. On false, *why says
  // which element stops it and what to use instead (event: an SFFM source, source_system.h).
  std::function<bool(const LcsProblem&, std::string* why)> applies;
  // Adaptive methods that locate switch changes (S, W) themselves: one guarded method per
  // configuration of the switches (guarded_method.h, switched_adaptive.h). Fixed-step methods
  // handle switches by interpolation (transient.cpp); where an adaptive method cannot, its
  // `applies` says so.
  std::function<std::unique_ptr<GuardedMethod>(const LcsProblem&, const MethodOptions&)> make_guarded;

  bool adaptive() const { return static_cast<bool>(make_continuous); }
  bool fixed_step() const { return static_cast<bool>(make_stepper); }
};

const std::vector<MethodEntry>& method_registry();
const MethodEntry* find_method(const std::string& name);  // nullptr when unknown
std::string method_names();                                // "euler, event, ..."
const MethodEntry& default_method();                       // the entry with is_default
const MethodEntry& fixed_step_default_method();            // the entry with is_fixed_step_default
// `run` without a method (SPEC §1: event wherever it applies): the default method if it serves
// this circuit, else the fixed-step default with *why saying why the default does not apply.
const MethodEntry& default_method_for(const LcsProblem& model, std::string* why);
const MethodEntry& exact_reference_method();               // the entry with exact_reference
const MethodEntry* smooth_reference_method();  // the entry with smooth_reference; nullptr: none

// `.options method=NAME` of a SPICE deck: a registry name, or one of ngspice's: trap and
// trapezoidal (the theta method at theta 0.5) and gear (no equivalent here: entry null, gear set).
// entry null and gear false: unknown.
struct SpiceMethod {
  const MethodEntry* entry = nullptr;
  std::optional<double> theta;  // the theta the name implies (trap: 0.5)
  bool gear = false;
};
SpiceMethod find_spice_method(const std::string& name);
std::string spice_method_names();  // method_names() and the ngspice names accepted: "..., trap"

}  // namespace lcs
