// `validate` and `bench` load libngspice before any other work. A library that cannot be loaded
// is a fault of the installation, like a missing gnuplot: exit 1 with the loader's reasons.
#pragma once

#include <string>

#include "cli/exit_codes.h"
#include "ngspice/ngspice_session.h"

namespace lcs {

// `who_needs_it`: the start of the message, "validate needs ngspice".
inline void require_ngspice(const std::string& who_needs_it) {
  try {
    require_ngspice_library();
  } catch (const NgspiceError& e) {
    throw CliError(kExitUsage, "lcspice: error: " + who_needs_it + ": " + e.what());
  }
}

}  // namespace lcs
