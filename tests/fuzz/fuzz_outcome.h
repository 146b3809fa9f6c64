// What a fuzz target accepts as a normal end of an input: the documented failures (SPEC §4:
// netlist and topology errors, exit 2; numerical failures, exit 3). Anything else that escapes
// (std::logic_error, std::invalid_argument from a solver, a crash, a sanitizer report) is a
// finding: the target aborts so libFuzzer saves the input.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "graph/topology.h"
#include "netlist/source_location.h"
#include "solver/model/numerical_failure.h"

namespace lcs::fuzz {

// Inputs larger than this are skipped: the parser's own bounds are tested elsewhere, and big
// legitimate decks would only slow the search.
constexpr size_t kMaxInputBytes = 4096;
// Model formation is cubic in the branches; larger circuits are skipped for speed.
constexpr size_t kMaxElements = 60;

template <class F>
void run_expecting_documented_errors(F&& body) {
  try {
    body();
  } catch (const NetlistError&) {
  } catch (const FileError&) {
  } catch (const TopologyError&) {
  } catch (const NumericalFailure&) {
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fuzz finding: undocumented exception: %s\n", e.what());
    std::abort();
  }
}

}  // namespace lcs::fuzz
