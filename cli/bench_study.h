// The work-precision study behind `lcspice bench` (SPEC §1): for one circuit, a reference by the
// event-driven method at tight tolerance (checked by tightening it further), then every method
// over a range of steps or tolerances and ngspice over a range of RELTOL, each recorded as
// (max relative error against the reference, CPU time, work counts).
//
// Two references, because two models are solved: the ideal (complementarity) circuit, solved
// exactly by `event`, for euler/theta/radau/event; and the smooth circuit (Shockley diodes, the
// deck ngspice runs), solved by `smooth` at tight tolerance, for smooth and ngspice. ngspice's
// error against the ideal reference is recorded as well; it cannot fall below the model gap.
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace lcs {

struct BenchSettings {
  bool quick = false;                        // a few settings per method: for the test suite
  bool ngspice = true;
  double ngspice_timeout = 300;              // wall-clock seconds per ngspice run
  std::vector<std::string> methods;          // empty: every method in the registry
  std::vector<std::string> ngspice_options;  // extra `.options` words for every ngspice run
  double min_timing_seconds = 0.05;          // repeat fast runs until this much CPU, keep the best
  // false: no smooth reference (ngspice is compared with the ideal one, the smooth method is not
  // run). Its rtol 1e-10 run can outlast the rest of the study: 310 s on a 50-stage multiplier.
  bool smooth_reference = true;
  // The ideal circuit's reference: "event" (exact between switchings; rtol 1e-13, checked at
  // 1e-14 with TSTEP/2) or "euler" (implicit Euler at TSTEP/64, checked at TSTEP/128; first
  // order, so its error is about its check's; read linearly between its rows at ngspice's
  // times). The event method is O(n^3) per mode: no reference in reasonable time for a
  // 1000-diode multiplier or ladder, where euler's costs 64 of its steps per TSTEP.
  std::string ideal_reference = "event";
};

struct BenchPoint {
  std::string method;     // registry name, or "ngspice"
  std::string setting;    // "h=5e-06", "rtol=1e-07", "reltol=0.001"
  double parameter = 0;   // the step or tolerance
  std::string reference;  // "ideal" or "smooth"
  double error = 0;       // max over probes and output times of |y - y_ref| / range(y_ref)
  double error_vs_ideal = 0;  // ngspice and smooth: the same against the ideal reference
  double cpu_seconds = 0;     // in-process CPU of the run (ngspice: its own analysis time)
  long steps = 0, lcp_solves = 0, events = 0, rows = 0;
  std::string failure;    // non-empty: the run failed (error and cpu are then NaN)
};

struct CircuitStudy {
  std::string circuit;        // the netlist path
  std::string title;
  std::vector<BenchPoint> points;
  double ideal_reference_check = 0;   // the reference against its tightening (ideal_reference_setting)
  std::string ideal_reference_setting;  // "event rtol=1e-13 vs 1e-14 at TSTEP/2", "euler h=TSTEP/64 vs TSTEP/128"
  double smooth_reference_check = 0;  // smooth at rtol 1e-10 against 1e-11 (NaN: no smooth)
  double emission = 0.05;             // N of the Shockley diodes in the smooth model
};

using BenchProgress = std::function<void(const std::string& what, double fraction)>;

// Throws CliError for netlist errors (exit 2) and when a reference cannot be computed (exit 3).
// `probes`: comma-separated probe list, empty for the netlist's own (.print, else defaults).
CircuitStudy study_circuit(const std::string& netlist_path, const std::string& probes,
                           const std::vector<std::string>& extra_ngspice_options,
                           const BenchSettings& settings, const BenchProgress& progress);

}  // namespace lcs
