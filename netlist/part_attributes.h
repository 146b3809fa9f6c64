// LTspice's part-database attributes on R, L and C cards (`L1 a b 10u Ipk=2 Rser=0.05
// mfg="Coilcraft" pn="MSS1260-103" type="ferrite"`, `C1 a b 100u V=50 Irms=2 Rser=0.01`,
// `R1 a b 1k tol=1 pwr=0.25`): ratings and part data written into every export that picked a
// part from LTspice's database. They do not change LTspice's simulation and do not change this
// one: skipped, named in one warning per card. Internal to the reader.
#pragma once

#include <string>
#include <vector>

#include "netlist/lexer.h"
#include "netlist/netlist.h"

namespace lcs::parse {

// Skips `KEY = value` at token i when KEY is a part attribute of `kind` (adding KEY as written
// to `skipped`); returns the token past the value, or i when it is not one.
std::size_t skip_part_attribute(const Card& card, std::size_t i, ElementKind kind, std::vector<std::string>& skipped);

// The warning for a card's skipped attributes (none: empty).
std::string part_attributes_warning(const std::string& name, const std::vector<std::string>& skipped);

}  // namespace lcs::parse
