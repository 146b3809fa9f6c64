#include "netlist/parallel_copies.h"

namespace lcs::parse {

void scale_for_parallel_copies(Element& e, double m) {
  if (m == 1.0) return;
  switch (e.kind) {
    case ElementKind::Resistor:
    case ElementKind::Inductor:
      e.value /= m;
      break;
    case ElementKind::Capacitor:
      e.value *= m;
      break;
    case ElementKind::Diode:
    case ElementKind::Bjt:  // area (0: not written, 1)
      e.value = (e.value > 0 ? e.value : 1.0) * m;
      break;
    case ElementKind::CurrentSource:
      e.waveform = e.waveform.scaled(m);
      break;
    case ElementKind::Vccs:  // m copies of a controlled current source: m times the current
    case ElementKind::Cccs:
      e.value *= m;
      break;
    case ElementKind::Vcvs:  // controlled voltage sources and switches: as ngspice, unscaled
    case ElementKind::Ccvs:
    case ElementKind::VSwitch:
    case ElementKind::CSwitch:
    case ElementKind::Coupling:
    case ElementKind::VoltageSource:
    case ElementKind::Line:
    case ElementKind::LossyLine:
      break;
  }
}

}  // namespace lcs::parse
