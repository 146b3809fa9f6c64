// Independent source waveforms with ngspice semantics: DC, SIN, PULSE, PWL, EXP, SFFM, AM.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace lcs {

struct Waveform {
  enum class Kind { Dc, Sin, Pulse, Pwl, Exp, Sffm, Am };
  Kind kind = Kind::Dc;
  double dc = 0.0;             // `DC value` (or a bare value); for Kind::Dc the value at all times
  // Parameters as written, in SPICE order; missing trailing ones are filled by resolve().
  //   SIN(VO VA FREQ TD THETA PHASE [NCYCLES])  PHASE in degrees; NCYCLES > 0 (LTspice): the
  //                                    sine stops at TD + NCYCLES/FREQ and holds its value there
  //   PULSE(V1 V2 TD TR TF PW PER [NP])  NP > 0: that many pulses, then V1 (ngspice 39, LTspice)
  //   PWL(t1 v1 t2 v2 ...) [r=T]       times non-decreasing; r=: repeat from the time point T on
  //   EXP(V1 V2 TD1 TAU1 TD2 TAU2)
  //   SFFM(VO VA FC MDI FS TD PHASEM PHASEC)     VO + VA sin(2 pi FC tau + PHASEC + MDI sin(2 pi FS tau + PHASEM))
  //   AM(VO VMO VMA FM FC TD PHASEM PHASEC)      VO + (VMO + VMA sin(2 pi FM tau + PHASEM)) sin(2 pi FC tau + PHASEC)
  //   (SFFM and AM: tau = t - TD, the value 0 before TD; phases in degrees)
  std::vector<double> params;
  // PWL `r=T` (ngspice): after its last point the stretch from the point at time T to the last
  // repeats (T is one of the points, the TD= shift included); none: no repeat.
  std::optional<double> repeat_from;
  bool resolved = false;
  bool frequency_defaulted = false;  // a SIN written with FREQ 0: ngspice's 1/TSTOP (resolve())
  int written = -1;            // how many params the card wrote (set by the first resolve())

  // Fills ngspice defaults that depend on the analysis: SIN FREQ = 1/TSTOP (also for a written 0,
  // as ngspice's vsrcload.c reads it); PULSE TR = TF = TSTEP,
  // PW = PER = TSTOP (TD = THETA = PHASE = 0); EXP TAU1 = TAU2 = TSTEP, TD2 = TD1 + TSTEP;
  // SFFM FC = 5/TSTOP, MDI = 90, FS = 500/TSTOP (MDI then limited to [0, FC/FS], as ngspice);
  // AM VMA = 1, FM = 5/TSTOP, FC = 500/TSTOP. Called by the parser once .tran is known
  // (with tstep = tstop = 0 when there is none; zero-length edges then count as jumps).
  void resolve(double tstep, double tstop);
  // Drops the defaults filled by an earlier resolve() and fills them again: for a run whose
  // TSTEP/TSTOP come from the command line rather than a .tran card.
  void reresolve(double tstep, double tstop);

  double value(double t) const;       // ngspice value at time t (t < 0 is treated as t = 0)
  double value_before(double t) const;  // limit from the left at t (differs from value at jumps)
  double derivative(double t) const;  // d/dt value; right derivative at corners
  // Bounds [min, max] of value(t) over [t0, t1] (exact for DC/PULSE/PWL/EXP; SIN bounded by
  // VO +- |VA|, SFFM by VO +- |VA|, AM by VO +- (|VMO| + |VMA|), and 0 before their TD).
  std::pair<double, double> range(double t0, double t1) const;
  // Times in (t0, t1) where value or slope is not smooth (PULSE and PWL corners, SIN, SFFM and AM
  // start at TD, EXP at TD1 and TD2).
  std::vector<double> breakpoints(double t0, double t1) const;

  // A SIN with NCYCLES > 0: TD + NCYCLES/FREQ, from which it holds its value; else infinity.
  double sine_end() const;

  std::string describe() const;       // "SIN(0 10 50)" style, for reports
  // The same waveform times m (a current source's m= multiplier: m sources in parallel).
  Waveform scaled(double m) const;
};

}  // namespace lcs
