// The named table of integration methods (`--method NAME`), sorted by name.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "solver/integrators/continuous_method.h"
#include "solver/integrators/time_stepper.h"

namespace lcs {

struct MethodOptions {
  double theta = 0.5;  // `--theta`, used by "theta"
  // `--rtol`, `--atol` of the adaptive methods; 0 means the method's default (event: rtol 1e-13
  // on event times; smooth: rtol 1e-6, atol 1e-9 as in SUNDIALS' weighted norm).
  double rtol = 0, atol = 0;
};

// Exactly one of make_stepper (fixed-step time-stepping, one LCP per step) and make_continuous
// (methods that choose their own steps and output times) is set.
struct MethodEntry {
  std::string name;
  std::string description;
  std::function<std::unique_ptr<TimeStepper>(const LcsProblem&, const MethodOptions&)>
      make_stepper;
  std::function<std::unique_ptr<ContinuousMethod>(const LcsProblem&, const MethodOptions&)>
      make_continuous;
  bool adaptive() const { return static_cast<bool>(make_continuous); }
};

const std::vector<MethodEntry>& method_registry();
const MethodEntry* find_method(const std::string& name);  // nullptr when unknown
std::string method_names();                                // "euler, event, ..."

}  // namespace lcs
