// The operating point of a circuit that steps on its descriptor form (sparse_descriptor.h: a
// Cockcroft–Walton multiplier, whose eliminated LCS is dense): without forming the dense LCS,
// whose static problem costs O(n^3) (a 1000-stage multiplier: 11.7 s against 1.2 s for its whole
// run from rest with UIC, measured with `lcspice run` on the shared machine).
//
// DC on the descriptor is its θ-method system with capacitor currents and inductor voltages set
// to zero. Where capacitors have no DC path or inductors close loops, that system is singular and
// the states it leaves free take the values of least stored energy (operating_point.cpp). One
// implicit-Euler step of length H from rest (x = 0) is the same system with a leak: capacitor b
// carries i = C_b v_b / H, inductor b drops v = L_b i_b / H. Leaks proportional to C and L reach
// least energy in the limit (min sum C_b v_b^2 and sum L_b i_b^2: the DC currents through leaks
// in series are equal, so series capacitors share one charge and parallel inductors split
// inversely to L), and H is chosen so that each leak is 1e-9 of the circuit's largest
// conductance (or resistance), the dense path's regularisation: the answer carries the leaks'
// currents, about 1e-9 of the circuit's, rather than being polished exact.
//
// Taken only where every pair is off, strictly (w > 0): a circuit at rest, or one whose sources
// leave every diode reverse-biased. Then the leaks' limit is the dense path's answer exactly (the
// linear circuit's, least energy on its free states). Where pairs conduct, the dense path decides
// which exactly: at DC many pairs can sit on their threshold at zero current (a charged
// multiplier), and the sparse mode search cycled there.
//
// The states the DC problem leaves free are found by a second step from a random start, well
// inside every pair's margin: a free state follows the start (its leak is all that holds it), a
// determined one moves by about 1e-9 of it.
#pragma once

#include "solver/model/circuit_model.h"
#include "solver/model/operating_point.h"

namespace lcs {

// False (the dense path decides) when the circuit has no descriptor form, a pair is on or at its
// threshold, or the sparse solve fails.
bool descriptor_operating_point(const CircuitModel& model, double t, OperatingPoint& op);

}  // namespace lcs
