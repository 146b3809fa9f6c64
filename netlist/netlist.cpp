#include "netlist/netlist.h"

namespace lcs {

const char* element_kind_name(ElementKind kind) {
  switch (kind) {
    case ElementKind::Resistor: return "resistor";
    case ElementKind::Inductor: return "inductor";
    case ElementKind::Capacitor: return "capacitor";
    case ElementKind::Coupling: return "coupling";
    case ElementKind::VoltageSource: return "voltage source";
    case ElementKind::CurrentSource: return "current source";
    case ElementKind::Diode: return "diode";
    case ElementKind::Bjt: return "bipolar transistor";
    case ElementKind::Line: return "transmission line";
    case ElementKind::LossyLine: return "lossy transmission line";
    case ElementKind::Vcvs: return "voltage-controlled voltage source";
    case ElementKind::Vccs: return "voltage-controlled current source";
    case ElementKind::Cccs: return "current-controlled current source";
    case ElementKind::Ccvs: return "current-controlled voltage source";
    case ElementKind::VSwitch: return "voltage-controlled switch";
    case ElementKind::CSwitch: return "current-controlled switch";
  }
  return "element";
}

SourceLocation MeasureExpression::location_of(const Name& n) const {
  SourceLocation at = loc;
  const std::size_t column = loc.column > 0 ? static_cast<std::size_t>(loc.column - 1) : std::string::npos;
  if (n.offset == std::string::npos || column == std::string::npos ||
      loc.line_text.compare(column, text.size(), text) != 0)
    return at;
  at.column = static_cast<int>(column + n.offset + 1);
  at.length = static_cast<int>(n.name.size());
  return at;
}

const char* measure_kind_name(Measure::Kind kind) {
  switch (kind) {
    case Measure::Kind::Avg: return "AVG";
    case Measure::Kind::Rms: return "RMS";
    case Measure::Kind::Min: return "MIN";
    case Measure::Kind::Max: return "MAX";
    case Measure::Kind::Pp: return "PP";
    case Measure::Kind::Integ: return "INTEG";
    case Measure::Kind::MinAt: return "MIN_AT";
    case Measure::Kind::MaxAt: return "MAX_AT";
    case Measure::Kind::FindAt: return "FIND AT";
    case Measure::Kind::FindWhen: return "FIND WHEN";
    case Measure::Kind::When: return "WHEN";
    case Measure::Kind::TrigTarg: return "TRIG/TARG";
    case Measure::Kind::Param: return "PARAM";
  }
  return "measure";
}

std::string Probe::name() const {
  if (!label.empty()) return label;
  switch (kind) {
    case Kind::NodeVoltage: return "v(" + a + ")";
    case Kind::NodePairVoltage: return "v(" + a + "," + b + ")";
    case Kind::ElementCurrent: return "i(" + a + ")";
    case Kind::TerminalCurrent: return std::string("i") + terminal + "(" + a + ")";
  }
  return a;
}

const Element* Netlist::find_element(const std::string& lower_name) const {
  for (const Element& e : elements)
    if (e.name == lower_name) return &e;
  return nullptr;
}

}  // namespace lcs
