// Transmission lines (Stewart 1.3.3; SPEC §2 `T` and `O` cards, probes i(t1) and i2(t1)) through
// the command line, against the method of characteristics written out in closed form.
//
// A lossless line of impedance Z0 and delay TD between port 1 (p1+, p1-) and port 2 (p2+, p2-),
// with i1 = i(t1) and i2 = i2(t1) the currents INTO the line at p1+ and at p2+:
//   v1(t) = Z0 i1(t) + e1(t),   e1(t) = v2(t - TD) + Z0 i2(t - TD),
//   v2(t) = Z0 i2(t) + e2(t),   e2(t) = v1(t - TD) + Z0 i1(t - TD),
// e/2 being the wave that arrives at the port. Each port is a Thevenin source e behind Z0 whose e
// is fixed one delay earlier, so a circuit that is otherwise resistive (diodes included: a diode
// behind a Thevenin source is a static complementarity problem in one unknown) is solved at any
// time t by a recursion of depth t/TD, with no discretisation: the references below are exact at
// every instant, edges included. Without UIC the history before t = 0 is the DC state, where the
// line is a through connection (v1 = v2, i1 = -i2).
//
// The time-stepping methods cap their step at TD; at a fixed step that divides TD their history
// samples fall on earlier steps, so they reproduce the plateaus between arrivals to rounding
// (tolerance 1e-6 of the scale here) and place a diode switching within one step.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>

#include "netlist/netlist.h"
#include "solver/integrators/transient.h"
#include "tests/cli_support.h"

