// Small helpers shared by the netlist reader tests.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "netlist/netlist.h"

namespace lcs::test {

inline Netlist parse(const std::string& text) { return parse_netlist_string(text, "t.cir"); }

// The formatted diagnostic of the NetlistError the text raises, or "<no error>".
inline std::string diag(const std::string& text, const std::string& file = "t.cir") {
  try {
    parse_netlist_string(text, file);
  } catch (const NetlistError& e) {
    return e.formatted();
  }
  return "<no error>";
}

// The probes' names, each followed by a blank ("v(a) i(r1) ").
inline std::string probe_names(const std::vector<Probe>& probes) {
  std::string out;
  for (const Probe& p : probes) out += p.name() + " ";
  return out;
}

inline const Element& element(const Netlist& n, const std::string& name) {
  const Element* e = n.find_element(name);
  if (!e) throw std::runtime_error("no element " + name);
  return *e;
}

}  // namespace lcs::test
