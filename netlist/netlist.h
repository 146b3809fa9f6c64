// The parsed, flattened circuit: what the netlist reader hands to the graph and model stages.
// Subcircuits are expanded, parameters substituted, names lower-cased (SPICE is case-insensitive).
#pragma once

#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "netlist/source_location.h"
#include "netlist/waveform.h"

namespace lcs {

enum class ElementKind {
  Resistor,       // R n+ n- value
  Inductor,       // L n+ n- value [IC=i0]
  Capacitor,      // C n+ n- value [IC=v0]
  Coupling,       // K L1 L2 k         (no nodes)
  VoltageSource,  // V n+ n- waveform
  CurrentSource,  // I n+ n- waveform  (current flows n+ -> through source -> n-)
  Diode,          // D anode cathode model
  Bjt,            // Q collector base emitter [substrate] model [area]
  Line,           // T p1+ p1- p2+ p2- Z0= TD= [IC=v1,i1,v2,i2]   (lossless)
  LossyLine,      // O p1+ p1- p2+ p2- model [IC=...]              (LTRA)
  Vcvs,           // E n+ n- nc+ nc- gain   v(n+,n-) = gain v(nc+,nc-)
  Vccs,           // G n+ n- nc+ nc- gm     current gm v(nc+,nc-) from n+ through it to n-
  Cccs,           // F n+ n- vname gain     current gain i(vname) from n+ through it to n-
  Ccvs,           // H n+ n- vname r        v(n+,n-) = r i(vname)
  VSwitch,        // S n+ n- nc+ nc- model [ON|OFF]   ideal switch, controlled by v(nc+,nc-)
  CSwitch,        // W n+ n- vname model [ON|OFF]     ideal switch, controlled by i(vname)
};

const char* element_kind_name(ElementKind kind);  // "resistor", "inductor", ...

struct Element {
  ElementKind kind = ElementKind::Resistor;
  // Lower-case name as written ("r1"), prefixed by the instance path inside subcircuits
  // ("x1.r1", "x2.x1.d3"). Unique within a Netlist.
  std::string name;
  // Lower-case node names; ground is always "0" ("gnd" is mapped to "0"). Nodes inside a
  // subcircuit instance that are not ports are prefixed like names ("x1.mid").
  std::vector<std::string> nodes;
  double value = 0.0;                  // R [ohm], L [H], C [F]; K: coupling coefficient k; Q: area
  std::optional<double> ic;            // IC= of L (current) and C (voltage)
  Waveform waveform;                   // V and I
  std::string model;                   // D, Q: model name, lower-case (flat)
  std::vector<std::string> coupled;    // K: the two inductor names (lower-case, full path)
  // T: characteristic impedance Z0 [ohm] (in `value`) and delay TD [s]; O: `model` names its
  // LTRA card. IC=v1,i1,v2,i2 (T and O): the port values the line holds before t = 0 with UIC.
  double delay = 0;
  std::vector<double> line_ic;
  // E, F, G, H: `value` is the gain (gm, r); F, H, W: `control` is the controlling voltage source
  // (flat name, resolved in the card's own subcircuit instance as ngspice does).
  std::string control;
  std::optional<bool> initially_on;    // S, W: ON or OFF on the card (the state at t = 0);
                                       // D, Q: false for OFF (the operating point to prefer)
  SourceLocation loc;                  // the card (for subcircuit elements: the card inside .subckt)
};

struct DiodeModel {
  std::string name;                    // lower-case
  std::optional<double> von, ron;      // ideal (piecewise-linear) parameters as written
  double is = 1e-14, n = 1.0, rs = 0.0;  // smooth (Shockley, ngspice level 1) parameters
  bool has_is = false, has_n = false, has_rs = false;  // which smooth ones were written
  // Reverse breakdown (a Zener): current flows backwards once the reverse voltage reaches BV,
  // ngspice's I = -IBV exp(-(V + BV) / (N Vt)); the ideal law is a second, reverse pair at -BV.
  std::optional<double> bv;            // V, > 0; none: no breakdown
  double ibv = 1e-3;                   // A, ngspice's default
  std::optional<double> nbv;           // the breakdown's emission coefficient (ngspice's NBV; none: N)
  std::optional<double> rrev;          // LTspice's Rrev: the breakdown's on-resistance (ideal law)
  // Junction capacitance CJO [F] (also CJ0, CJ). Modelled only under `.options diodecap`
  // (SPEC §2 lists it as ignored), at its zero-bias value across the junction as the
  // transistors' CJE/CJC are: ngspice's depletion curve (VJ, M, FC) and the diffusion charge
  // (TT) are not modelled.
  std::optional<double> cjo;
  std::vector<std::string> ignored;    // accepted ngspice parameters unused by lcspice (cjo, tt, ...)
  SourceLocation loc;
};

// `.model NAME NPN(...)` / `PNP(...)`: the full Ebers–Moll transistor (Stewart 1.3.2, 5.4.7).
// Junction E is base–emitter, C is base–collector. Per-junction VONE/VONC and RONE/RONC override
// VON/RON. Gummel–Poon parameters the model does not use are accepted and listed in `ignored`.
struct BjtModel {
  std::string name;                    // lower-case
  bool pnp = false;
  double bf = 100, br = 1;             // forward / reverse current gain (alpha = beta / (1 + beta))
  std::optional<double> von, ron, vone, vonc, rone, ronc;  // ideal junction parameters as written
  double is = 1e-16, nf = 1.0, nr = 1.0;  // smooth (Shockley) junction parameters
  bool has_is = false, has_nf = false, has_nr = false;
  std::optional<double> cje;           // B–E capacitance [F], the book's regularisation (bjtcap)
  std::optional<double> cjc;           // B–C capacitance [F] (zero-bias, as CJE; the Miller capacitance)
  std::vector<std::string> ignored;    // accepted Gummel–Poon parameters unused by lcspice
  SourceLocation loc;
  // Set by smooth_netlist (the smooth method): the junctions are Shockley curves, an ideal one
  // replaced by its smooth equivalent with this emission coefficient and saturation current.
  struct Smooth { double emission = 0, saturation_current = 0; };
  std::optional<Smooth> smooth;
};

// `.model NAME LTRA(R= L= G= C= LEN=)`: a lossy (Heaviside RLCG) line, per-unit-length values
// (Stewart 1.3.3, (1.11)-(1.12)). L, C and LEN are required (an RC line, L = 0, has no
// wavefront and is not modelled); R and G default to 0.
struct LineModel {
  std::string name;                    // lower-case
  double r = 0, l = 0, g = 0, c = 0, len = 0;
  std::vector<std::string> ignored;    // accepted ngspice LTRA parameters unused by lcspice
  SourceLocation loc;
};

// `.model NAME SW(VT= VH= RON= ROFF=)` / `CSW(IT= IH= RON= ROFF=)`: an ideal switch (ngspice's
// defaults). It turns on when its control exceeds VT + VH and off when it falls below VT - VH.
struct SwitchModel {
  std::string name;                    // lower-case
  bool current_controlled = false;     // CSW: IT/IH in amperes
  double vt = 0, vh = 0;               // threshold and hysteresis (V, or A for CSW)
  bool reversed = false;               // on below VT - VH, off above VT + VH (PSpice VON < VOFF)
  double ron = 1, roff = 1e12;         // ROFF default 1/GMIN
  SourceLocation loc;
};

struct TranSpec {
  double tstep = 0, tstop = 0, tstart = 0, tmax = 0;  // tmax 0: not given
  bool uic = false;
  bool step_picked = false;  // written as `.tran 0 TSTOP` or `.tran TSTOP`: tstep is lcspice's choice
  bool stop_only = false;    // written as LTspice's `.tran TSTOP`
  SourceLocation loc;
};
constexpr int kPickedStepsPerSpan = 1000;  // `.tran [0] TSTOP`: TSTEP = (TSTOP - TSTART) / 1000

struct NodeIc {                        // one entry of `.ic v(node)=value`
  std::string node;                    // lower-case, "0" for ground
  double value = 0;
  SourceLocation loc;
};

struct Probe {
  enum class Kind { NodeVoltage, NodePairVoltage, ElementCurrent, TerminalCurrent };
  Kind kind = Kind::NodeVoltage;
  std::string a, b;                    // nodes (a, b) or element name (a); lower-case
  SourceLocation loc;                  // empty file when it came from the command line
  char terminal = 0;                   // TerminalCurrent: 'c', 'b', 'e' (a BJT's ic/ib/ie), '2' (i2(t1))
  // When set, the header instead of the canonical name: i(r1) of a resistor left out of the
  // circuit (both terminals on one node) is read as v(0,0), which is zero, under its own name.
  std::string label = {};
  std::string name() const;            // canonical CSV header: "v(n)", "v(p,n)", "i(d1)", "ic(q1)"
};

// Parses one probe as written in `.print`/`.save`/`--probe`: v(n), v(n1,n2), i(name), and a
// transistor's terminal currents ic(q), ib(q), ie(q).
// Throws NetlistError (with `loc` adjusted by the column offset inside `text`).
Probe parse_probe(const std::string& text, const SourceLocation& loc);

// `.measure tran` (alias `.meas`): one measurement of the transient's waveforms, evaluated
// after `run` (cli/measure.h). Times are seconds; every window is [from, to] of the run's rows,
// its ends interpolated.
struct MeasureCrossing {
  // The instant a probe crosses a level (WHEN, TRIG, TARG), or a fixed time (TRIG/TARG AT=).
  std::optional<double> at;            // AT=t: the instant itself, no probe
  Probe probe;                         // the probe that crosses
  std::optional<Probe> other;          // WHEN p1=p2: the level is another probe
  double level = 0;                    // VAL=v, or WHEN p=v
  // Which crossing (ngspice's counting): the first of any kind when none is written, else the
  // count-th rise, fall or crossing of either kind, or the last one (count 0 with `last`).
  enum class Edge { First, Rise, Fall, Cross };
  Edge edge = Edge::First;
  int count = 0;
  bool last = false;
  double td = 0;                       // TD=: crossings before it do not count
  double from = 0;                     // FROM=
  std::optional<double> to;            // TO=
};

// PARAM='expression': a value computed from other measures' results and the deck's parameters
// and functions (ngspice 39: after every other measure, the PARAMs in card order, each seeing
// the ones above it).
struct MeasureExpression {
  std::string text;                    // as written, without its quotes or braces
  SourceLocation loc;                  // the text on the card
  // Names it reads that are neither parameters nor functions of the deck (lower-case, first
  // use first): the measures it uses (checked against them when the deck is elaborated).
  struct Name {
    std::string name;
    std::size_t offset = std::string::npos;  // its first use in `text`; npos: only a .func body reads it
  };
  std::vector<Name> names;
  // Where a name is written on the card (the whole text when the text spans lines or a .func
  // body reads it).
  SourceLocation location_of(const Name& name) const;
  // Measure results by lower-case name: the value, nullopt for no measure of that name; throws
  // std::runtime_error saying why a measure of that name has no value.
  using MeasureLookup = std::function<std::optional<double>(const std::string& name)>;
  // The value; a measure's result hides a .param of its name, and a measure without a value
  // leaves it seen (as ngspice stores results as parameters). Throws std::runtime_error saying
  // what failed ("PARAM 'a/b': division by zero", a name unknown or without a value, ...).
  std::function<double(const MeasureLookup&)> evaluate;
};

struct Measure {
  enum class Kind {
    Avg, Rms, Min, Max, Pp, Integ, MinAt, MaxAt,  // of `probe` over [from, to]
    FindAt,     // FIND probe AT=at
    FindWhen,   // FIND probe WHEN ...: probe's value at the crossing `when`
    When,       // WHEN ...: the crossing's time
    TrigTarg,   // TRIG ... TARG ...: targ's time minus trig's
    Param,      // PARAM='expression' of other measures
  };
  std::string name;                    // lower-case, as printed ("trise = 2.197e-04")
  Kind kind = Kind::Avg;
  Probe probe;                         // AVG .. MAX_AT, FIND
  double from = 0;                     // AVG .. MAX_AT
  std::optional<double> to;
  double at = 0;                       // FIND AT=
  MeasureCrossing when;                // FIND .. WHEN, WHEN; TRIG for TrigTarg
  MeasureCrossing targ;                // TrigTarg
  MeasureExpression expression;        // Param
  SourceLocation loc;                  // the measure's name on the card
};
const char* measure_kind_name(Measure::Kind kind);  // "AVG", "FIND", "TRIG/TARG", ...

struct Netlist {
  std::string file;                    // path of the top-level file as given
  std::string title;                   // first line, as written
  std::vector<Element> elements;       // in card order, subcircuits expanded in place
  std::map<std::string, DiodeModel> diode_models;  // by lower-case name
  std::map<std::string, BjtModel> bjt_models;      // by lower-case name
  std::map<std::string, LineModel> line_models;    // LTRA, by lower-case name
  std::map<std::string, SwitchModel> switch_models;  // SW and CSW, by lower-case name
  std::optional<TranSpec> tran;
  std::vector<NodeIc> node_ics;
  std::vector<NodeIc> node_sets;       // `.nodeset`: choose among several operating points
  std::vector<Probe> probes;           // `.print tran` and `.save`, in order, duplicates removed
  // A .print asked for V(*) or I(*) (Xyce, PSpice's alias(*)): the default probes, then those of
  // `probes` that are not among them (cli probes_for).
  bool every_probe = false;
  std::vector<Measure> measures;       // `.meas tran`, in card order (probes checked like .print's)
  std::map<std::string, std::string> options;  // `.options` name (lower-case) -> value text ("" for flags)
  // Set by smooth_netlist (solver/model): every diode is a Shockley junction with the card's
  // VON in series, so the checks of the ideal law (impedance-free diode loops) do not apply.
  bool smooth_junctions = false;
  std::map<std::string, SourceLocation> option_locs;
  std::vector<std::string> warnings;   // formatted "FILE:LINE:COL: warning: ..." lines

  const Element* find_element(const std::string& lower_name) const;
};

// Reads and flattens a netlist. Throws NetlistError for every problem in the input (syntax,
// unknown model, duplicate names, unsupported card, unreadable .include file, ...).
// A file that cannot be opened at the top level throws FileError (a usage error, exit 1).
struct ReadOptions {
  // For commands that run a transient analysis (`run`, `validate`): a deck with neither a `.tran`
  // card nor a `tran` command in `.control`, that asks for another analysis (`.op`, `dc` ...), is
  // refused before its cards are elaborated (the refusal is the first thing wrong with it).
  bool require_transient = false;
};
Netlist parse_netlist_file(const std::string& path, const ReadOptions& options = {});
Netlist parse_netlist_string(const std::string& text, const std::string& file_name,
                             const ReadOptions& options = {});

}  // namespace lcs
