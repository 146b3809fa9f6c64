// LTspice's instance parasitics on L, C and V cards (`L1 a b 10u Rser=0.05 Rpar=10k Cpar=2p`,
// `C1 a b 100u Rser=10m Lser=5n`, `V1 a b SINE(0 5 1k) Rser=1 Cpar=1n`): each is read as its
// own element beside the card's, named after it with the parasitic's suffix ("l1#rser"). The
// series ones (Rser, then Lser) sit between the card's first node and the element, through
// internal nodes of the same names; the parallel ones (Rpar, Cpar) across the card's two nodes,
// the whole series combination, as LTspice's inductor model puts them. i(l1) stays the current
// of the ideal element. A name with '#' is the circuit's inner detail: nodes and elements so
// named are left out of the default probes (SPEC §3 lists the netlist's own). A value of 0 for
// Rser, Lser or Cpar means none, as in LTspice; Rpar must be positive. Internal to the reader.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "netlist/lexer.h"
#include "netlist/netlist.h"
#include "netlist/param_scope.h"

namespace lcs::parse {

struct InstanceParasitics {
  std::optional<double> rser, lser, rpar, cpar;
  bool any() const { return rser || lser || rpar || cpar; }
};

// Whether an element of `kind` takes the parasitic `lower_key` (rser, lser, rpar, cpar).
bool takes_parasitic(ElementKind kind, const std::string& lower_key);

// Reads `KEY = value` at token i when `kind` takes KEY; returns the token past the value, or i
// when KEY is not one of its parasitics. `name` (flat) is for messages. Throws NetlistError.
std::size_t read_parasitic(const Card& card, std::size_t i, ElementKind kind, const ParamScope& scope,
                           const std::string& name, InstanceParasitics& out);

// The elements `p` adds beside `e` (after e's own multiplier is applied; `m` scales them the same
// way), moving e's first node onto the series chain's last internal node.
std::vector<Element> expand_parasitics(Element& e, const InstanceParasitics& p, double m);

}  // namespace lcs::parse
