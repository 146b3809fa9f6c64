// Independent source waveforms with ngspice semantics: DC, SIN, PULSE, PWL.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace lcs {

struct Waveform {
  enum class Kind { Dc, Sin, Pulse, Pwl };
  Kind kind = Kind::Dc;
  double dc = 0.0;             // `DC value` (or a bare value); for Kind::Dc the value at all times
  // Parameters as written, in SPICE order; missing trailing ones are filled by resolve().
  //   SIN(VO VA FREQ TD THETA PHASE)   PHASE in degrees
  //   PULSE(V1 V2 TD TR TF PW PER)
  //   PWL(t1 v1 t2 v2 ...)             times non-decreasing
  std::vector<double> params;
  bool resolved = false;
  int written = -1;            // how many params the card wrote (set by the first resolve())

  // Fills ngspice defaults that depend on the analysis: SIN FREQ = 1/TSTOP; PULSE TR = TF = TSTEP,
  // PW = PER = TSTOP (TD = THETA = PHASE = 0). Called by the parser once .tran is known
  // (with tstep = tstop = 0 when there is none; zero-length edges then count as jumps).
  void resolve(double tstep, double tstop);
  // Drops the defaults filled by an earlier resolve() and fills them again: for a run whose
  // TSTEP/TSTOP come from the command line rather than a .tran card.
  void reresolve(double tstep, double tstop);

  double value(double t) const;       // ngspice value at time t (t < 0 is treated as t = 0)
  double value_before(double t) const;  // limit from the left at t (differs from value at jumps)
  double derivative(double t) const;  // d/dt value; right derivative at corners
  // Bounds [min, max] of value(t) over [t0, t1] (exact for DC/PULSE/PWL; SIN bounded by VO +- |VA|).
  std::pair<double, double> range(double t0, double t1) const;
  // Times in (t0, t1) where value or slope is not smooth (PULSE and PWL corners, SIN start at TD).
  std::vector<double> breakpoints(double t0, double t1) const;

  std::string describe() const;       // "SIN(0 10 50)" style, for reports
};

}  // namespace lcs
