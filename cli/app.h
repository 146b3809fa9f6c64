#pragma once

namespace lcs {
// The `lcspice` program: parses the command line, runs a subcommand, maps errors to SPEC §4 codes.
int run_cli(int argc, char** argv);
}  // namespace lcs
