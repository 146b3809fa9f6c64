// Devices: the unit of extension (DESIGN.md "Devices"). Every element kind is one device, in one
// file, behind this interface, registered by card letter in device_registry.cpp.
//
// Model formation (circuit_model.cpp) is "collect the devices' stamps, then eliminate":
//  1. branches(): the device's two-terminal branches and their tree class. The graph stays
//     two-terminal; a multi-terminal device is a composite of branches (as Gnucap's d_bjt.model
//     is a circuit of primitives).
//  2. stamp(): its constitutive relations as triplets over branch voltages v_b, branch currents
//     i_b and inputs u_k (so dense or sparse assembly is the assembler's choice); its
//     energy-storing branches with their initial values; its complementarity pairs with their
//     ideal law and smooth curve; its inputs (independent sources now, history sources later).
//  3. delayed inputs and max_step(): a device with history (a transmission line) stamps inputs
//     whose value is a combination of its branch quantities `delay` earlier (Stamps::Delayed);
//     the model keeps their past (DelayHistory) as the integrators accept steps, and no step is
//     longer than max_step().
//  4. ngspice(): its cards in the deck `validate` runs; notes(): what `analyze` says about it.
#pragma once

#include <array>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "graph/circuit_graph.h"
#include "netlist/netlist.h"
#include "solver/model/input_provider.h"
#include "solver/devices/junction_fit.h"
#include "solver/model/pair_law.h"

namespace lcs {

// One branch a device adds to the circuit graph (node names as in the netlist).
struct BranchDecl {
  std::string name;
  BranchClass cls = BranchClass::Resistor;
  std::string from, to;
};

// One term of a constitutive relation  sum(coeff * quantity) = 0.
struct Term {
  enum class Of { Voltage, Current, Input };  // v_b, i_b (b a global branch index), u_k
  Of of = Of::Voltage;
  int index = 0;
  double coeff = 0;
};

// What devices stamp, collected in device order (so branches, inputs and pairs are numbered in
// card order). Plain data: the assembler reads it.
struct Stamps {
  struct Relation { int branch; std::vector<Term> terms; };  // the static equation of `branch`
  struct Storage { int branch; double value; std::optional<double> ic; };  // C [F] or L [H]
  struct Coupling { int branch_a, branch_b; double k; };  // mutual inductance M = k sqrt(La Lb)
  struct Pair { int branch; PairLaw law; };
  std::vector<Relation> relations;
  std::vector<Storage> storage;
  std::vector<Coupling> couplings;
  std::vector<Pair> pairs;
  std::vector<InputSignal> inputs;  // u_1, u_2, ... (u_0 = 1 carries the thresholds VON)
  // History inputs (Stewart 1.3.3, the method of characteristics): u_input(t) is the sum of
  // `wave` (over branch voltages, currents and inputs) at t - delay; `before` its value before
  // the run when it starts from rest (UIC), as the device's IC= says.
  struct Delayed { int input; double delay; std::vector<Term> wave; double before = 0; };
  std::vector<Delayed> delayed;
  // What a device with history is at DC, one relation (sum of terms = 0) per history input: the
  // operating point solves these instead of the waves' delays (a lossless line: v1 = v2,
  // i1 = -i2; a lossy one: its DC two-port).
  std::vector<std::vector<Term>> dc_relations;

