// The devices lcspice simulates, one row per element kind, sorted by card letter (the way
// ngspice lists its devices in devices/dev.c and Gnucap registers apps/d_*.cc).
#pragma once

#include <functional>
#include <memory>
#include <vector>

#include "solver/devices/device.h"

namespace lcs {

struct DeviceEntry {
  char letter;        // the card letter
  ElementKind kind;   // what the netlist reader made of that letter
  const char* name;   // "resistor", ...
  std::function<std::unique_ptr<Device>(const Element&, const Netlist&, const DeviceOptions&)> make;
};

const std::vector<DeviceEntry>& device_registry();

// The device of one netlist element. Throws NetlistError (at the card) for an element kind no
// device handles.
std::unique_ptr<Device> make_device(const Element& element, const Netlist& netlist,
                                    const DeviceOptions& options);

// Every element of the netlist as a device, in card order.
std::vector<std::shared_ptr<Device>> make_devices(const Netlist& netlist, const DeviceOptions& options);

// The circuit graph of the devices' branches (node "0" first, then nodes in order of appearance).
CircuitGraph graph_of_devices(const std::vector<std::shared_ptr<Device>>& devices);

}  // namespace lcs
