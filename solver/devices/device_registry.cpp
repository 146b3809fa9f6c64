#include "solver/devices/device_registry.h"

#include "solver/devices/bjt.h"
#include "solver/devices/capacitor.h"
#include "solver/devices/controlled_source.h"
#include "solver/devices/coupling.h"
#include "solver/devices/diode.h"
#include "solver/devices/independent_source.h"
#include "solver/devices/inductor.h"
#include "solver/devices/resistor.h"
#include "solver/devices/switch.h"
#include "solver/devices/transmission_line.h"

namespace lcs {

namespace {
template <class D>
std::unique_ptr<Device> make(const Element& e, const Netlist& n, const DeviceOptions& o) {
  return std::make_unique<D>(e, n, o);
}
}  // namespace

const std::vector<DeviceEntry>& device_registry() {
  static const std::vector<DeviceEntry> table = {
      {'c', ElementKind::Capacitor, "capacitor", make<Capacitor>},
      {'d', ElementKind::Diode, "diode", make<Diode>},
      {'e', ElementKind::Vcvs, "voltage-controlled voltage source", make<ControlledSource>},
      {'f', ElementKind::Cccs, "current-controlled current source", make<ControlledSource>},
      {'g', ElementKind::Vccs, "voltage-controlled current source", make<ControlledSource>},
      {'h', ElementKind::Ccvs, "current-controlled voltage source", make<ControlledSource>},
      {'i', ElementKind::CurrentSource, "current source", make<IndependentSource>},
      {'k', ElementKind::Coupling, "coupling", make<Coupling>},
      {'l', ElementKind::Inductor, "inductor", make<Inductor>},
      {'o', ElementKind::LossyLine, "lossy transmission line", make<TransmissionLine>},
      {'q', ElementKind::Bjt, "bipolar transistor", make<Bjt>},
      {'r', ElementKind::Resistor, "resistor", make<Resistor>},
      {'s', ElementKind::VSwitch, "voltage-controlled switch", make<Switch>},
      {'t', ElementKind::Line, "transmission line", make<TransmissionLine>},
      {'v', ElementKind::VoltageSource, "voltage source", make<IndependentSource>},
      {'w', ElementKind::CSwitch, "current-controlled switch", make<Switch>},
  };
  return table;
}

std::unique_ptr<Device> make_device(const Element& element, const Netlist& netlist,
                                    const DeviceOptions& options) {
  for (const DeviceEntry& entry : device_registry())
    if (entry.kind == element.kind) return entry.make(element, netlist, options);
  throw NetlistError(element.loc, "element " + element.name + ": no device simulates this kind");
}

std::vector<std::shared_ptr<Device>> make_devices(const Netlist& netlist, const DeviceOptions& options) {
  std::vector<std::shared_ptr<Device>> devices;
  for (size_t e = 0; e < netlist.elements.size(); ++e) {
    devices.push_back(make_device(netlist.elements[e], netlist, options));
    devices.back()->set_element_index(static_cast<int>(e));
  }
  return devices;
}

CircuitGraph graph_of_devices(const std::vector<std::shared_ptr<Device>>& devices) {
  CircuitGraph g;
  for (size_t d = 0; d < devices.size(); ++d)
    for (const BranchDecl& b : devices[d]->branches())
      g.add_branch(devices[d]->element_index(), b.name, b.cls, b.from, b.to);
  return g;
}

}  // namespace lcs
