// An lcspice netlist as an ngspice deck with smooth (Shockley) diodes: the witness that
// `lcspice validate` compares against. Each device writes its own cards (Device::ngspice); the
// translation as a whole is:
//
//  - Ideal diode (VON, RON) -> a voltage source VON in series with a Shockley diode of emission
//    coefficient N (default 0.05), IS (default 1e-14) and RS = RON:
//        anode --[+ VON -]-- mid --|>|-- cathode
//    As N -> 0 the Shockley curve tends to the ideal one; the two differ by about
//    N*Vt*ln(i/IS) per conducting junction (the "model gap"). The threshold source doubles as
//    the diode's ammeter.
//  - Diode cards that give smooth parameters (IS, N or RS) keep them, behind a 0 V ammeter: the
//    comparison is then lcspice's ideal law (VON/RON, or the chord fitted to the card) against
//    the card's own Shockley diode.
//  - R, L (IC=), C (IC=), K, V and I (DC, SIN, PULSE, PWL) are written as they are, with their
//    flattened names (an element `r1` of instance `x1` becomes `r_x1.r1`: ngspice reads the
//    element type from the first letter). A PULSE edge of zero length, a jump for lcspice (which
//    ngspice would silently replace by TSTEP), becomes an edge of 1e-6 TSTOP that ends at the
//    jump instant, so both agree at the instant itself, where lcspice reports the value after
//    the jump (shorter edges are lost to ngspice's breakpoint resolution).
//  - IC= on elements without UIC (lcspice applies it, ngspice would not): the deck gets UIC and
//    IC= on every capacitor and inductor from lcspice's initial state (initial_conditions).
//  - Names the translation makes up (threshold sources, ammeters, their nodes) are made unique
//    against the netlist's own names.
//  - Every probed current other than a voltage source's gets a 0 V ammeter in series, so
//    i(element) is read from the ammeter's branch current (same direction as SPEC §3).
//  - `.tran TSTEP TSTOP TSTART TMAX [UIC]` with TMAX = max_step, or TSTEP unless the netlist
//    gives a smaller one (ngspice's default maximum step, (TSTOP-TSTART)/50, gives wrong answers
//    with sharp diodes; `validate` passes its output interval), `.ic` as it is, `.options` from
//    TranslationOptions.
#pragma once

#include <map>
#include <set>
#include <string>
#include <vector>

#include "solver/devices/device.h"
#include "solver/model/circuit_model.h"

namespace lcs {

struct TranslationOptions {
  double emission = 0.05;            // N of the Shockley diodes standing in for ideal ones
  double saturation_current = 1e-14; // IS of those diodes
  double max_step = 0;               // ngspice TMAX; 0: TSTEP (or the netlist's smaller TMAX)
  double tstop = 0;                  // ngspice TSTOP; 0: the netlist's (sources are written as
                                     // the netlist gives them either way)
  std::vector<std::string> options;  // extra `.options` words, e.g. "reltol=1e-4"
  // Test hooks, in the deck only (`validate` must fail): diodes written anode/cathode swapped,
  // with their series resistance scaled, or left out (open).
  std::set<std::string> reversed_diodes, open_diodes;
  std::map<std::string, double> ron_factor;
  // When set, ngspice starts from these capacitor voltages / inductor currents (by element name)
  // with UIC: lcspice's own initial state, for netlists whose IC= ngspice would ignore without UIC.
  std::map<std::string, double> initial_conditions;
  // ... and these lines from their port voltages and currents (v1, i1, v2, i2; by element name).
  std::map<std::string, std::array<double, 4>> line_initial_conditions;
  // When set, `.nodeset` of these node voltages (by node name): ngspice seeks its own operating
  // point from lcspice's, for circuits with several (no UIC: its start is then its own).
  std::map<std::string, double> nodesets;
  // When set, `.ic` of these node voltages (no UIC): ngspice's operating point held there, its
  // t = 0 row that point, released after (where `.nodeset` let it settle elsewhere).
  std::map<std::string, double> node_holds;
};

struct TranslatedDeck {
  std::vector<std::string> lines;            // title first, `.end` last
  double tstop = 0;                          // where its .tran ends
  std::map<std::string, ProbeSource> probes; // by lcspice probe name ("v(a)", "i(d1)")
  std::vector<std::string> ideal_diodes;     // devices whose junctions are threshold source + sharp Shockley
  std::vector<std::string> witnesses;        // what stands in for a device, where it says (transistors)
};

// `model` supplies the diode laws and the probes' elements; `probes` are the lcspice probes the
// comparison needs. Throws std::invalid_argument for a netlist without .tran.
TranslatedDeck translate_to_ngspice(const CircuitModel& model, const std::vector<Probe>& probes,
                                    const TranslationOptions& options);
// The same from the netlist and its devices alone (solver/devices/device_registry.h), with no
// model formed: what `bench --scale` uses, so that an ngspice run does not pay for forming
// lcspice's model of a large circuit.
TranslatedDeck translate_to_ngspice(const Netlist& netlist, const std::vector<std::shared_ptr<Device>>& devices,
                                    const std::vector<Probe>& probes, const TranslationOptions& options);

// The name a node has in the ngspice deck (KiCad's `net-(r1-pad1)` spelled `net-_lp_r1-pad1_rp_`),
// and its vector's name ("0" is not a vector: ground).
std::string ngspice_node_name(const std::string& node);
std::string ngspice_node_vector(const std::string& node);

}  // namespace lcs
