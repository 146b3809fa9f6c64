// The named table of integration methods (`--method NAME`), sorted by name.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "solver/integrators/time_stepper.h"

namespace lcs {

struct MethodOptions {
  double theta = 0.5;  // `--theta`, used by "theta"
};

struct MethodEntry {
  std::string name;
  std::string description;
  std::function<std::unique_ptr<TimeStepper>(const CircuitModel&, const MethodOptions&)> make;
};

const std::vector<MethodEntry>& method_registry();
const MethodEntry* find_method(const std::string& name);  // nullptr when unknown
std::string method_names();                                // "euler, theta"

}  // namespace lcs
