// The differential check of one random circuit (issue 9): every registered method runs it, every
// run must end normally (or in a documented failure) with well-formed rows, and each method's
// waveforms must agree with the exact event-driven reference within the tolerance its row of
// kMethodTolerances states (differential.cpp, where each tolerance is derived).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "tests/random/random_circuit.h"

namespace lcs::random_circuit {

// The first valid variant of a seed's circuit (formation rejects a few: a capacitor across the
// source, a diode forward-biased by it). `discarded` counts the variants rejected on the way.
Deck valid_deck(std::uint64_t seed, int* discarded = nullptr);

struct MethodVerdict {
  std::string method;
  bool compared = false;        // agreement was asserted (not: a rough deck for this method)
  double discrepancy = 0;       // the worst probe's mean discrepancy at the last step tried
  std::string worst_probe;
  std::vector<double> history;  // that discrepancy at h, h/2, ... as far as refinement went
  std::string documented_failure;  // a NumericalFailure allowed for this method (exit 3)
};

struct SeedVerdict {
  Deck deck;
  int discarded = 0;
  std::vector<std::string> problems;  // empty: the seed passes
  std::vector<MethodVerdict> methods;
  double seconds = 0;
};

// Runs every check on the seed's circuit. Exceptions other than the documented ones become
// problems, as do malformed rows and discrepancies beyond tolerance.
SeedVerdict check_seed(std::uint64_t seed);

// What a failing seed prints: its problems, the netlist, and how to run it again.
std::string describe_failure(const SeedVerdict& v);

}  // namespace lcs::random_circuit