namespace lcs::cli_testing {
namespace {

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// The circuit file still says what the closed form assumes.
void expect_cards(const std::string& name, const std::vector<std::string>& cards) {
  const std::string text = read_file(circuit(name));
  for (const std::string& card : cards)
    EXPECT_NE(text.find("\n" + card + "\n"), std::string::npos) << "circuits/" << name << ".cir no longer has: " << card;
}

// ngspice PULSE(V1 V2 TD TR TF PW PER), TR and TF nonzero.
struct Pulse {
  double v1, v2, delay, tr, tf, pw, per;
  double operator()(double t) const {
    if (t < delay) return v1;
    double s = std::fmod(t - delay, per);
    if (s < tr) return v1 + (v2 - v1) * s / tr;
    s -= tr;
    if (s < pw) return v2;
    s -= pw;
    if (s < tf) return v2 + (v1 - v2) * s / tf;
    return v1;
  }
};

// =============================================================================================
// Reflection ladder (circuits/tline_reflection_ladder.cir): a step of Vs from Rs into a line
// (Z0, TD) ending in RL. Bounce diagram: the incident wave V1 = Vs Z0/(Rs + Z0), reflection
// coefficients GL = (RL - Z0)/(RL + Z0) and GS = (Rs - Z0)/(Rs + Z0). The k-th wave arriving at
// the load (k = 0, 1, ...) is V1 (GS GL)^k and adds (1 + GL) times itself to v(out), at
// t0 + (2k+1) TD; the k-th wave arriving back at the source (k >= 1) is V1 GL (GS GL)^(k-1) and
// adds (1 + GS) times itself to v(in), at t0 + 2k TD. Each jump is the source's edge, delayed: a
// linear ramp of TR, crossing its half-height TR/2 after the arrival.
struct Ladder {
  double vs = 1, rs = 25, z0 = 50, rl = 150, td = 1e-9, t0 = 1e-9, tr = 10e-12, tstop = 16e-9;
  double v1() const { return vs * z0 / (rs + z0); }
  double gl() const { return (rl - z0) / (rl + z0); }
  double gs() const { return (rs - z0) / (rs + z0); }
  double final_value() const { return vs * rl / (rs + rl); }
  // Level after arrival k (k = -1: before the first): v(out), arrivals at t0 + (2k+1) TD.
  double out(int k) const {
    double sum = 0, g = 1;
    for (int j = 0; j <= k; ++j, g *= gs() * gl()) sum += v1() * (1 + gl()) * g;
    return sum;
  }
  // v(in), arrivals at t0 + 2k TD (k = 0: the source's own edge, which launches V1).
  double in(int k) const {
    if (k < 0) return 0;
    double sum = v1(), g = 1;
    for (int j = 1; j <= k; ++j, g *= gs() * gl()) sum += v1() * gl() * (1 + gs()) * g;
    return sum;
  }
  struct Probe {
    std::string name;
    std::vector<double> arrival, level;  // level[k] from arrival[k] + TR until arrival[k+1]
  };
  std::vector<Probe> probes() const {
    Probe o{"v(out)", {}, {}}, i{"v(in)", {}, {}};
    for (int k = 0; t0 + (2 * k + 1) * td < tstop; ++k) o.arrival.push_back(t0 + (2 * k + 1) * td), o.level.push_back(out(k));
    for (int k = 0; t0 + 2 * k * td < tstop; ++k) i.arrival.push_back(t0 + 2 * k * td), i.level.push_back(in(k));
    return {o, i};
  }
};

TEST(TlineReflectionLadder, ClosedFormIsTheBounceDiagramOfTheCircuitFile) {
  const Ladder s;
  expect_cards("tline_reflection_ladder", {"V1 src 0 PULSE(0 1 1n 10p 10p 100n 200n)", "Rs src in 25",
                                           "T1 in 0 out 0 Z0=50 TD=1n", "RL out 0 150", ".tran 5p 16n"});
  EXPECT_DOUBLE_EQ(s.v1(), 2.0 / 3);
  EXPECT_DOUBLE_EQ(s.gl(), 0.5);
  EXPECT_DOUBLE_EQ(s.gs(), -1.0 / 3);
  // v(out): 1, 5/6, 31/36; v(in): 2/3, 8/9, 23/27; both tend to RL/(Rs + RL) = 6/7.
  EXPECT_NEAR(s.out(0), 1.0, 1e-15);
  EXPECT_NEAR(s.out(1), 5.0 / 6, 1e-15);
  EXPECT_NEAR(s.out(2), 31.0 / 36, 1e-15);
  EXPECT_NEAR(s.in(1), 8.0 / 9, 1e-15);
  EXPECT_NEAR(s.in(2), 23.0 / 27, 1e-15);
  EXPECT_NEAR(s.out(60), s.final_value(), 1e-15);
  EXPECT_NEAR(s.in(60), s.final_value(), 1e-15);
  // Seven arrivals at the load, eight at the source within TSTOP, each still distinguishable from
  // the final value at the tolerances below (the 6th differs by (1/6)^6 = 2e-5).
  EXPECT_EQ(s.probes()[0].arrival.size(), 7u);
  EXPECT_EQ(s.probes()[1].arrival.size(), 8u);
  EXPECT_GT(std::abs(s.out(5) - s.final_value()), 1e-5);
}

// Every row on a plateau (more than `margin` away from the probe's own arrivals and their edges)
// against the plateau's level; and the midpoint of each of the first six plateaus has a row.
void check_ladder_plateaus(const Csv& csv, double margin, double tol, double tstep) {
  const Ladder s;
  const auto t = column(csv, "time");
  for (const Ladder::Probe& p : s.probes()) {
    SCOPED_TRACE(p.name);
    const auto v = column(csv, p.name);
    ASSERT_EQ(v.size(), t.size());
    std::vector<int> rows(p.arrival.size() + 1, 0);
    for (size_t r = 0; r < t.size(); ++r) {
      int k = -1;  // the last arrival whose edge is over
      bool on_edge = false;
      for (size_t a = 0; a < p.arrival.size(); ++a) {
        if (t[r] >= p.arrival[a] - margin && t[r] <= p.arrival[a] + s.tr + margin) on_edge = true;
        if (t[r] > p.arrival[a] + s.tr) k = static_cast<int>(a);
      }
      if (on_edge) continue;
      const double level = k < 0 ? 0.0 : p.level[k];
      EXPECT_NEAR(v[r], level, tol * s.final_value()) << "t = " << t[r] << ", after arrival " << k;
      ++rows[k + 1];
    }
    for (size_t a = 0; a < 6 && a < p.arrival.size(); ++a) {
      EXPECT_GT(rows[a + 1], 100) << "plateau after arrival " << a << " (" << p.arrival[a] << " s)";
      const double mid = p.arrival[a] + s.td;  // plateaus last 2 TD
      double nearest = INFINITY;
      for (double tr : t) nearest = std::min(nearest, std::abs(tr - mid));
      EXPECT_LE(nearest, tstep * (1 + 1e-9)) << "no row near the plateau midpoint " << mid;
    }
  }
}

TEST(TlineReflectionLadder, EventPlateausAreTheBounceDiagramToRounding) {
  const Csv csv = run_csv(circuit("tline_reflection_ladder"), "event");
  ASSERT_GT(csv.rows.size(), 3000u);  // every TSTEP = 5 ps to 16 ns
  check_ladder_plateaus(csv, 1e-3 * Ladder().td, 1e-9, 5e-12);
}

TEST(TlineReflectionLadder, EventArrivalsAreOddAndEvenMultiplesOfTdPlusHalfTheEdge) {
  const Ladder s;
  const Csv csv = run_csv(circuit("tline_reflection_ladder"), "event");
  const auto t = column(csv, "time");
  for (const Ladder::Probe& p : s.probes()) {
    SCOPED_TRACE(p.name);
    const auto v = column(csv, p.name);
    ASSERT_EQ(v.size(), t.size());
    for (size_t a = 0; a < 7 && a < p.arrival.size(); ++a) {
      const double before = a == 0 ? 0.0 : p.level[a - 1], after = p.level[a], half = 0.5 * (before + after);
      const double sign = after > before ? 1 : -1;
      // The first row past half the jump, after the previous plateau's middle.
      size_t r = 0;
      while (r < t.size() && (t[r] < p.arrival[a] - s.td || sign * (v[r] - half) < 0)) ++r;
      ASSERT_LT(r, t.size()) << "v never crosses " << half << " after " << p.arrival[a];
      ASSERT_GT(r, 0u);
      const double crossing = t[r - 1] + (half - v[r - 1]) * (t[r] - t[r - 1]) / (v[r] - v[r - 1]);
      EXPECT_NEAR(crossing, p.arrival[a] + 0.5 * s.tr, 1e-3 * s.td) << "arrival " << a;
    }
  }
}

TEST(TlineReflectionLadder, EulerAndRadau5AtAStepDividingTdHitThePlateaus) {
  const double h = 5e-12;  // TD / 200
  for (const std::string method : {"euler", "radau5"}) {
    SCOPED_TRACE(method);
    const Csv csv = run_csv(circuit("tline_reflection_ladder"), method, "--step 5p");
    ASSERT_GT(csv.rows.size(), 3000u);
    check_ladder_plateaus(csv, 3 * h, 1e-6, h);
  }
}

// =============================================================================================
// Line terminated by a diode (Stewart Fig. 1.10; circuits/tline_diode_termination.cir): source
// Vs(t) behind Rs at port 1, RD in series with an ideal diode (VON, RON) at port 2. With the
// characteristics above:
//   port 1: v1 = Vs - Rs i1 = Z0 i1 + e1  ->  i1 = (Vs - e1)/(Rs + Z0);
//   port 2: the diode current is id = -i2 and its law 0 <= id _|_ VON + (RON + RD) id - v2 >= 0
//           with v2 = e2 - Z0 id has the one solution id = max(0, (e2 - VON)/(Z0 + RD + RON)),
//           v2 = e2 - Z0 id.
// So the diode conducts exactly while the incoming e2 exceeds VON, and it switches where e2
// crosses VON. e2 is piecewise linear: it changes only while an echo of one of the source's edges
// arrives (t0 + m TD + [0, TR], every corner of the pulse train lying on t0 + m TD), so the
// switching instants lie on those edges and the plateaus between them are flat.
// DC (t < 0): i = max(0, (Vs(0) - VON)/(Rs + RD + RON)), v1 = v2 = Vs(0) - Rs i.
struct DiodeLine {
  double z0 = 50, td = 1e-9, rs = 10, rd = 10, von = 0.7, ron = 1, tstop = 24e-9;
  Pulse vs{-0.5, 0.5, 0.5e-9, 20e-12, 20e-12, 5.98e-9, 12e-9};
  struct Port {
    double v, i;  // i into the line at p+
  };
  double dc_current() const { return std::max(0.0, (vs(0) - von) / (rs + rd + ron)); }
  Port port1(double t) const {
    if (t < 0) return {vs(0) - rs * dc_current(), dc_current()};
    const Port q = port2(t - td);
    const double i1 = (vs(t) - (q.v + z0 * q.i)) / (rs + z0);
    return {vs(t) - rs * i1, i1};
  }
  double e2(double t) const {
    const Port p = port1(t - td);
    return p.v + z0 * p.i;
  }
  Port port2(double t) const {
    if (t < 0) return {vs(0) - rs * dc_current(), -dc_current()};
    const double e = e2(t), id = std::max(0.0, (e - von) / (z0 + rd + ron));
    return {e - z0 * id, -id};
  }
  // The probes of the run.
  std::map<std::string, double> probes(double t) const {
    const Port p1 = port1(t), p2 = port2(t);
    return {{"v(in)", p1.v}, {"v(out)", p2.v}, {"v(k)", p2.v + rd * p2.i}, {"i(d1)", -p2.i},
            {"i(t1)", p1.i}, {"i2(t1)", p2.i}};
  }

