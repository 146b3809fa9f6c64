// The `.options` values lcspice reads, read once and validated. Unknown option names are
// accepted (and ignored) as before; a bad value of a known one is a netlist error at its entry.
#pragma once

#include <optional>
#include <string>

#include "netlist/netlist.h"

namespace lcs {

struct NetlistOptions {
  // `.options ifit=`: the diode fit current in amperes (a SPICE number, 10m), > 0 and finite.
  // nullopt: not given (callers use their own default, 10 mA).
  std::optional<double> ifit;
  // `.options method=`: a method registry name; "" when not given. trap and trapezoidal are the
  // theta method with theta 0.5; gear leaves it "" and sets `gear` for the caller to warn.
  std::string method;
  bool gear = false;
  // `.options theta=` in [0, 1] (trap: 0.5; an explicit theta= wins); nullopt: not given.
  std::optional<double> theta;
  // `.options bjtcap=`: a base–emitter capacitance [F] for every transistor (Stewart 5.4.7's
  // physical regularisation), over the cards' CJE; >= 0 and finite. nullopt: not given.
  std::optional<double> bjtcap;
  // `.options diodecap` (diodecap=1; diodecap=0: off): each diode's CJO as a capacitance across
  // its junction (model_card.h). Off by default: SPEC §2 lists CJO as ignored.
  bool diodecap = false;

  bool IsValid(std::string* why) const;
};

// Throws NetlistError located at the offending `.options` entry (netlist.option_locs):
//   "unknown method 'NAME' (known: euler, ..., trap)"
//   ".options theta must be a number in [0, 1]"
//   ".options ifit must be a positive number of amperes"
//   ".options bjtcap must be a capacitance in farads, not negative"
//   ".options diodecap takes no value, or 0 or 1"
NetlistOptions read_netlist_options(const Netlist& netlist);

}  // namespace lcs
