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
// Elements after subcircuit expansion. Formation is sparse, so circuits large enough for the
// sparse active-set steps (48 pairs) and the descriptor form (128) are in reach (seeds:
// tests/fuzz/seeds, a few hundred bytes each through nested subcircuits).
constexpr size_t kMaxElements = 300;
// The adaptive methods on such circuits are seconds to minutes of work per deck in the
// instrumented build (a 64-stage multiplier: event 22 s, smooth 41 s in Release), not hangs to
// find: they keep the former bound, and so does every method without large-circuit steps
// (radau; transient_fuzz.cpp).
constexpr size_t kMaxElementsAdaptive = 60;

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
