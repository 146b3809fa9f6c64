#include "solver/integrators/method_registry.h"

#include "solver/integrators/smooth_method.h"
#include "solver/integrators/theta_method.h"

namespace lcs {

const std::vector<MethodEntry>& method_registry() {
  static const std::vector<MethodEntry> table = {
      {"euler", "implicit Euler (theta = 1), fixed step, one LCP per step",
       [](const CircuitModel& m, const MethodOptions&) {
         return std::make_unique<ThetaMethod>(m, 1.0);
       },
       {}},
      {"smooth",
       "Shockley diodes (Stewart 8.2 smoothing) as a DAE, SUNDIALS IDA (variable-order BDF), "
       "--rtol/--atol",
       {},
       [](const CircuitModel& m, const MethodOptions& o) {
         return std::make_unique<SmoothMethod>(m, o);
       }},
      {"theta", "theta-method (--theta, default 0.5: trapezoidal), fixed step, one LCP per step",
       [](const CircuitModel& m, const MethodOptions& o) {
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
