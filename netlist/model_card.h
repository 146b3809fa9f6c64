// `.model NAME TYPE [(] params [)]`: diode models (D) and transistor models (NPN, PNP) with ideal
// and smooth parameters; LTRA models are accepted for the cards that will use them and store
// nothing yet.
// Internal to the netlist reader.
#pragma once

#include <string>
#include <vector>

#include "netlist/lexer.h"
#include "netlist/netlist.h"
#include "netlist/param_scope.h"

namespace lcs::parse {

struct ModelCard {
  std::string name;   // lower-case, as written
  std::string type;   // "d", "npn", "pnp" or "ltra"
  DiodeModel diode;   // type "d": name = prefix + name
  BjtModel bjt;       // type "npn" or "pnp": name = prefix + name
  LineModel line;     // type "ltra": name = prefix + name
  SwitchModel sw;     // type "sw", "csw", "vswitch" or "iswitch" (PSpice's, read as SW/CSW): name = prefix + name
  // A type ngspice knows and lcspice does not simulate (NMOS, NUMD, LCOUPLE, ...): kept only to
  // refuse the elements that use it (see out_of_scope.h); `type` is that type, lower-case.
  bool unsimulated = false;
};

// `diode_capacitance` (`.options diodecap`): a diode card's CJO is modelled; otherwise it is read
// (into DiodeModel::cjo, unused) and listed among the ignored parameters, as SPEC §2 has it.
ModelCard parse_model_card(const Card& card, const ParamScope& scope, const std::string& prefix,
                           std::vector<std::string>& warnings, bool diode_capacitance = false);

}  // namespace lcs::parse
