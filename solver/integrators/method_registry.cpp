#include "solver/integrators/method_registry.h"

#include <functional>
#include <stdexcept>

#include "solver/integrators/event_driven.h"
#include "solver/integrators/source_system.h"
#include "solver/integrators/radau_iia.h"
#include "solver/integrators/smooth_method.h"
#include "solver/integrators/theta_method.h"
#include "solver/model/dense_budget.h"
#include "solver/model/switch_family.h"

namespace lcs {

namespace {

// The event method caches a dense exponential per mode and step (O(n^2) memory, O(n^3) time
// each), so its cost grows like N^2.5 in the pairs: `lcspice bench --scale rectifiers --sizes
// 16,32,64,128 --methods event,euler --no-ngspice` measured 0.16, 0.57, 2.6 and 15 CPU s per
// simulated second (90 MB at 128) against euler's 0.014-0.14. Up to 128 pairs the exact answer
// is worth that; above it `run` takes the fixed-step default unless asked. Circuits with lines
// take it too: `/usr/bin/time lcspice run circuits/tline_*.cir --method M` measured 0.25-2.7 s
// for event against 0.01-0.03 s for euler (ltra4_1_line.sp of ngspice's examples: 11 s of
// event steps after the refit).
constexpr int kEventDefaultMaxPairs = 128;

using StepperFactory = decltype(MethodEntry::make_stepper);
using ContinuousFactory = decltype(MethodEntry::make_continuous);

MethodEntry fixed_step(const std::string& name, const std::string& description, StepperFactory make) {
  MethodEntry e;
  e.name = name;
  e.description = description;
  e.make_stepper = std::move(make);
  e.bench_sweep = BenchSweep::StepSize;
  return e;
}

MethodEntry adaptive(const std::string& name, const std::string& description, ContinuousFactory make) {
  MethodEntry e;
  e.name = name;
  e.description = description;
  e.make_continuous = std::move(make);
  e.bench_sweep = BenchSweep::Tolerance;
  return e;
}

// Methods that work on the dense LCS (dense_budget.h) refuse a circuit whose dense working set,
// `copies` matrices of (n + m)^2 numbers, is over the budget, unless `steps_sparse` says they
// work on this circuit's sparse form instead.
void limit_dense(MethodEntry& e, int copies, std::function<bool(const LcsProblem&)> steps_sparse) {
  auto inner = std::move(e.applies);
  e.applies = [inner, copies, steps_sparse](const LcsProblem& m, std::string* why) {
    if (inner && !inner(m, why)) return false;
    if (steps_sparse && steps_sparse(m)) return true;
    if (dense_within_budget(m.state_count(), m.pair_count(), copies)) return true;
    if (why)
      *why = dense_budget_reason(m.state_count(), m.pair_count(), copies) +
             (steps_sparse ? "" : "; methods euler and theta step on the sparse circuit");
    return false;
  };
}

std::vector<MethodEntry> make_table() {
  std::vector<MethodEntry> table;

  MethodEntry euler = fixed_step(
      "euler", "implicit Euler (theta = 1), fixed step, one LCP per step",
      [](const LcsProblem& m, const MethodOptions& o) { return std::make_unique<ThetaMethod>(m, 1.0, o.sparse); });
  euler.is_fixed_step_default = true;
  euler.large_circuit_steps = true;
  table.push_back(euler);

  auto make_event = [](const LcsProblem& m, const MethodOptions& o) {
    EventOptions e;
    if (o.rtol > 0) e.rtol = o.rtol;
    e.history_series = o.history_series;
    if (o.event_mode_cache_bytes > 0) e.mode_cache_bytes = o.event_mode_cache_bytes;
    return std::make_unique<EventDriven>(m, e);
  };
  MethodEntry event = adaptive(
      "event",
      "event-driven: exact matrix exponentials inside each mode, events (mode and switch changes) "
      "located by bisection (--rtol on event times, default 1e-13), next mode from a tiny-step LCP",
      make_event);
  event.make_guarded = make_event;
  event.exact_reference = true;
  event.is_default = true;
  event.serves_as_default = [](const LcsProblem& m, std::string* why) {
    if (m.has_history()) {
      if (why)
        *why = "transmission lines: the event method's exact line history took 5 to 23 times "
               "implicit Euler's time on circuits/tline_*.cir, 800 times on ngspice's ltra4_1_line.sp";
      return false;
    }
    if (m.pair_count() <= kEventDefaultMaxPairs) {
      // A dense exponential costs O(n^3) whatever the pairs: an RC line of 3000 sections with
      // one diode ran for minutes; 256 states and pairs are the 128 rectifiers measured above.
      if (m.state_count() + m.pair_count() <= 2 * kEventDefaultMaxPairs) return true;
      if (why)
        *why = std::to_string(m.state_count()) + " states and " + std::to_string(m.pair_count()) +
               " pairs, more than the " + std::to_string(2 * kEventDefaultMaxPairs) +
               " up to which the event method's dense exponentials stay cheap";
      return false;
    }
    if (why)
      *why = std::to_string(m.pair_count()) + " complementarity pairs, more than the " +
             std::to_string(kEventDefaultMaxPairs) + " up to which the event method's dense "
             "exponentials stay cheap";
    return false;
  };
  event.history_degree = 4;
  event.applies = [](const LcsProblem& problem, std::string* why) {
    return event_method_applies(problem.inputs(), why);
  };
  table.push_back(event);

  MethodEntry radau3 = fixed_step(
      "radau3", "Radau IIA, 2 stages (order 3), fixed step, one LCP of size 2m per step",
      [](const LcsProblem& m, const MethodOptions&) { return std::make_unique<RadauIIA>(m, 2); });
  radau3.history_degree = 2;
  table.push_back(radau3);
  MethodEntry radau5 = fixed_step(
      "radau5", "Radau IIA, 3 stages (order 5), fixed step, one LCP of size 3m per step",
      [](const LcsProblem& m, const MethodOptions&) { return std::make_unique<RadauIIA>(m, 3); });
  radau5.history_degree = 4;
  table.push_back(radau5);

  MethodEntry smooth = adaptive(
      "smooth",
      "Shockley diodes (Stewart 8.2 smoothing) as a DAE, SUNDIALS IDA (variable-order BDF), "
      "--rtol/--atol",
      [](const LcsProblem& m, const MethodOptions& o) { return std::make_unique<SmoothMethod>(m, o); });
  smooth.smooth_model = true;
  // Linear: the history holds IDA's steps and its interpolant on the TSTEP grid (smooth_method.cpp),
  // samples with IDA's local error each; a degree-4 interpolant through steps 1e-16 s apart
  // turned that noise into an input IDA chased with ever smaller steps (tline_clamp_receiver).
  smooth.history_degree = 1;
  smooth.smooth_reference = true;
  smooth.make_guarded = [](const LcsProblem& m, const MethodOptions& o) {
    return std::make_unique<SmoothMethod>(m, o);
  };
  // Switch guards are IDA root functions: a circuit without states has no IDA run.
  smooth.applies = [](const LcsProblem& problem, std::string* why) {
    const auto* circuit = dynamic_cast<const CircuitModel*>(&problem);
    if (!circuit || problem.state_count() > 0) return true;
    const SwitchFamily switches(*circuit);
    if (switches.empty()) return true;
    if (why)
      *why = "switch " + switches.switches().front().name +
             ": the smooth method locates switch changes only in a circuit with states (capacitors "
             "or inductors); use --method event, euler, theta, radau3 or radau5";
    return false;
  };
  table.push_back(smooth);

  MethodEntry theta = fixed_step(
      "theta", "theta-method (--theta, default 0.5: trapezoidal), fixed step, one LCP per step",
      [](const LcsProblem& m, const MethodOptions& o) {
        return std::make_unique<ThetaMethod>(m, o.theta, o.sparse, kDescriptorPairs, o.euler_at_switching);
      });
  theta.uses_theta = true;
  theta.large_circuit_steps = true;
  table.push_back(theta);

  // Dense matrices of (n + m)^2 each a method holds at once, about: event the LCS, a mode's
  // exponential and its dynamics; Radau IIA with s stages its s(n + m) stage system and factors;
  // smooth the LCS, IDA's Jacobian and its LU; the θ-method's dense step the LCS, Phi, W^-1 B, C Phi.
  // The θ-method steps on a sparse LCS or a descriptor form (theta_method.h); smooth on a sparse
  // LCS without lines (its sparse Jacobian and KLU, shockley_dae.h).
  const auto theta_sparse = [](const LcsProblem& m) { return m.sparse_lcs() || m.sparse_descriptor(); };
  const auto smooth_sparse = [](const LcsProblem& m) { return m.sparse_lcs() && !m.has_history(); };
  for (MethodEntry& e : table) {
    if (e.name == "event") limit_dense(e, 3, nullptr);
    else if (e.name == "radau3") limit_dense(e, 2 * 2 + 1, nullptr);
    else if (e.name == "radau5") limit_dense(e, 3 * 3 + 1, nullptr);
    else if (e.name == "smooth") limit_dense(e, 3, smooth_sparse);
    else limit_dense(e, 4, theta_sparse);
  }
  return table;
}

const MethodEntry& the_entry(bool MethodEntry::*trait, const char* what) {
  for (const MethodEntry& e : method_registry())
    if (e.*trait) return e;
  throw std::logic_error(std::string("the method registry has no ") + what);
}

}  // namespace

const std::vector<MethodEntry>& method_registry() {
  static const std::vector<MethodEntry> table = make_table();
  return table;
}

const MethodEntry* find_method(const std::string& name) {
  for (const MethodEntry& e : method_registry())
    if (e.name == name) return &e;
  return nullptr;
}

std::string method_names() {
  std::string out;
  for (const MethodEntry& e : method_registry()) out += (out.empty() ? "" : ", ") + e.name;
  return out;
}

const MethodEntry& default_method() { return the_entry(&MethodEntry::is_default, "default method"); }

const MethodEntry& fixed_step_default_method() {
  return the_entry(&MethodEntry::is_fixed_step_default, "fixed-step default");
}

const MethodEntry& default_method_for(const LcsProblem& model, std::string* why) {
  const MethodEntry& d = default_method();
  if (d.applies && !d.applies(model, why)) return fixed_step_default_method();
  if (d.serves_as_default && !d.serves_as_default(model, why)) return fixed_step_default_method();
  return d;
}

const MethodEntry& exact_reference_method() {
  return the_entry(&MethodEntry::exact_reference, "exact reference");
}

const MethodEntry* smooth_reference_method() {
  for (const MethodEntry& e : method_registry())
    if (e.smooth_reference) return &e;
  return nullptr;
}

SpiceMethod find_spice_method(const std::string& name) {
  SpiceMethod m;
  if ((m.entry = find_method(name))) return m;
  if (name == "trap" || name == "trapezoidal") {
    m.entry = find_method("theta");
    m.theta = 0.5;
  } else if (name == "gear") {
    m.gear = true;
  }
  return m;
}

std::string spice_method_names() { return method_names() + ", trap"; }

}  // namespace lcs
