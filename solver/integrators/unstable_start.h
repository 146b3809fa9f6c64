// Whether a transient starts at an unstable equilibrium. The operating point is an equilibrium
// of the circuit in its mode there (the pairs that conduct, Stewart 8.3.1); when that mode's
// dynamics dx/dt = Ax x + ... has an eigenvalue with Re λ > 0, a deviation grows as e^(Re λ t).
// A symmetric astable multivibrator at its both-saturated point is one: every simulator leaves
// it only where the sources push it or rounding does, and where rounding does, when and which
// way is arbitrary. The user is told, and told how to make the answer reproducible.
#pragma once

#include <optional>
#include <string>

#include "solver/model/circuit_model.h"
#include "solver/model/initial_state.h"

namespace lcs {

struct UnstableStartOptions {
  // Growth that makes rounding visible within the run: e^36 * 1e-16 ~ 0.4 of a state's size.
  double visible_growth = 36;
  // Modes are checked up to this many states (the eigenvalues of a dense n x n matrix).
  int max_states = 200;
};

// The warning, or nothing (stable, not an operating point start, or a circuit too large to check).
std::optional<std::string> unstable_start_warning(const CircuitModel& model, const InitialState& init,
                                                  bool uic, double t0, double tstop,
                                                  const UnstableStartOptions& options = {});

}  // namespace lcs