  // Adds an input and returns its index k (u_k).
  int input(InputSignal signal) {
    inputs.push_back(std::move(signal));
    return static_cast<int>(inputs.size());
  }
};

// What a device sees while stamping: where its own branches landed in the graph.
struct StampContext {
  const CircuitGraph& graph;
  int first_branch = 0;  // global index of the device's branch 0
  int branch(int local) const { return first_branch + local; }
};

// Where an lcspice probe's value comes from among ngspice's vectors: value = plus - minus
// (minus empty: 0).
struct ProbeSource {
  std::string plus, minus;
};

// What a device needs to write its ngspice cards, and where they go.
struct NgspiceDeckContext {
  double tstop = 0;
  double emission = 0.05;             // N of the Shockley diodes standing in for ideal ones
  double saturation_current = 1e-14;  // their IS
  bool current_probed = false;        // i(device) is probed: it needs an ammeter
  // Test hooks (`validate` must fail on a wrong witness): a diode written anode/cathode swapped,
  // with its series resistance scaled, or left out (an open circuit in its place).
  bool reversed = false;
  double ron_factor = 1.0;
  bool open = false;
  std::optional<double> initial_value;  // UIC start value of a capacitor or inductor
  std::map<std::string, double> branch_initial;  // of a device's inner capacitors, by branch ("q1:cbe")
  std::optional<std::array<double, 4>> line_initial;  // a line's UIC start: v1, i1, v2, i2
  // A name unique in the deck (threshold sources, ammeters, their nodes).
  std::function<std::string(const std::string&)> fresh;
};

struct NgspiceCards {
  std::vector<std::string> lines, models;
  std::map<std::string, ProbeSource> probes;  // by lcspice probe name ("i(d1)")
  bool ideal_diode = false;  // a diode given a threshold source + sharp Shockley junction
  std::string witness;       // what stands in for the device, when `validate` should say so
};

// A complementarity pair whose ideal law is a line fitted to the junction's Shockley curve (a
// card with no VON/RON): diode_refit.h refits it over the currents it carries in the circuit.
struct FittedJunction {
  std::string range_key;   // its entry in DeviceOptions::diode_ranges
  bool breakdown = false;  // its currents are that entry's reverse range (a Zener's pair)
  std::string probe;       // the element or branch whose current i(probe) it is ...
  double sign = 1;         // ... times this
  DiodeModel card;         // the curve's card (a transistor junction's as a diode)
  IdealDiodeLaw law;       // the line it has now
};

class Device {
 public:
  explicit Device(const Element& element) : element_(element) {}
  virtual ~Device() = default;
  Device(const Device&) = delete;
  Device& operator=(const Device&) = delete;

  const Element& element() const { return element_; }
  int element_index() const { return element_index_; }  // in Netlist::elements
  void set_element_index(int index) { element_index_ = index; }
  const std::string& name() const { return element_.name; }

  virtual std::vector<BranchDecl> branches() const = 0;
  virtual void stamp(const StampContext& context, Stamps& stamps) const = 0;

  // SPEC §3 default probes: is this device's current among them (V, L and D elements)? Which of
  // its terminal currents are (a transistor's ic, ib, ie)?
  virtual bool current_probed_by_default() const { return false; }
  virtual std::vector<char> terminals_probed_by_default() const { return {}; }
  // A multi-terminal device's current into one terminal (SPEC §3, `ic(q1)`) as a combination of
  // its own branch currents: (local branch, coefficient). Empty: no such terminal.
  virtual std::vector<std::pair<int, double>> terminal_current(char terminal) const { return {}; }
  // i(element) of a device of several branches (a diode with its breakdown branch) as a
  // combination of its own branch currents; empty: the current of its branch of that name.
  virtual std::vector<std::pair<int, double>> element_current() const { return {}; }

  // Devices with history (lines): the longest step they allow (their shortest delay: a step
  // that ends at t reads the past at t - delay, which must already be known).
  virtual bool has_history() const { return false; }
  virtual double max_step() const { return std::numeric_limits<double>::infinity(); }

  // Cards for the ngspice deck of `validate` (deck_translation.h says what the deck is).
  virtual NgspiceCards ngspice(const NgspiceDeckContext& context) const = 0;
  // What `analyze` warns about it (parameters the ideal model ignores, fits).
  virtual std::vector<std::string> notes() const { return {}; }
  // Its pairs whose laws were fitted to a Shockley curve, for the refit to this circuit's currents.
  virtual std::vector<FittedJunction> fitted_junctions() const { return {}; }

  // ngspice reads the element type from the first letter of the name: `r1` of instance `x1`
  // (flattened "x1.r1") is written `r_x1.r1`.
  static std::string deck_name(char letter, const std::string& name);
  static std::string number(double x);  // "%.12g"

 protected:
  Element element_;
  int element_index_ = -1;
};

// What model formation passes to every device it creates.
struct DeviceOptions {
  double ifit = 10e-3;  // diode fit current (`.options ifit=`)
  // Per fitted junction (FittedJunction::range_key: a diode's element name, a transistor's
  // "q1:be" / "q1:bc"): the currents it carried in this circuit, over which its card's Shockley
  // curve is fitted (diode_refit.h); a junction not listed gets the ifit decade pair.
  std::map<std::string, DiodeCurrentRanges> diode_ranges;
  std::optional<double> bjtcap;  // base–emitter capacitance of every transistor (`.options bjtcap=`)
  bool diodecap = false;         // each diode's CJO across its junction (`.options diodecap`)
  // The run's time scales (a lossy line's kernel is fitted over the band they span; 0: unknown)
  // and the target relative error of that fit.
  double tstop = 0, tstep = 0;
  double line_fit_tolerance = 1e-4;
  // Switches (S, W): the configuration being formed, by switch name (true: on). A switch not
  // listed takes its card's ON/OFF, else off.
  std::map<std::string, bool> switch_on;
};

}  // namespace lcs
