// Probes as written in .print/.save/--probe: v(node), v(node1,node2), i(element), and the
// terminal currents of a transistor ic(q), ib(q), ie(q), and a line's port-2 current i2(t).
#include <algorithm>

#include "netlist/element_card.h"
#include "netlist/lexer.h"
#include "netlist/netlist.h"

namespace lcs {

Probe parse_probe(const std::string& text, const SourceLocation& loc) {
  // Leading and trailing blanks are not part of the probe; the caret goes under the rest.
  std::size_t b = text.find_first_not_of(" \t");
  std::size_t e = text.find_last_not_of(" \t");
  std::string s = b == std::string::npos ? std::string() : text.substr(b, e - b + 1);
  SourceLocation at = loc;
  if (at.column > 0 && b != std::string::npos) at.column += static_cast<int>(b);
  at.length = std::max<int>(1, static_cast<int>(s.size()));

  auto fail = [&]() -> Probe {
    throw NetlistError(at, "invalid probe " + parse::quote(s) +
                               ": expected v(node), v(node1,node2), i(element), ic/ib/ie(transistor) or i2(line)");
  };
  auto blank = [](char c) { return c == ' ' || c == '\t'; };
  auto name_char = [&](char c) { return !blank(c) && c != '(' && c != ')' && c != ',' && c != '=' &&
                                        c != '{' && c != '}' && static_cast<unsigned char>(c) > 0x20; };
  std::string lower = parse::to_lower(s);
  std::size_t i = 0;
  auto skip = [&] {
    while (i < lower.size() && blank(lower[i])) ++i;
  };
  auto name = [&]() {
    skip();
    std::size_t start = i;
    while (i < lower.size() && name_char(lower[i])) ++i;
    i = static_cast<std::size_t>(parse::kicad_net_name_end(lower, static_cast<int>(start), static_cast<int>(i)));
    return lower.substr(start, i - start);
  };
  if (lower.empty() || (lower[0] != 'v' && lower[0] != 'i')) return fail();
  const char kind = lower[i++];
  char terminal = 0;
  if (kind == 'i' && i < lower.size() &&
      (lower[i] == 'c' || lower[i] == 'b' || lower[i] == 'e' || lower[i] == '1' || lower[i] == '2'))
    terminal = lower[i++];
  skip();
  if (i >= lower.size() || lower[i] != '(') return fail();
  ++i;
  std::string a = name();
  if (a.empty()) return fail();
  std::string b2;
  skip();
  if (i < lower.size() && lower[i] == ',') {
    ++i;
    b2 = name();
    if (b2.empty() || kind != 'v') return fail();
    skip();
  }
  if (i >= lower.size() || lower[i] != ')') return fail();
  ++i;
  skip();
  if (i != lower.size()) return fail();

  Probe p;
  p.loc = at;
  auto node = [](const std::string& n) { return parse::is_ground(n) ? std::string("0") : n; };
  if (terminal == '1') {  // i1(t1) is i(t1): a line's port-1 current
    p.kind = Probe::Kind::ElementCurrent;
    p.a = a;
  } else if (terminal) {
    p.kind = Probe::Kind::TerminalCurrent;
    p.a = a;
    p.terminal = terminal;
  } else if (kind == 'i') {
    p.kind = Probe::Kind::ElementCurrent;
    p.a = a;
  } else if (b2.empty()) {
    p.kind = Probe::Kind::NodeVoltage;
    p.a = node(a);
  } else {
    p.kind = Probe::Kind::NodePairVoltage;
    p.a = node(a);
    p.b = node(b2);
  }
  return p;
}

}  // namespace lcs
