// The verdict of `lcspice validate` (issue 9): lcspice's ideal diodes and ngspice's Shockley
// diodes differ by the model gap g = N Vt ln(I/IS) per conducting junction, which moves values
// and, where a diode switches, the instant of the edge. The comparison therefore has a tube:
// ngspice passes at time t when its value lies, within the value tolerance, between the ideal
// answers at VON and at VON + g (the whole effect of the gap on that probe, edges included)
// somewhere in [t - dt, t + dt] (dt: the time the gap moves a turn-on, g over the slope of the
// junction's voltage before it, at least one output interval).
#pragma once

#include <string>
#include <vector>

#include "netlist/netlist.h"
#include "solver/model/circuit_model.h"

namespace lcs {

// The model gap of a junction carrying at most `peak` amperes (0 when it never conducts more
// than IS): the extra voltage a Shockley diode (N, IS) needs over the ideal threshold.
double model_gap(double peak, double emission, double saturation_current);

// The netlist with every named junction's threshold raised by its gap: an ideal diode with
// VON + gap and the RON it had, a transistor junction ("q1:be", "q1:bc") likewise on a card of
// the transistor's own (`model` gives the laws lcspice used, fits included).
Netlist netlist_with_shifted_thresholds(const CircuitModel& model,
                                        const std::vector<std::pair<std::string, double>>& gaps);

// How far the gap g moves a junction's turn-on in time: g over the rate at which its voltage
// v_d approached the threshold just before each turn-on (lcspice's rows: times, v_d, i_d), the
// median over its turn-ons (a tangential approach, slope near 0, is one of them at most and
// must not widen the whole tube); 0 when it never turns on.
double turn_on_shift(const std::vector<double>& times, const std::vector<double>& vd,
                     const std::vector<double>& id, double gap);

struct TubeDistance {
  double max = 0;         // largest distance of ngspice's value from the tube
  double worst_time = 0;  // where
};

// times: lcspice's output times; nominal, shifted: a probe at VON and at VON + g on those times;
// witness: ngspice's value at the same times.
TubeDistance tube_distance(const std::vector<double>& times, const std::vector<double>& nominal,
                           const std::vector<double>& shifted, const std::vector<double>& witness,
                           double dt);

}  // namespace lcs
