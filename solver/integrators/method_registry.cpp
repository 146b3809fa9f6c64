#include "solver/integrators/method_registry.h"

#include "solver/integrators/event_driven.h"
#include "solver/integrators/radau_iia.h"
#include "solver/integrators/smooth_method.h"
#include "solver/integrators/theta_method.h"

namespace lcs {

const std::vector<MethodEntry>& method_registry() {
  static const std::vector<MethodEntry> table = {
      {"euler", "implicit Euler (theta = 1), fixed step, one LCP per step",
       [](const LcsProblem& m, const MethodOptions&) {
         return std::make_unique<ThetaMethod>(m, 1.0);
       },
       {}},
      {"event",
       "event-driven: exact matrix exponentials inside each mode, events located by bisection "
       "(--rtol on event times, default 1e-13), next mode from a tiny-step LCP",
       {},
       [](const LcsProblem& m, const MethodOptions& o) {
         EventOptions e;
         if (o.rtol > 0) e.rtol = o.rtol;
         return std::make_unique<EventDriven>(m, e);
       }},
      {"radau3", "Radau IIA, 2 stages (order 3), fixed step, one LCP of size 2m per step",
       [](const LcsProblem& m, const MethodOptions&) {
         return std::make_unique<RadauIIA>(m, 2);
       },
       {}},
      {"radau5", "Radau IIA, 3 stages (order 5), fixed step, one LCP of size 3m per step",
       [](const LcsProblem& m, const MethodOptions&) {
         return std::make_unique<RadauIIA>(m, 3);
       },
       {}},
      {"smooth",
       "Shockley diodes (Stewart 8.2 smoothing) as a DAE, SUNDIALS IDA (variable-order BDF), "
       "--rtol/--atol",
       {},
       [](const LcsProblem& m, const MethodOptions& o) {
         return std::make_unique<SmoothMethod>(m, o);
       }},
      {"theta", "theta-method (--theta, default 0.5: trapezoidal), fixed step, one LCP per step",
       [](const LcsProblem& m, const MethodOptions& o) {
         return std::make_unique<ThetaMethod>(m, o.theta);
       },
       {}},
  };
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

}  // namespace lcs
