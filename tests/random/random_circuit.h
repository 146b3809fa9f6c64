// Random circuits for the differential test (issue 9): netlist text in the SPEC §2 dialect, a
// function of the seed alone. Every number is drawn as an integer from std::mt19937_64 (whose
// output the standard fixes) and written as an exact decimal, so a seed gives the same deck on
// every platform and compiler.
//
// Shape: 2-7 named nodes and ground, a resistor spanning tree over them (every node has a DC path
// to ground and a unique potential), one voltage source with a random waveform, sometimes a
// current source, extra resistors, capacitors and inductors, 1-6 diodes with their own .model
// (VON in [0, 1] V, RON in [0.01, 100] Ω, never 0) between random nodes or in series with an
// inductor through a node of their own (the "L diode" of Stewart 5.4.4), and a .tran card.
// Time constants are tied to TSTOP (RC and L/R from TSTOP/1000 to TSTOP, LC periods above
// TSTOP/6) so that implicit Euler at TSTOP/20000 resolves what the circuit does.
#pragma once

#include <cstdint>
#include <string>

namespace lcs::random_circuit {

struct Deck {
  std::uint64_t seed = 0;
  int variant = 0;
  std::string text;    // the netlist, ending with .end
  // UIC (a start that need not be consistent) or a source jump (PULSE edge or PWL step of zero
  // length): the circuit may jump or run through a transient as fast as RON C = 1e-8 TSTOP.
  bool rough = false;
};

// The circuit of `seed`. Not every deck is valid (a capacitor across the source is a loop the
// model folds, an inductor across it has no DC operating point): callers discard what model
// formation rejects and take the next variant (`variant` is mixed into the stream).
Deck generate(std::uint64_t seed, int variant = 0);

// An exact decimal m * 10^e written with a SPICE scale suffix: (47, -10) -> "4.7n".
std::string spice_number(std::int64_t mantissa, int exponent);

}  // namespace lcs::random_circuit