  struct Switch {
    double t;
    bool on;
  };
  std::vector<Switch> switches;  // where e2 crosses VON: scan at 1 ps, then bisect
  std::vector<double> kinks;     // every time where a probe may have a corner

  DiodeLine() {
    const double dt = 1e-12;
    bool on = e2(0) > von;
    for (int n = 1; n * dt <= tstop; ++n) {
      if ((e2(n * dt) > von) == on) continue;
      double a = (n - 1) * dt, b = n * dt;
      for (int it = 0; it < 200; ++it) {
        const double m = 0.5 * (a + b);
        if (m <= a || m >= b) break;
        ((e2(m) > von) == on ? a : b) = m;
      }
      on = !on;
      switches.push_back({b, on});
    }
    std::vector<double> bases;
    for (double start = vs.delay; start < tstop; start += vs.per)
      for (double c : {0.0, vs.tr, vs.tr + vs.pw, vs.tr + vs.pw + vs.tf}) bases.push_back(start + c);
    for (const Switch& s : switches) bases.push_back(s.t);
    for (double b : bases)
      for (int m = 0; b + m * td <= tstop; ++m) kinks.push_back(b + m * td);
  }
  // The exact probe's range over [t - dt, t + dt] (piecewise linear: ends and corners suffice).
  std::pair<double, double> range(const std::string& probe, double t, double dt) const {
    std::vector<double> times = {std::max(0.0, t - dt), t, t + dt};
    for (double k : kinks)
      if (k > t - dt && k < t + dt) times.push_back(k);
    double lo = INFINITY, hi = -INFINITY;
    for (double s : times) {
      const double v = probes(s).at(probe);
      lo = std::min(lo, v), hi = std::max(hi, v);
    }
    return {lo, hi};
  }
  // The probe's largest magnitude over the rows' times: what its tolerances are relative to.
  double scale(const std::string& probe, const std::vector<double>& times) const {
    double s = 0;
    for (double t : times) s = std::max(s, std::abs(probes(t).at(probe)));
    return s;
  }
  // Between echoes: more than `margin` away from every window t0 + m TD + [0, TR].
  bool on_plateau(double t, double margin) const {
    const double phase = std::fmod(t - vs.delay + 100 * td, td);
    return phase >= vs.tr + margin && phase <= td - margin;
  }
};

const std::vector<std::string> kDiodeProbes = {"v(in)", "v(out)", "v(k)", "i(d1)", "i(t1)", "i2(t1)"};
const std::string kDiodeProbeOption = "--probe 'v(in),v(out),v(k),i(d1),i(t1),i2(t1)'";

TEST(TlineDiodeTermination, ClosedFormSwitchesOnAtEachIncidentWaveAndOffAtTheSourcesReflection) {
  const DiodeLine s;
  expect_cards("tline_diode_termination",
               {"V1 src 0 PULSE(-0.5 0.5 0.5n 20p 20p 5.98n 12n)", "Rs src in 10", "T1 in 0 out 0 Z0=50 TD=1n",
                "RD out k 10", "D1 k 0 dsw", ".model dsw D(VON=0.7 RON=1)", ".tran 10p 24n"});
  ASSERT_EQ(s.switches.size(), 4u);
  // On: the first edge (1 V -> 2 x 1 V x 50/60 more at port 2, from e2 = -0.5 V) reaches VON
  // 1.2/1.6667 of the way up the 20 ps edge that arrives at 1.5 ns.
  EXPECT_TRUE(s.switches[0].on);
  EXPECT_NEAR(s.switches[0].t, 1.5e-9 + 20e-12 * 1.2 / (2 * 50.0 / 60), 1e-18);
  EXPECT_NEAR(s.e2(1.9e-9), -0.5 + 2 * 50.0 / 60, 1e-15);
  // Off on the echo arriving at 3.5 ns (the source's reflection), while the source is high.
  EXPECT_FALSE(s.switches[1].on);
  EXPECT_GT(s.switches[1].t, 3.5e-9);
  EXPECT_LT(s.switches[1].t, 3.52e-9);
  EXPECT_EQ(s.vs(s.switches[1].t), 0.5);
  // The second pulse, on a ringing line: on at 13.5 ns, off at 15.5 ns.
  EXPECT_TRUE(s.switches[2].on);
  EXPECT_GT(s.switches[2].t, 13.5e-9);
  EXPECT_LT(s.switches[2].t, 13.52e-9);
  EXPECT_FALSE(s.switches[3].on);
  EXPECT_GT(s.switches[3].t, 15.5e-9);
  EXPECT_LT(s.switches[3].t, 15.52e-9);
  // The plateau levels of the comment in the circuit file.
  EXPECT_NEAR(s.probes(2e-9).at("i(d1)"), 7.6503e-3, 1e-7);
  EXPECT_NEAR(s.probes(2e-9).at("v(out)"), 0.7842, 1e-4);
  EXPECT_NEAR(s.e2(4e-9), 0.5656, 1e-4);
  EXPECT_NEAR(s.probes(14e-9).at("i(d1)"), 10.7469e-3, 1e-7);
  // No row of a 10 ps grid sits on a switching: at every grid point e2 is clearly on one side.
  for (int n = 0; n * 10e-12 <= s.tstop; ++n) EXPECT_GT(std::abs(s.e2(n * 10e-12) - s.von), 1e-6) << n;
}

// The diode's switching instants seen in a run: a turn-on at the last row without current before
// a row with current, a turn-off at the first row without current after one with current.
std::vector<DiodeLine::Switch> switches_in(const std::vector<double>& t, const std::vector<double>& id, double thr) {
  std::vector<DiodeLine::Switch> out;
  for (size_t r = 1; r < t.size(); ++r) {
    const bool was = id[r - 1] > thr, is = id[r] > thr;
    if (!was && is) out.push_back({t[r - 1], true});
    if (was && !is) out.push_back({t[r], false});
  }
  return out;
}

TEST(TlineDiodeTermination, EventMatchesTheCharacteristicsEverywhere) {
  const DiodeLine s;
  const Csv csv = run_csv(circuit("tline_diode_termination"), "event", kDiodeProbeOption);
  const auto t = column(csv, "time");
  ASSERT_GT(t.size(), 2300u);
  // Levels to 1e-9 of each probe's scale, in time to 1e-3 TD: each row lies within the exact
  // waveform's range over [t - 1e-3 TD, t + 1e-3 TD] (on a plateau: its level).
  const double dt = 1e-3 * s.td;
  for (const std::string& probe : kDiodeProbes) {
    SCOPED_TRACE(probe);
    const auto v = column(csv, probe);
    ASSERT_EQ(v.size(), t.size());
    const double scale = s.scale(probe, t);
    int plateau_rows = 0;
    for (size_t r = 0; r < t.size(); ++r) {
      const auto [lo, hi] = s.range(probe, t[r], dt);
      EXPECT_GE(v[r], lo - 1e-9 * scale) << "t = " << t[r];
      EXPECT_LE(v[r], hi + 1e-9 * scale) << "t = " << t[r];
      plateau_rows += s.on_plateau(t[r], dt);
    }
    EXPECT_GT(plateau_rows, 2000);
  }
  // Switching instants: each is a row (SPEC §3: every switching event is output).
  const auto id = column(csv, "i(d1)");
  const auto seen = switches_in(t, id, 1e-9 * 10.7469e-3);
  ASSERT_EQ(seen.size(), s.switches.size());
  for (size_t k = 0; k < seen.size(); ++k) {
    EXPECT_EQ(seen[k].on, s.switches[k].on) << k;
    EXPECT_NEAR(seen[k].t, s.switches[k].t, 1e-3 * s.td) << k;
  }
}

// The waves each segment sends into the line are read back as Taylor series (taylor_segment.h):
// this circuit has no states, so every mode's ||M|| is the sources' and the fitted inputs', and no
// segment needs the exact product. A regression to per-read products keeps the rows (the test
// above) but costs 30 times the run (README, "Transmission lines").
TEST(TlineDiodeTermination, EventReadsEverySegmentOfItsHistoryAsATaylorSeries) {
  const fs::path dir = scratch_dir("tline_taylor_history");
  const Result r = run_lcspice("run '" + circuit("tline_diode_termination").string() +
                                   "' --method event --stats -o '" + (dir / "out.csv").string() + "'",
                               dir);
  ASSERT_EQ(r.code, 0) << r.err;
  const size_t at = r.err.find("line history: ");
  ASSERT_NE(at, std::string::npos) << r.err;
  long taylor = -1, exact = -1;
  ASSERT_EQ(std::sscanf(r.err.c_str() + at,
                        "line history: %ld segments kept as Taylor series, %ld as exact products", &taylor,
                        &exact),
            2)
      << r.err;
  EXPECT_GT(taylor, 2000);
  EXPECT_EQ(exact, 0);
}

// The same event runs with the history read as Taylor series and through the exact product, on
// the line decks with states (the diode-terminated line's modes are only its inputs' shift): every
// row on the TSTEP grid agrees to 2e-10 of its probe's range. Each fit of the history holds to
// 1e-11 of the waves (kHistoryTol); the clamp receiver carries a wave's error around 10 round
// trips (TSTOP = 20 TD), the lossy cable damps it by about 1 % a pass. Measured: 1.9e-11 (clamp
// receiver), 8.4e-13 (lossy rectifier), a tenth of the bound and less.
TEST(TlineHistory, TaylorSeriesGiveTheRowsOfTheExactProduct) {
  for (const std::string name : {"tline_clamp_receiver", "tline_lossy_rectifier"}) {
    SCOPED_TRACE(name);
    const Netlist netlist = parse_netlist_file(circuit(name).string());
    ModelOptions mo;
    mo.t1 = netlist.tran->tstop;
    const CircuitModel model = CircuitModel::build(netlist, mo);
    const OutputMap map = model.output_map(model.default_probes());
    MemorySink rows[2];
    TransientSummary summary[2];
    for (int series = 0; series < 2; ++series) {
      TransientOptions o;
      o.method = "event";
      o.step = netlist.tran->tstep;
      o.tstop = netlist.tran->tstop;
      o.method_options.history_series = series == 1;
      summary[series] = run_transient(model, map, o, rows[series]);
    }
    EXPECT_EQ(summary[0].stepper.taylor_segments, 0);
    EXPECT_GT(summary[1].stepper.taylor_segments, 1000);
    // Grid rows of each run by their step number.
    const double h = netlist.tran->tstep;
    std::map<long, Eigen::VectorXd> grid[2];
    for (int k = 0; k < 2; ++k)
      for (size_t r = 0; r < rows[k].times.size(); ++r) {
        const double t = rows[k].times[r];
        if (std::abs(t - std::round(t / h) * h) <= 1e-9 * h) grid[k][std::lround(t / h)] = rows[k].rows[r];
      }
    ASSERT_EQ(grid[0].size(), grid[1].size());
    ASSERT_GT(grid[0].size(), 4000u);
    const int probes = static_cast<int>(grid[0].begin()->second.size());
    for (int p = 0; p < probes; ++p) {
      double lo = INFINITY, hi = -INFINITY, worst = 0;
      for (const auto& [step, row] : grid[0]) {
        lo = std::min(lo, row(p));
        hi = std::max(hi, row(p));
        ASSERT_EQ(grid[1].count(step), 1u) << step;
        worst = std::max(worst, std::abs(grid[1].at(step)(p) - row(p)));
      }
      EXPECT_LE(worst, 2e-10 * std::max(hi - lo, 1e-300)) << "probe " << p;
    }
  }
}

TEST(TlineDiodeTermination, EulerAndRadau5AtAStepDividingTdMatchThePlateausAndSwitchWithinAStep) {
  const DiodeLine s;
  const double h = 10e-12;  // TD / 100, the .tran TSTEP
  for (const std::string method : {"euler", "radau5"}) {
    SCOPED_TRACE(method);
    const Csv csv = run_csv(circuit("tline_diode_termination"), method, "--step 10p " + kDiodeProbeOption);
    const auto t = column(csv, "time");
    ASSERT_GT(t.size(), 2300u);
    // Plateaus (more than 3 steps from every echo of an edge): 1e-6 of each probe's scale.
    for (const std::string& probe : kDiodeProbes) {
      SCOPED_TRACE(probe);
      const auto v = column(csv, probe);
      ASSERT_EQ(v.size(), t.size());
      const double scale = s.scale(probe, t);
      int rows = 0;
      for (size_t r = 0; r < t.size(); ++r) {
        if (!s.on_plateau(t[r], 3 * h)) continue;
        EXPECT_NEAR(v[r], s.probes(t[r]).at(probe), 1e-6 * scale) << "t = " << t[r];
        ++rows;
      }
      EXPECT_GT(rows, 2000);
    }
    // The same four switchings, each within one step of the exact instant.
    const auto seen = switches_in(t, column(csv, "i(d1)"), 1e-6 * 10.7469e-3);
    ASSERT_EQ(seen.size(), s.switches.size());
    for (size_t k = 0; k < seen.size(); ++k) {
      EXPECT_EQ(seen[k].on, s.switches[k].on) << k;
      EXPECT_NEAR(seen[k].t, s.switches[k].t, h * (1 + 1e-6)) << k;
    }
  }
}

// =============================================================================================
// Lossy line (circuits/tline_lossy_rectifier.cir): `analyze` reports the line (and the fitted
// kernel's error: the wording is the implementation's), and ngspice's LTRA agrees (validate runs
// ngspice in-process, as tests/validate_test.cpp: no guard).
TEST(TlineLossyRectifier, AnalyzeReportsTheLine) {
  const fs::path dir = scratch_dir("tline_lossy_analyze");
  const Result r = run_lcspice("analyze '" + circuit("tline_lossy_rectifier").string() + "'", dir);
  EXPECT_EQ(r.code, 0) << r.out << r.err;
  EXPECT_NE(lower(r.out).find("o1"), std::string::npos) << r.out;
  // The kernel fit is reported with its errors, within the fit's 1e-4 target.
  const std::string out = r.out;
  const size_t at = out.find("max relative error ");
  ASSERT_NE(at, std::string::npos) << out;
  EXPECT_LE(std::stod(out.substr(at + 19)), 1e-4) << out;
  const size_t again = out.find("max relative error ", at + 1);
  ASSERT_NE(again, std::string::npos) << out;
  EXPECT_LE(std::stod(out.substr(again + 19)), 1e-4) << out;
}

// The CCP's index (Stewart 5.3): a diode at a line port sees Z0 at once (M0 = D = Z0 + RON > 0,
// index 0); behind a capacitor with RON = 0 it sees nothing at once (D = 0) and the capacitor
// within the kernel's first instant (m(0+) = CB = 1/C > 0, index 1).
TEST(TlineAnalyze, CcpIndexZeroAtAPortAndOneBehindACapacitor) {
  const fs::path dir = scratch_dir("tline_ccp_index");
  const std::string head = "ccp\nv1 s 0 sin(0 1 10meg)\nrs s in 50\nt1 in 0 out 0 z0=50 td=1n\n";
  const std::string tail = ".model dd d(von=0.5 ron=0)\n.tran 1n 100n\n.end\n";
  std::ofstream(dir / "port.cir") << head << "d1 out 0 dd\n" << tail;
  std::ofstream(dir / "cap.cir") << head << "rc out c 10\ncc c 0 1n\nd1 c 0 dd\n" << tail;
  for (const auto& [deck, index, m0, m1] : {std::tuple<std::string, int, bool, bool>{"port.cir", 0, true, false},
                                           std::tuple<std::string, int, bool, bool>{"cap.cir", 1, false, true}}) {
    SCOPED_TRACE(deck);
    const Result r = run_lcspice("analyze --json '" + (dir / deck).string() + "'", dir);
    ASSERT_EQ(r.code, 0) << r.err;
    const size_t at = r.out.find("\"ccp\": {");
    ASSERT_NE(at, std::string::npos) << r.out;
    const std::string ccp = r.out.substr(at, r.out.find('}', at) - at);
    EXPECT_NE(ccp.find("\"delays\": [1e-09]"), std::string::npos) << ccp;
    EXPECT_NE(ccp.find(std::string("\"m0_p_matrix\": ") + (m0 ? "true" : "false")), std::string::npos) << ccp;
    EXPECT_NE(ccp.find(std::string("\"m1_p_matrix\": ") + (m1 ? "true" : "false")), std::string::npos) << ccp;
    EXPECT_NE(ccp.find("\"index\": " + std::to_string(index)), std::string::npos) << ccp;
  }
}


// =============================================================================================
// Bad lines: exit 2 before anything is simulated, located (FILE:LINE:), naming the element (or the
// incomplete model). Each
// deck has a control, the same deck with the one value made right, which runs (exit 0): the error
// is about that value, not about the deck around it.
struct BadLine {
  std::string tag, line_card, model_card, element;
  std::string good_line_card, good_model_card;
};

std::string line_deck(const std::string& line_card, const std::string& model_card) {
  // Lines 1-4: title, source, source resistor, the line (line 4); the model card on line 6.
  return "bad line\nV1 s 0 DC 1\nR1 s in 50\n" + line_card + "\nR2 out 0 50\n" +
         (model_card.empty() ? "* no model" : model_card) + "\n.tran 10p 10n\n.end\n";
}

TEST(TlineBadInput, NonPositiveDelayOrImpedanceAndIncompleteLtraModelsAreLocatedErrors) {
  const std::string ltra = ".model cable LTRA(R=0.05 L=250n G=0 C=100p LEN=20)";
  const std::vector<BadLine> cases = {
      {"td_zero", "T1 in 0 out 0 Z0=50 TD=0", "", "t1", "T1 in 0 out 0 Z0=50 TD=1n", ""},
      {"td_negative", "T1 in 0 out 0 Z0=50 TD=-1n", "", "t1", "T1 in 0 out 0 Z0=50 TD=1n", ""},
      {"z0_zero", "T1 in 0 out 0 Z0=0 TD=1n", "", "t1", "T1 in 0 out 0 Z0=50 TD=1n", ""},
      {"z0_negative", "T1 in 0 out 0 Z0=-50 TD=1n", "", "t1", "T1 in 0 out 0 Z0=50 TD=1n", ""},
      // An incomplete model is an error at its own card, naming the model.
      {"ltra_no_len", "O1 in 0 out 0 cable", ".model cable LTRA(R=0.05 L=250n G=0 C=100p)", "cable",
       "O1 in 0 out 0 cable", ltra},
      {"ltra_no_c", "O1 in 0 out 0 cable", ".model cable LTRA(R=0.05 L=250n G=0 LEN=20)", "cable",
       "O1 in 0 out 0 cable", ltra},
      {"ltra_unknown_model", "O1 in 0 out 0 nosuch", ltra, "o1", "O1 in 0 out 0 cable", ltra},
  };
  for (const BadLine& c : cases) {
    SCOPED_TRACE(c.tag);
    const fs::path dir = scratch_dir("tline_bad_" + c.tag), deck = dir / (c.tag + ".cir"), good = dir / "good.cir";
    std::ofstream(deck) << line_deck(c.line_card, c.model_card);
    std::ofstream(good) << line_deck(c.good_line_card, c.good_model_card);
    const Result r = run_lcspice("run '" + deck.string() + "' -o '" + (dir / "out.csv").string() + "'", dir);
    EXPECT_EQ(r.code, 2) << r.err;
    EXPECT_NE(r.err.find("error"), std::string::npos) << r.err;
    EXPECT_NE(lower(r.err).find(c.element), std::string::npos) << r.err;
    // Located on the element's card, or (an incomplete model) on the model card.
    const bool at_element = r.err.find(deck.string() + ":4:") != std::string::npos;
    const bool at_model = !c.model_card.empty() && r.err.find(deck.string() + ":6:") != std::string::npos;
    EXPECT_TRUE(at_element || at_model) << r.err;
    EXPECT_FALSE(fs::exists(dir / "out.csv")) << "nothing is simulated";
    const Result control = run_lcspice("run '" + good.string() + "' -o '" + (dir / "good.csv").string() + "'", dir);
    EXPECT_EQ(control.code, 0) << "the corrected deck: " << control.err;
  }
}

// =============================================================================================
// Probes at DC: a 1 V source behind 50 ohm, the line, a load. The line is a through connection:
// i(t1) = 1 V / (50 + RL) into port 1, i2(t1) = -i(t1) (the current leaves port 2 into the load).
double op_value(const std::string& out, const std::string& probe) {
  const size_t at = out.find("  " + probe + " ");
  EXPECT_NE(at, std::string::npos) << probe << " not in\n" << out;
  if (at == std::string::npos) return NAN;
  return std::stod(out.substr(out.find('=', at) + 1));
}

fs::path dc_deck(const std::string& tag, const std::string& line_cards, double rl) {
  const fs::path dir = scratch_dir("tline_dc_" + tag), deck = dir / (tag + ".cir");
  std::ofstream(deck) << "line at DC\nV1 s 0 DC 1\nR1 s a 50\n" << line_cards << "\nR2 b 0 " << rl << "\n.tran 10p 10n\n.end\n";
  return deck;
}

TEST(TlineProbes, OpGivesPortCurrentsIntoEachPortOfALosslessLine) {
  const fs::path deck = dc_deck("op_t", "T1 a 0 b 0 Z0=50 TD=1n", 50);
  const Result r = run_lcspice("op '" + deck.string() + "'", deck.parent_path());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NEAR(op_value(r.out, "v(a)"), 0.5, 1e-12) << r.out;
  EXPECT_NEAR(op_value(r.out, "v(b)"), 0.5, 1e-12) << r.out;
  EXPECT_NEAR(op_value(r.out, "i(t1)"), 10e-3, 1e-14) << r.out;
  EXPECT_NEAR(op_value(r.out, "i2(t1)"), -10e-3, 1e-14) << r.out;
}

// G = 0: at DC the lossy line is its series resistance R LEN = 0.05 x 20 = 1 ohm.
TEST(TlineProbes, OpGivesPortCurrentsIntoEachPortOfALossyLine) {
  const fs::path deck = dc_deck("op_o", "O1 a 0 b 0 cable\n.model cable LTRA(R=0.05 L=250n G=0 C=100p LEN=20)", 50);
  const Result r = run_lcspice("op '" + deck.string() + "'", deck.parent_path());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NEAR(op_value(r.out, "v(a)"), 51.0 / 101, 1e-12) << r.out;
  EXPECT_NEAR(op_value(r.out, "v(b)"), 50.0 / 101, 1e-12) << r.out;
  EXPECT_NEAR(op_value(r.out, "i(o1)"), 1.0 / 101, 1e-14) << r.out;
  EXPECT_NEAR(op_value(r.out, "i2(o1)"), -1.0 / 101, 1e-14) << r.out;
}

// Without UIC a run starts in the DC state and stays there: a mismatched load (150 ohm: any other
// start would ring with GL = 1/2, GS = 0) keeps every row at v = 0.75 V, i = 5 mA, in every method.
TEST(TlineProbes, RunStartsInTheDcStateAndStaysThereWithPortCurrentsInTheCsv) {
  const fs::path deck = dc_deck("run_t", "T1 a 0 b 0 Z0=50 TD=1n", 150);
  for (const std::string method : {"", "event", "euler", "radau5"}) {
    SCOPED_TRACE("method " + method);
    const Csv csv = run_csv(deck, method, "--probe 'v(a),v(b),i(t1),i2(t1)'");
    ASSERT_EQ(csv.header, (std::vector<std::string>{"time", "v(a)", "v(b)", "i(t1)", "i2(t1)"}));
    ASSERT_GT(csv.rows.size(), 900u);
    for (const std::vector<double>& row : csv.rows) {
      EXPECT_NEAR(row[1], 0.75, 1e-9) << "t = " << row[0];
      EXPECT_NEAR(row[2], 0.75, 1e-9) << "t = " << row[0];
      EXPECT_NEAR(row[3], 5e-3, 1e-11) << "t = " << row[0];
      EXPECT_NEAR(row[4], -5e-3, 1e-11) << "t = " << row[0];
    }
  }
}

}  // namespace
}  // namespace lcs::cli_testing
