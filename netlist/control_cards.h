// Dot cards other than .param/.model/.subckt/.include: classification, and the control cards of
// the top level (.tran, .ic, .print/.plot/.save, .options). Internal to the netlist reader.
#pragma once

#include <string>
#include <vector>

#include "netlist/lexer.h"
#include "netlist/netlist.h"
#include "netlist/param_scope.h"

namespace lcs::parse {

enum class DotCard {
  Param,
  Func,      // .func NAME(ARGS) {BODY}: a user function of the scope's expressions
  Model,
  Subckt,
  Ends,
  Tran,
  Ic,
  Nodeset,   // same syntax as .ic: hints that choose among several operating points
  Print,     // .print, .plot
  Save,      // .save, .probe
  Options,   // .options, .option, .opt
  Op,        // accepted silently (and LTspice's `.backanno`, an annotation marker)
  Global,    // .global NODE...: nodes shared by every subcircuit instance
  Title,     // .title text
  Measure,   // .measure, .meas (measure_card.h)
  Ignored,   // analyses and cards lcspice does not run (.ac .dc .noise .tf .four ...): warning
  Endc,      // a stray .endc (the lexer takes .control blocks out)
  Unknown,
};

DotCard classify_dot_card(const std::string& lower_keyword);

// Control cards may only appear at the top level.
bool allowed_in_subcircuit(DotCard kind);

// LTspice's flags after the values: `startup` (supplies ramped up from 0 V over 20 us) is read
// as UIC, a start from rest, with a warning; `steady` and `nodiscard` are warned about and ignored.
TranSpec parse_tran(const Card& card, const ParamScope& scope, std::vector<std::string>& warnings);
// .ic and .nodeset: v(node)=value ...
std::vector<NodeIc> parse_ic(const Card& card, const ParamScope& scope);
// .print/.plot (`tran` or no analysis name: probes; another analysis: ignored with a warning)
// and .save/.probe (`all`, `alli`, `allv` mean the default probes). Entries lcspice does not write
// (expressions such as v(1)*i(r1), power p(x), device parameters @d1[id], FORMAT=) are skipped
// with a warning each. A .print's V(*) or I(*) (Xyce; PSpice's V(alias(*))) asks for every
// voltage and current, lcspice's default probes: `every` is set (the run writes them all, the
// named probes of every card among them).
std::vector<Probe> parse_probe_card(const Card& card, std::vector<std::string>& warnings, bool& every);
void parse_options(const Card& card, const ParamScope& scope, Netlist& netlist);

}  // namespace lcs::parse
