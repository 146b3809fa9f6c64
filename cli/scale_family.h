// The circuit families of `lcspice bench --scale`: netlists of N repeated diode cells, written
// in lcspice's SPICE dialect, so that cost can be measured against the number of diodes.
//
//  - cw: an N-stage Cockcroft-Walton multiplier (2N diodes, 2N capacitors) on a 100 V, 50 Hz
//    SIN source, starting empty (UIC), a 1 Gohm load at the top: with no load it pumps up to
//    2N (100 V - VON).
//  - ladder: one RC line of 1 kohm and 10 nF cut into N sections, a clamp diode from every node
//    to a 2 V source (N diodes); 5 V, 1 kHz SIN. The diodes' RON is N kohm, so the clamps add up
//    to 1 mS for every N: every N discretises the same clamped line and every clamp conducts
//    near each positive peak.
//  - rectifiers: N half-wave rectifiers on one 10 V, 50 Hz SIN source (N diodes), each a 1 ohm
//    series resistor, a diode, 100 uF and a load of 1.0 to 1.9 kohm (by branch, so that they
//    switch at different instants).
//
// Each netlist runs five source periods at 200 steps a period and prints one or two node
// voltages.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace lcs {

enum class ScaleFamily { CockcroftWalton, Ladder, Rectifiers };

const char* scale_family_name(ScaleFamily family);               // "cw", "ladder", "rectifiers"
std::optional<ScaleFamily> find_scale_family(const std::string& name);
std::string scale_family_names();                                // "cw, ladder, rectifiers"

// N counts stages (cw), sections (ladder) or rectifiers.
int scale_family_diodes(ScaleFamily family, int n);
// Sizes whose diode counts run 10, 20, 50, 100, 200, 500, 1000.
std::vector<int> default_scale_sizes(ScaleFamily family);
// The node the family's output is read at, for size n ("b3": the top of a 3-stage multiplier).
std::string scale_family_output_node(ScaleFamily family, int n);

// The netlist text for size n >= 1 (std::invalid_argument otherwise).
std::string scale_family_netlist(ScaleFamily family, int n);
// Its file name, "<family>_<n>.cir".
std::string scale_family_deck_name(ScaleFamily family, int n);

}  // namespace lcs
