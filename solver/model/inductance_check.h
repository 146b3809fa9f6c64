// Mutual couplings that no set of real windings can have. Each K card is checked on its own at
// parse time (|k| <= 1, netlist/element_card.cpp); an inductor coupled to two or more others can
// still be impossible: three windings with k12 = k13 = 0.9 and k23 = -0.9 have an inductance
// matrix with a negative eigenvalue, stored energy 1/2 i^T L i < 0 for some currents, and a
// "solution" that grows without bound. ngspice refuses the same systems ("The Inductive System
// consisting of ... is not positive definite").
#pragma once

#include "netlist/netlist.h"

namespace lcs {

// For every group of inductors joined by couplings, the inductance matrix L = D K D (D = diag
// sqrt(L_i), K the coupling coefficients with 1 on the diagonal) must be positive semidefinite;
// it has the inertia of K (Sylvester), so K is what is examined. Semidefinite is allowed: a
// flux-free current pattern is the perfect coupling that perfect_coupling.h reduces. Throws
// TopologyError naming the couplings and inductors of the first group that fails.
void check_inductance_matrices(const Netlist& netlist);

// Smallest eigenvalue below which K counts as indefinite (K has ones on its diagonal).
constexpr double kIndefiniteTolerance = 1e-12;

}  // namespace lcs
