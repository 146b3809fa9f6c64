// Exit codes fixed by SPEC §4.
#pragma once

#include <stdexcept>
#include <string>

namespace lcs {

enum ExitCode : int {
  kExitOk = 0,
  kExitUsage = 1,      // unknown option, missing file
  kExitNetlist = 2,    // netlist or topology error: nothing simulated
  kExitNumerical = 3,  // no solution / step failure: rows so far are kept
  kExitValidate = 4,   // validate: a probe outside tolerance
};

// Thrown by commands with the full text to print on standard error and the exit code.
class CliError : public std::runtime_error {
 public:
  CliError(int code, const std::string& text) : std::runtime_error(text), code_(code) {}
  int code() const { return code_; }

 private:
  int code_;
};

}  // namespace lcs
