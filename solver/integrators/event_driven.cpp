#include "solver/integrators/event_driven.h"
#include "solver/model/empty_safe.h"

#include <algorithm>
#include <cstdio>
#include <limits>
#include <array>
#include <cmath>
#include <complex>
#include <map>
#include <string>
#include <unordered_set>

#include <unsupported/Eigen/MatrixFunctions>

#include "solver/integrators/dyadic_time.h"
#include "solver/integrators/exponential_action.h"
#include "solver/integrators/exponential_cache.h"
#include "solver/integrators/taylor_segment.h"
#include "solver/integrators/mode_dynamics.h"
#include "solver/integrators/pairs_at_zero_lcp.h"
#include "solver/integrators/source_system.h"
#include "solver/lcp/lcp.h"
#include "solver/model/numerical_failure.h"

namespace lcs {

namespace {

constexpr int kMaxLevel = 64;
// A constraint value below -kTol times the size of the terms that make it up is a violation;
// within +-kZeroTol of them it counts as zero and its derivatives decide (8.3.3).
constexpr double kTol = 1e-12;
constexpr double kZeroTol = 1e-9;
constexpr int kSuspicionLevels = 10;
constexpr double kSettleDecay = 40;  // e^-40 = 4e-18: a decayed component is below rounding
constexpr double kReducedEta = 1e-3;  // eta_r times the fastest rate (Impl::eta_r)
constexpr int kGrowRounds = 4;        // Impl::select: the reduced set grows at most this often
constexpr int kDerivativeLevels = 4;  // w and its first three derivatives in the reduced q
constexpr double kNoise = 1e-4;  // kNoise * kTol = 1e-16: rounding of a row times |X|
constexpr double kUncoupled = 1e-13;  // of the largest row of a unit: see zero_uncoupled_rows
constexpr double kUncoupledRounding = 8;  // times eps / rcond of the mode's system: the same
constexpr double kUncoupledMost = 1e-9;   // at most (kZeroTol): a row this small is zero anyway
// Impl::propagate: modes of at least kActionStates unknowns (states and source states) step by
// the exponential's action until the products spent on one step level would have paid for its
// dense exponential, about kDenseProductsPerState products per unknown (Eigen's Padé scaling
// and squaring measured 8 to 46 times n matrix-vector products for n = 50 ... 400).
constexpr int kActionStates = 32;
constexpr long kDenseProductsPerState = 10;
// |X| in that floor is |W X|: a ramp's slope u' enters as the change it makes before the next
// reset (SourceSystem::rounding_weights), not in V/s.

// Smallest value of the cubic Hermite interpolant with values a, b and slopes da, db (per unit
// interval) on [0, 1]: a dip between two feasible end points means a possible double crossing.
double hermite_min(double a, double b, double da, double db) {
  const double c1 = da, c2 = -3 * a - 2 * da + 3 * b - db, c3 = 2 * a + da - 2 * b + db;
  double lo = std::min(a, b);
  auto at = [&](double s) {
    if (s > 0 && s < 1) lo = std::min(lo, a + s * (c1 + s * (c2 + s * c3)));
  };
  if (std::abs(c3) > 1e-300) {
    const double disc = c2 * c2 - 3 * c3 * c1;
    if (disc >= 0) {
      const double r = std::sqrt(disc);
      at((-c2 + r) / (3 * c3));
      at((-c2 - r) / (3 * c3));
    }
  } else if (std::abs(c2) > 1e-300) {
    at(-c1 / (2 * c2));
  }
  return lo;
}

// The tolerance scale of each row of a product M X: the size of the terms it adds up, plus the
// rounding noise the mode's matrices carry (entries that should be 0 but are ~1e-16 of their
// row), taken as the row's norm times `x_size`, the weighted size of X.
void row_scales(const Eigen::MatrixXd& Mabs, const Eigen::VectorXd& Mnorm, const Eigen::VectorXd& X,
                double x_size, Eigen::VectorXd& out) {
  out.noalias() = Mabs * X.cwiseAbs();
  out += (kNoise * x_size) * Mnorm;
}

}  // namespace

// One mode (active set) with one form of the sources: the augmented linear system
// d/dt [x; σ] = M [x; σ] and its constraint rows.
// A time the run must stop at: a source breakpoint (the sources change form), an extra output
// time, or TSTOP when it is not a multiple of TSTEP.
struct Stop {
  DyadicTime at;
  double t;
  bool breakpoint, output;
};

struct Mode {
  std::vector<bool> active;
  std::string signature;
  ModeDynamics dyn;
  int q = 0;                        // n + dim σ
  Eigen::MatrixXd M;                // [[Ax, Eu P + Ed P S], [0, S]]
  Eigen::MatrixXd G, GM, GMM, Gabs, GMabs, GMMabs;  // g_i = z_i (active) or w_i (inactive)
  Eigen::VectorXd Gnorm, GMnorm, GMMnorm, Pcnorm;  // row norms: the rounding floor of each row
  Eigen::MatrixXd Z;                // z = Z [x; σ]
  Eigen::MatrixXd Pc;               // index-one constraints as rows over [x; σ]
  // Coarsest step level: h <= 0.5 / rate, rate the largest oscillation |Im λ| or growth Re λ of M,
  // so no sign change of a constraint hides inside a step. `settled_level` leaves out the
  // eigenvalues that decay by e^-kSettleDecay within `settle_time` <= h0 of the mode's (re)start:
  // a transistor junction's CJE through its RON rings at 1e9/s and is gone in 0.1 µs, and
  // holding the whole mode to 1e-10 s steps for it cost 25 million steps on a 2 ms astable.
  int level = 0, settled_level = 0;
  double settle_time = 0;
  // Switch guards (SwitchGuards) as rows over [x; σ]: guard = Guard [x; σ] - guard_offset.
  Eigen::MatrixXd Guard, GuardM, Guardabs;
  Eigen::VectorXd guard_offset, Guardnorm;
  // Impl::propagate: exp(M t) X without exp(M t), and the products it took per step level.
  ExponentialAction action;
  bool has_action = false;
  std::array<long, kMaxLevel + 1> action_products{};
  std::size_t bytes = 0;        // what the matrices above hold (the mode budget counts it)
  std::uint64_t last_used = 0;  // Impl::use_clock when last asked for
};

namespace {

std::size_t mode_bytes(const Mode& md) {
  std::size_t entries = 0;
  for (const Eigen::MatrixXd* A : {&md.M, &md.G, &md.GM, &md.GMM, &md.Gabs, &md.GMabs, &md.GMMabs, &md.Z, &md.Pc,
                                   &md.Guard, &md.GuardM, &md.Guardabs, &md.dyn.Kx, &md.dyn.Ku, &md.dyn.Kd,
                                   &md.dyn.Ax, &md.dyn.Eu, &md.dyn.Ed, &md.dyn.Wx, &md.dyn.Wu, &md.dyn.Wd,
                                   &md.dyn.Cc, &md.dyn.Fc, &md.dyn.project})
    entries += static_cast<std::size_t>(A->size());
  for (const Eigen::VectorXd* v : {&md.Gnorm, &md.GMnorm, &md.GMMnorm, &md.Pcnorm, &md.guard_offset, &md.Guardnorm})
    entries += static_cast<std::size_t>(v->size());
  return entries * sizeof(double) + md.active.size() + 2 * md.signature.size();
}

}  // namespace

struct EventDriven::Impl {
  const LcsProblem& model;
  EventOptions options;
  StepperStats stats;
  std::map<std::string, std::unique_ptr<Mode>> modes;
  ExponentialCache exponentials;  // exp(M h0 / 2^j) per mode and j, computed on first use
  // The modes are dense (the matrices of Mode, O((n + m) q) each: 3.5 MB at 200 states and 200
  // pairs) and a large circuit visits hundreds: past options.mode_cache_bytes the least recently
  // used are dropped at the next restart (trim_modes) and built again when needed.
  std::size_t mode_bytes_held = 0, mode_bytes_peak = 0;
  long mode_evictions = 0, mode_rebuilds = 0;
  std::uint64_t use_clock = 0;
  std::unordered_set<std::string> seen_modes;  // keys built once: stats.modes counts them
  std::unique_ptr<SourceSystem> sources;
  double h0 = 0;
  int stop_level = 43;
  double bracket = 0;  // 2 h0 / 2^stop_level: twice the length events are located to
  Eigen::VectorXd event_left;  // after bisect(): the bracket's left end (X is its right end)
  double event_width = 0;      // and its length in seconds
  int n = 0, m = 0;
  bool step_levels = true;  // modes get their step level (an eigenvalue problem); not to select one
  double prepared_h0 = 0, prepared_tstop = -1;  // prepare()'s grid: segments on it keep the modes
  std::vector<Stop> stops;                       // RunSegment's, for the grid below
  double stops_h0 = -1, stops_tstop = -1;
  std::vector<double> stops_extra;
  // Lines' history segments read their modes (and the wave rows kept per mode) until the run
  // ends: there no mode is dropped.
  bool evict_modes = true;

  // Switch guards: their values and slopes at X, and scratch at a step's end.
  SwitchGuards guards;
  int guard_count = 0;
  Eigen::VectorXd gga, gda, ggb, gdb, gscale;

  // Mode selection: implicit Euler with the tiny step eta, LCP(Csel x + Fsel u(t + eta), Msel).
  double eta = 0;
  Eigen::MatrixXd Csel, Fsel;
  // The reduced problem of the pairs at zero (pairs_at_zero_lcp.h): the same LCP at a step
  // eta_r = kReducedEta / rate, large enough that its levels w, eta_r w', eta_r^2 w'', ... stand
  // apart from Lemke's tolerances (1e-12 of |q|), which at eta (1e-8 / rate) took eta w' for zero
  // next to a w of O(1).
  double eta_r = 0;
  Eigen::MatrixXd Mred, Cred, Fred;
  std::unique_ptr<LcpWarmSolver> selector;
  // Impulses (4.5): pairs with a zero row of D can take a jump x+ = x + B_J nu.
  std::vector<int> impulsive;
  Eigen::MatrixXd CJ, FJ, BJ, CBJ;

  // Run state.
  Mode* cur = nullptr;
  double entered_at = 0;  // when cur was (re)started: its fast decays settle from here
  std::string unresolved_note;  // a mode the selection under way could not resolve (note_unresolved)
  DyadicTime pos;
  Eigen::VectorXd X;       // [x; σ]
  Eigen::VectorXd W;       // rounding weights of [x; σ] for the current source form
  Eigen::VectorXd ga, da;  // constraint values and slopes at X
  // RunSegment's check for a stepped-over turn-off, across the run's segments (a switch starts
  // one): per pair, 0 or the z it closed at below zero, and whether it was closed at the last row.
  Eigen::VectorXd z_floor;
  std::vector<bool> closed_at_last_row;
  std::vector<char> below_at_start;  // constraints that began the mode just below zero
  Eigen::VectorXd start_value;       // their values then: an excused one may not fall below it
  Eigen::VectorXd scale, slope_scale;
  std::array<Eigen::VectorXd, kMaxLevel + 1> Xb, gb, db, sc;

  Impl(const LcsProblem& mdl, const EventOptions& o)
      : model(mdl), options(o), exponentials(o.exponential_cache_bytes) {}

  Mode& mode(const std::vector<bool>& active, const std::string& signature);
  void note_unresolved(const ModeDynamics& d);
  void trim_modes();
  const Eigen::MatrixXd& exponential(Mode& md, int j);
  // out = exp(M h0 / 2^j) X: from the cached exponential, or for a large mode by the
  // exponential's action until its products add up to the dense exponential's cost (then the
  // exponential is formed and cached: a level used often pays for it once).
  void propagate(Mode& md, int j, const Eigen::VectorXd& X, Eigen::VectorXd& out);
  void prepare(double tstep, double tstop);
  bool consistent(Mode& md, const Eigen::VectorXd& X, std::vector<int>* near_zero,
                  const Eigen::MatrixXd* error, std::vector<int>* failing = nullptr,
                  double slope_tol = kZeroTol) const;
  void zero_uncoupled_rows(const std::vector<bool>& active, double rcond, Eigen::MatrixXd& G) const;
  Mode& select(double t, const Eigen::VectorXd& x, const Eigen::VectorXd& sigma,
               const std::string& signature, const Mode* previous, bool event = false,
               const Eigen::VectorXd* op_z = nullptr);
  Eigen::VectorXd rcp_levels(const std::vector<bool>& active, const std::vector<int>& set,
                             const std::string& signature, const Eigen::VectorXd& Xs,
                             const Eigen::MatrixXd* error);
  bool apply_impulse(Eigen::VectorXd& x, const Eigen::VectorXd& u);
  // `mode_start`: the mode was just (re)selected; otherwise the sources were reset within it (a
  // grid time, a line's history), and a constraint excused before keeps its starting value.
  void refresh_constraints(bool mode_start);
  void project();
  bool step(int j);  // false at an event
  void bisect(int j);
  bool far_past(const Eigen::VectorXd& g, const Eigen::VectorXd& scale) const;
  bool right_far = false;
  bool violated(const Eigen::VectorXd& Xv, Eigen::VectorXd& g, Eigen::VectorXd& scale) const;
  // Guard values at Xv (into g, their tolerance scale into scale) and which are below zero.
  void guard_values(const Eigen::VectorXd& Xv, Eigen::VectorXd& g, Eigen::VectorXd& scale) const;
  std::vector<int> guards_below(const Eigen::VectorXd& Xv) const;
  Eigen::VectorXd right;  // bisection: the violated end
  bool advance_to(const DyadicTime& target, const Progress& progress);
  void check_projected_steps(int level);
  long next_projection_check = 1L << 20;
  long steps_at_last_check = 0;
  double t_at_last_check = 0;
  Eigen::VectorXd state() const { return X.head(n); }
  Eigen::VectorXd inputs() const { return sources->P(cur->signature) * X.tail(X.size() - n); }
};

// A row that should be exactly zero (a pair whose z or w the mode does not couple to the state:
// a diode in series with a blocking junction) comes out of the mode's elimination as rounding:
// 5.5e-20 where the other rows of its unit are 1.7 (ngspice's ltra4_1_line at 22.9 ns). Judged
// against its own size, its value -5.5e-20 A and its derivatives failed the right mode, and the
// run stopped with "no consistent mode". A row below kUncoupled of the largest row of its unit
// (currents: a link diode's z, a tree diode's w; the others voltages) is that rounding, and is
// set to the zero it stands for. The rounding of the elimination grows with the condition of the
// mode's system (eps / rcond relative to its largest entries), so the bound does too, up to
// kUncoupledMost. A differential pair with a current-mirror load (no capacitances) at its
// input's zero crossing: the mirror's diode-connected junction, on at zero current while the
// pair's collector is off, came out at -3.7e-16 A against 1e-3 A (4.5e-13 of its unit) with the
// system's rcond 6.9e-7, every other mode failed too, and event stopped with "no consistent mode".
void EventDriven::Impl::zero_uncoupled_rows(const std::vector<bool>& active, double rcond,
                                            Eigen::MatrixXd& G) const {
  const double bound =
      std::min(kUncoupledMost, std::max(kUncoupled, kUncoupledRounding * std::numeric_limits<double>::epsilon() / rcond));
  double largest[2] = {0, 0};
  auto unit = [&](int i) { return active[i] != model.pairs()[i].voltage_type ? 0 : 1; };
  Eigen::VectorXd norms = G.rowwise().norm();
  for (int i = 0; i < m; ++i) largest[unit(i)] = std::max(largest[unit(i)], norms(i));
  for (int i = 0; i < m; ++i)
    if (norms(i) <= bound * largest[unit(i)]) G.row(i).setZero();
}

void EventDriven::Impl::note_unresolved(const ModeDynamics& d) {
  std::string pairs;
  for (int i : d.active) pairs += (pairs.empty() ? "" : ", ") + model.pairs()[i].name;
  char buf[320];
  std::snprintf(buf, sizeof buf,
                "the mode with %s conducting holds a resistance of %.3g ohm beside %.3g ohm, below the "
                "1e-13 of it the event method tells from zero (a huge resistor in a loop with the diodes'); "
                "use --method euler, theta or radau5, or a smaller resistor",
                pairs.c_str(), d.unresolved, d.unresolved_beside);
  unresolved_note = buf;
}

Mode& EventDriven::Impl::mode(const std::vector<bool>& active, const std::string& signature) {
  std::string key;
  for (bool a : active) key.push_back(a ? '1' : '0');
  key += '|' + signature;
  auto it = modes.find(key);
  if (it != modes.end()) {
    it->second->last_used = ++use_clock;
    if (it->second->dyn.unresolved > 0) note_unresolved(it->second->dyn);
    return *it->second;
  }
  auto md = std::make_unique<Mode>();
  md->active = active;
  md->signature = signature;
  md->dyn = ModeDynamics::build(model.lcs(), active);
  // A mode whose loop resistance the method cannot tell from zero (mode_dynamics.cpp) would run
  // as RON = 0: it is never taken, and if the selection finds no other mode, its reason is the
  // error (the default run then falls back to implicit Euler, whose step LCP keeps it).
  if (md->dyn.unresolved > 0) {
    md->dyn.well_posed = false;
    note_unresolved(md->dyn);
  }
  const ModeDynamics& d = md->dyn;
  const Eigen::MatrixXd P = sources->P(signature), S = sources->S(signature);
  const int p = static_cast<int>(S.rows());
  md->q = n + p;
  if (d.well_posed) {
    md->M = Eigen::MatrixXd::Zero(md->q, md->q);
    md->M.topLeftCorner(n, n) = d.Ax;
    md->M.topRightCorner(n, p) = d.Eu * P + d.Ed * P * S;
    md->M.bottomRightCorner(p, p) = S;
    md->G = Eigen::MatrixXd::Zero(m, md->q);
    md->Z = Eigen::MatrixXd::Zero(m, md->q);
    for (size_t r = 0; r < d.active.size(); ++r) {
      const int i = d.active[r];
      // Blocks of the no-column Kx/Wx of a circuit without states point past null (UBSan).
      if (n > 0) md->G.block(i, 0, 1, n) = d.Kx.row(r);
      if (p > 0) md->G.block(i, n, 1, p) = d.Ku.row(r) * P + d.Kd.row(r) * P * S;
      md->Z.row(i) = md->G.row(i);
    }
    for (size_t r = 0; r < d.inactive.size(); ++r) {
      const int i = d.inactive[r];
      if (n > 0) md->G.block(i, 0, 1, n) = d.Wx.row(r);
      if (p > 0) md->G.block(i, n, 1, p) = d.Wu.row(r) * P + d.Wd.row(r) * P * S;
    }
    zero_uncoupled_rows(md->active, d.rcond, md->G);
    md->GM = md->G * md->M;
    md->GMM = md->GM * md->M;
    md->Gabs = md->G.cwiseAbs();
    md->GMabs = md->GM.cwiseAbs();
    md->GMMabs = md->GMM.cwiseAbs();
    md->Pc.resize(d.Cc.rows(), md->q);
    md->Pc << d.Cc, d.Fc * P;
    md->Gnorm = md->G.rowwise().norm();
    md->GMnorm = md->GM.rowwise().norm();
    md->GMMnorm = md->GMM.rowwise().norm();
    md->Pcnorm = md->Pc.rowwise().norm();
    if (guard_count > 0) {
      // control = G x + H z + J u + K u' with z = Z [x; σ], u = P σ, u' = P S σ.
      Eigen::MatrixXd R = guards.H * md->Z;
      if (n > 0) R.leftCols(n) += guards.G;
      if (p > 0) R.rightCols(p) += guards.J * P + guards.K * P * S;
      md->Guard = guards.sign.asDiagonal() * R;
      md->guard_offset = guards.sign.cwiseProduct(guards.threshold);
      md->GuardM = md->Guard * md->M;
      md->Guardabs = md->Guard.cwiseAbs();
      md->Guardnorm = md->Guard.rowwise().norm();
    }
    double omega = 0, omega_settled = 0;
    if (md->q > 0 && step_levels) {
      Eigen::EigenSolver<Eigen::MatrixXd> es(md->M, false);
      // A growth bounds the step as an oscillation does: an unstable mode (a cross-coupled pair
      // at its symmetric equilibrium, Re λ = 2e10/s) would overflow exp(M h0) to inf, and inf
      // times a zero deviation is NaN. At h <= 0.5/growth each step grows at most e^0.5 and the
      // deviation that rounding seeds is seen leaving, as in every simulator.
      if (es.info() == Eigen::Success)
        for (const std::complex<double>& lambda : es.eigenvalues()) {
          const double rate = std::max(std::abs(lambda.imag()), lambda.real());
          omega = std::max(omega, rate);
          const double decay_time = lambda.real() < 0 ? kSettleDecay / -lambda.real() : INFINITY;
          if (decay_time <= h0)
            md->settle_time = std::max(md->settle_time, decay_time);
          else
            omega_settled = std::max(omega_settled, rate);
        }
    }
    while (md->level < 40 && h0 / std::ldexp(1.0, md->level) * omega > 0.5) ++md->level;
    while (md->settled_level < 40 && h0 / std::ldexp(1.0, md->settled_level) * omega_settled > 0.5)
      ++md->settled_level;
  }
  md->bytes = mode_bytes(*md);
  md->last_used = ++use_clock;
  mode_bytes_held += md->bytes;
  mode_bytes_peak = std::max(mode_bytes_peak, mode_bytes_held);
  if (seen_modes.insert(key).second)
    ++stats.modes;
  else
    ++mode_rebuilds;
  return *modes.emplace(key, std::move(md)).first->second;
}

// Called where no reference to a mode is held but `cur`, which stays (so does one mode alone
// above the budget). The modes one selection builds stay until the next restart: the peak can
// pass the budget by them.
void EventDriven::Impl::trim_modes() {
  while (mode_bytes_held > options.mode_cache_bytes && modes.size() > 1) {
    auto victim = modes.end();
    for (auto it = modes.begin(); it != modes.end(); ++it)
      if (it->second.get() != cur && (victim == modes.end() || it->second->last_used < victim->second->last_used))
        victim = it;
    exponentials.drop(victim->second.get());  // keyed by the mode's address, which may be reused
    mode_bytes_held -= victim->second->bytes;
    modes.erase(victim);
    ++mode_evictions;
  }
}

const Eigen::MatrixXd& EventDriven::Impl::exponential(Mode& md, int j) {
  return exponentials.get(&md, j, [&] {
    ++stats.factorisations;
    return md.q > 0 ? Eigen::MatrixXd((md.M * std::ldexp(h0, -j)).exp()) : Eigen::MatrixXd();
  });
}

void EventDriven::Impl::propagate(Mode& md, int j, const Eigen::VectorXd& Xin, Eigen::VectorXd& out) {
  if (md.q >= kActionStates) {
    if (const Eigen::MatrixXd* E = exponentials.find(&md, j)) {
      out.noalias() = *E * Xin;
      return;
    }
    if (!md.has_action) {
      md.action = ExponentialAction(md.M);
      md.has_action = true;
    }
    const double t = std::ldexp(h0, -j);
    // Products counted at their cost against a dense one: a sparse mode's rarely pay for it.
    if (static_cast<double>(md.action_products[j] + md.action.planned_products(t)) * md.action.relative_cost() <=
        static_cast<double>(kDenseProductsPerState * md.q)) {
      const long products = md.action.apply(t, Xin, out);
      md.action_products[j] += products;
      ++stats.exponential_actions;
      stats.action_products += products;
      return;
    }
  }
  out.noalias() = exponential(md, j) * Xin;
}

void EventDriven::Impl::prepare(double tstep, double tstop) {
  const Lcs& s = model.lcs();
  n = s.states();
  m = s.pairs();
  h0 = tstep;
  exponentials.clear();
  modes.clear();
  mode_bytes_held = 0;
  seen_modes.clear();
  sources = std::make_unique<SourceSystem>(model, tstop);
  stop_level = 1;
  while (stop_level < 62 && std::ldexp(1.0, -stop_level) > options.rtol) ++stop_level;
  bracket = std::ldexp(h0, 1 - stop_level);
  event_left.resize(0);

  // The selection step: tiny against the output step and the circuit's fastest rate (as for
  // the start of time-stepping), so its solution is the rational complementarity problem's.
  double rate = s.A.size() > 0 ? s.A.cwiseAbs().rowwise().sum().maxCoeff() : 0.0;
  if (m > 0 && n > 0) {
    const Eigen::MatrixXd CB = s.C * s.B;
    for (int i = 0; i < m; ++i)
      if (s.D(i, i) > 0) rate = std::max(rate, CB.row(i).cwiseAbs().sum() / s.D(i, i));
  }
  eta = 1e-8 * (rate > 0 ? std::min(tstep, 1.0 / rate) : tstep);
  const Eigen::MatrixXd W = Eigen::MatrixXd::Identity(n, n) - eta * s.A;
  Eigen::PartialPivLU<Eigen::MatrixXd> lu(W);
  const Eigen::MatrixXd WB = n > 0 ? solve_or_empty(lu, s.B) : Eigen::MatrixXd(0, m);
  const Eigen::MatrixXd WE = n > 0 ? solve_or_empty(lu, s.E) : Eigen::MatrixXd(0, s.inputs());
  Csel = n > 0 ? Eigen::MatrixXd(s.C * lu.inverse()) : Eigen::MatrixXd(m, 0);
  Fsel = eta * s.C * WE + s.F;
  selector = std::make_unique<LcpWarmSolver>(s.D + eta * s.C * WB);
  eta_r = kReducedEta * (rate > 0 ? std::min(tstep, 1.0 / rate) : tstep);
  {
    Eigen::PartialPivLU<Eigen::MatrixXd> lr(Eigen::MatrixXd::Identity(n, n) - eta_r * s.A);
    const Eigen::MatrixXd RB = n > 0 ? solve_or_empty(lr, s.B) : Eigen::MatrixXd(0, m);
    const Eigen::MatrixXd RE = n > 0 ? solve_or_empty(lr, s.E) : Eigen::MatrixXd(0, s.inputs());
    Cred = n > 0 ? Eigen::MatrixXd(s.C * lr.inverse()) : Eigen::MatrixXd(m, 0);
    Fred = eta_r * s.C * RE + s.F;
    Mred = s.D + eta_r * s.C * RB;
  }

  impulsive.clear();
  const Eigen::MatrixXd CB = s.C * s.B;
  for (int i = 0; i < m; ++i)
    if (s.D.row(i).cwiseAbs().maxCoeff() == 0 && CB(i, i) > 0) impulsive.push_back(i);
  const int k = static_cast<int>(impulsive.size());
  CJ.resize(k, n);
  FJ.resize(k, s.inputs());
  BJ.resize(n, k);
  CBJ.resize(k, k);
  for (int a = 0; a < k; ++a) {
    CJ.row(a) = s.C.row(impulsive[a]);
    FJ.row(a) = s.F.row(impulsive[a]);
    BJ.col(a) = s.B.col(impulsive[a]);
    for (int b = 0; b < k; ++b) CBJ(a, b) = CB(impulsive[a], impulsive[b]);
  }
}

// The mode fits the state if, for every pair, the first of (g, g', g'') that is not zero within
// tolerance is positive (8.3.3), and its index-one constraints hold. After an event the state
// checked is the crossing estimated inside the final bisection bracket, and `error` (columns
// over [x; sigma]: the sum over them of |row . column| bounds how far that row's value at the
// estimate can be from its value at the crossing) widens every tolerance for "at zero".
bool EventDriven::Impl::consistent(Mode& md, const Eigen::VectorXd& Xs,
                                   std::vector<int>* near_zero,
                                   const Eigen::MatrixXd* error, std::vector<int>* failing,
                                   double slope_tol) const {
  if (!md.dyn.well_posed) return false;
  const Eigen::VectorXd g = md.G * Xs, d = md.GM * Xs, dd = md.GMM * Xs;
  const double xn = W.cwiseProduct(Xs).norm();
  Eigen::VectorXd sg, sd, sdd;
  row_scales(md.Gabs, md.Gnorm, Xs, xn, sg);
  row_scales(md.GMabs, md.GMnorm, Xs, xn, sd);
  row_scales(md.GMMabs, md.GMMnorm, Xs, xn, sdd);
  bool ok = true;
  for (int i = 0; i < m; ++i) {
    // After an event the values are taken at the estimated crossing and known to its error.
    // Without one (the start, a breakpoint, a wavefront's arrival) nothing was located: the
    // state is exact and "zero" is rounding. (A value within one bracket of its slope once
    // counted as zero there too: at --rtol 1e-3 and a 1 ms TSTEP the bracket is 2 us, and a
    // hobby astable's base 4.3 V past VON at t = 0, moving at 3e9 V/s, passed with its junction
    // held off; BjtAstable.HobbyAstableAtCoarseTolerancesStartsInItsConsistentMode.) (The
    // new mode's slope times the bracket, used before, has nothing to do with where the event
    // was located and can be far larger: the astable's Q2 collector, 4.8 V falling at 4.9e10
    // V/s and saturating 98 ps later, counted as zero with a negative slope against a 122 ps
    // bracket at --rtol 1e-4, and the only right mode was refused. And past the crossing, the
    // boost's diode with RON CSW = 5 ps already had a current relaxing downwards.)
    double t0 = kZeroTol * sg(i);
    if (error)
      for (Eigen::Index c = 0; c < error->cols(); ++c) t0 += std::abs(md.G.row(i).dot(error->col(c)));
    double t1 = slope_tol * sd(i), t2 = slope_tol * sdd(i);
    // Below kZeroTol (the retry in select()) the slopes are known only to what the crossing's
    // estimate changes in them.
    if (error && slope_tol < kZeroTol)
      for (Eigen::Index c = 0; c < error->cols(); ++c) {
        t1 += std::abs(md.GM.row(i).dot(error->col(c)));
        t2 += std::abs(md.GMM.row(i).dot(error->col(c)));
      }
    if (g(i) > t0) continue;
    if (near_zero && g(i) >= -t0) near_zero->push_back(i);
    if (g(i) < -t0) {
      ok = false;
      if (failing) failing->push_back(i);
    } else if (d(i) < -t1 || (d(i) <= t1 && dd(i) < -t2)) {
      ok = false;
      if (failing) failing->push_back(i);
    }
  }
  if (md.Pc.rows() > 0) {
    const Eigen::VectorXd r = md.Pc * Xs;
    Eigen::VectorXd sr;
    row_scales(md.Pc.cwiseAbs(), md.Pcnorm, Xs, xn, sr);
    // A constraint that holds in the new mode but not in the one that ran into the event (the
    // junction that just closed) is checked at the estimated crossing too, to its error;
    // project() then puts the state, past the crossing, on it. (At the bracket's end, to
    // rounding, it failed: a 9e3 V/s base voltage crossing VON stopped up to 1.7e-8 V past it at
    // --rtol 1e-6, and no mode of the astable passed.)
    if (error)
      for (Eigen::Index c = 0; c < error->cols(); ++c) sr += (md.Pc * error->col(c)).cwiseAbs() / kZeroTol;
    for (int i = 0; i < r.size(); ++i)
      if (std::abs(r(i)) > kZeroTol * sr(i) + 1e-300) ok = false;
  }
  return ok;
}

// The mode that holds from t on at the state x with the sources' state sigma (of `signature`).
Mode& EventDriven::Impl::select(double t, const Eigen::VectorXd& x, const Eigen::VectorXd& sigma,
                                const std::string& signature, const Mode* previous, bool event,
                                const Eigen::VectorXd* op_z) {
  unresolved_note.clear();
  Eigen::VectorXd Xs(n + sigma.size());
  Xs << x, sigma;
  // After an event the modes are checked at the crossing, estimated inside the final bracket
  // [event_left, X] (length L) by linear interpolation of the constraint of the mode that ran
  // into it that crossed first (unless an impulse was taken, see below). Its error:
  // the interpolation's, L^2/8 times the second derivative M^2 X, and the crossing time's,
  // |g''| L^2 / (8 |g'|) of that constraint, times the first derivative M X.
  Eigen::VectorXd Xc;
  Eigen::MatrixXd error_storage;
  const Eigen::MatrixXd* error = nullptr;
  const Eigen::VectorXd* Xt = &Xs;
  if (event && previous && previous->dyn.well_posed && previous->signature == signature &&
      previous->q == Xs.size() && event_left.size() == Xs.size() && X.size() == Xs.size()) {
    const Eigen::VectorXd gl = previous->G * event_left, gr = previous->G * X;
    const Eigen::VectorXd v1 = previous->M * X, v2 = previous->M * v1;
    const double L = event_width;
    double theta = 1, dt = 0;
    for (int i = 0; i < m; ++i) {
      if (!(gr(i) < 0 && gl(i) >= 0 && gl(i) > gr(i))) continue;
      const double th = gl(i) / (gl(i) - gr(i));
      if (th > theta) continue;
      theta = th;
      const double slope = std::abs(previous->GM.row(i).dot(X));
      dt = slope > 0 ? std::min(L, std::abs(previous->GMM.row(i).dot(X)) * L * L / (8 * slope)) : L;
    }
    error_storage.resize(Xs.size(), 2);
    if (Xs.head(n) == X.head(n)) {
      Xc = Xs - (1 - theta) * (X - event_left);
      Xt = &Xc;
      error_storage << v2 * (L * L / 8), v1 * dt;
    } else {
      // An impulse has already put the constraints that were past zero back on it (from the
      // bracket's end; moved back to the crossing, they would be off by the overshoot, and the
      // astable's closing base-emitter junction refused its mode): the end is checked, known
      // to what the bracket changes.
      error_storage << v2 * (L * L / 2), v1 * L;
    }
    error = &error_storage;
  }
  // A ramp moves u by at most its slope times the time to the next reset (grid time or corner).
  const std::vector<double>& bp = sources->breakpoints();
  const auto next = std::upper_bound(bp.begin(), bp.end(), t);
  const double segment = next == bp.end() ? h0 : std::min(h0, *next - t);
  W.resize(Xs.size());
  W << Eigen::VectorXd::Ones(n), sources->rounding_weights(signature, segment);
  // The operating point's mode first, where it continues the state (the start is the operating
  // point: SPEC 2). The switching LCP below can have several solutions at x (a monostable at
  // rest: with its timing capacitor's voltage, both transistors' states are consistent) and
  // Lemke's pick need not be the operating point's.
  if (op_z && m > 0) {
    std::vector<bool> op_active(m);
    for (int i = 0; i < m; ++i) op_active[i] = (*op_z)(i) > 0;
    Mode& at_rest = mode(op_active, signature);
    if (consistent(at_rest, *Xt, nullptr, error)) return at_rest;
  }
  std::vector<bool> active(m, false);
  std::string lemke_failure;    // why the switching LCP gave no first guess, if it did not
  std::string guess;            // the first guess instead, for the message
  std::vector<int> degenerate;  // pairs the switching LCP leaves at z = w = 0
  Eigen::VectorXd q;
  if (m > 0) {
    q = Csel * x + Fsel * model.input_values(t + eta);
    const LcpSolution& sol = selector->solve(q);
    // Lemke's "numerical failure" still returns its residual-minimal point. At an event the
    // switching LCP is degenerate by construction (a pair just reached zero), and rows whose
    // entries are all O(eta) (a diode whose only other path is an inductor) can leave the
    // final basis too ill-conditioned to pass feas_tol. Its active set is then only a first
    // guess, checked by consistent() and searched around like any other; only a ray or the
    // pivot limit (no solution found at all) ends the run.
    // Several solutions (transistor feedback) make Lemke's pick a first guess as well: the
    // derivatives (consistent()) decide which mode continues the state.
    const bool answered = sol.status == LcpStatus::Solved || sol.status == LcpStatus::NumericalFailure ||
                          sol.status == LcpStatus::NotUnique;
    // A ray (or the pivot limit) with a mode to continue: rounding in a switching LCP whose
    // entries span 1e9 (a 1 GOhm shunt) and 0 (RON = 0 diodes) ended Lemke's path at the first
    // event of a bridge with an inductive load. The mode that ran into the event is then the
    // first guess, and the search below decides as it does after any guess.
    // At the start the operating point's mode is that first guess: a RON = 0 bridge into an
    // inductor with thresholds 0.05 V apart leaves every row of the inductor's current at
    // O(eta) against the O(1) of its neighbours, below Lemke's tolerance, and the LCP "has no
    // solution" at t = 0 where a diode at its threshold holds the floating node.
    // With neither at the start (UIC), nothing conducting is the first guess: a half-wave
    // rectifier into an RL load with a freewheeling diode starts with the inductor's current
    // tied to the two diodes' (both off, at zero), the switching LCP's rows of it O(eta), and
    // Lemke's path ended on a ray at t = 0.
    const bool from_previous = previous && previous->signature == signature;
    if (!answered && !from_previous && !op_z && previous) {
      if (!unresolved_note.empty()) throw NumericalFailure(t, unresolved_note);
      throw NumericalFailure(t, std::string("no next mode: the switching LCP has no solution (Lemke: ") +
                                    lcp_status_name(sol.status) + ")");
    }
    if (!answered) lemke_failure = lcp_status_name(sol.status);
    if (answered) {
      for (int i = 0; i < m; ++i) active[i] = sol.z(i) > 0;
      const double qs = q.cwiseAbs().maxCoeff(), zs = sol.z.cwiseAbs().maxCoeff() + qs;
      for (int i = 0; i < m; ++i)
        if (std::abs(sol.z(i)) <= kZeroTol * zs && std::abs(sol.w(i)) <= kZeroTol * qs)
          degenerate.push_back(i);
    } else if (from_previous) {
      active = previous->active;
      guess = "the mode before the event";
    } else if (op_z) {
      for (int i = 0; i < m; ++i) active[i] = (*op_z)(i) > 0;
      guess = "the operating point's";
    } else {
      guess = "the one with nothing conducting";
    }
  }
  std::vector<int> near_zero;
  Mode& first = mode(active, signature);
  if (consistent(first, *Xt, &near_zero, error)) return first;
  // The LCP's own ambiguous pairs (the mode it names may not even be well posed: a node left
  // floating when every diode at it is off), then ...
  for (int i : degenerate)
    if (std::find(near_zero.begin(), near_zero.end(), i) == near_zero.end()) near_zero.push_back(i);
  // ... the pairs at zero in the mode that ran into the event (the ones that switched, and
  // degenerate ones such as a diode holding a floating node's potential at zero current).
  if (previous && previous->dyn.well_posed && previous->signature == signature) {
    const Eigen::VectorXd g = previous->G * Xs, d = previous->GM * Xs;
    Eigen::VectorXd sg;
    row_scales(previous->Gabs, previous->Gnorm, Xs, W.cwiseProduct(Xs).norm(), sg);
    for (int i = 0; i < m; ++i)
      if (std::abs(g(i)) <= kZeroTol * sg(i) + std::abs(d(i)) * bracket &&
          std::find(near_zero.begin(), near_zero.end(), i) == near_zero.end())
        near_zero.push_back(i);
  }
  if (near_zero.empty())
    for (int i = 0; i < m; ++i) near_zero.push_back(i);
  // The pairs at zero decide among themselves (pairs_at_zero_lcp.h), on the values of their w
  // in the mode with all of them off, at the crossing: w, w', w'', w(3) (rcp_levels). (w stays: a
  // pair whose z just reached zero can open onto a w far from zero, the voltage of an RON diode
  // in an inductor's path.) The held pairs whose z the others leave undetermined join them (a
  // reverse-biased junction at a node reached otherwise only through a diode at zero: ngspice's
  // ltra4_1_line, where M_αα was singular at every event and the reduced problem never
  // answered). The pairs a picked mode violates that were outside the set join it too, and the
  // reduced problem is solved again, at most kGrowRounds times.
  const Eigen::VectorXd qr =
      m > 0 ? Eigen::VectorXd(Cred * x + Fred * model.input_values(t + eta_r)) : Eigen::VectorXd();
  std::vector<int> reduced_set = near_zero;
  for (int round = 0; round <= kGrowRounds; ++round) {
    for (int i : undetermined_held_pairs(Mred, active, reduced_set)) reduced_set.push_back(i);
    const Eigen::VectorXd derivatives = rcp_levels(active, reduced_set, signature, *Xt, error);
    const auto reduced = pairs_at_zero_lcp(Mred, qr, active, reduced_set,
                                           derivatives.size() > 0 ? &derivatives : nullptr);
    if (!reduced) break;
    Mode& md = mode(*reduced, signature);
    std::vector<int> failing;
    if (consistent(md, *Xt, nullptr, error, &failing)) return md;
    bool grew = false;
    for (int i : failing)
      if (std::find(reduced_set.begin(), reduced_set.end(), i) == reduced_set.end()) {
        reduced_set.push_back(i);
        grew = true;
      }
    if (!grew) break;
  }
  for (int i : reduced_set)
    if (std::find(near_zero.begin(), near_zero.end(), i) == near_zero.end()) near_zero.push_back(i);
  // Left to a search, for what the reduced LCP does not settle: a mode with a node left floating
  // (not well posed: a bridge rectifier at its source's zero crossing), transistor feedback
  // (several solutions, Lemke's pick not the one that continues the state), a pair not at zero
  // that has to change with one that is (antiparallel RON = 0 diodes on an inductor). Without
  // it 22 of the tests fail. Not strictly complementary (8.3.3: the active set is ambiguous):
  // try the pairs at zero the other way round, fewest changes first, the first 10 of them.
  auto search = [&](const std::vector<int>& candidates, double slope_tol = kZeroTol) -> Mode* {
    const int k = std::min<int>(static_cast<int>(candidates.size()), 10);
    for (int changes = 1; changes <= k; ++changes) {
      std::vector<bool> pick(k, false);
      std::fill(pick.begin(), pick.begin() + changes, true);
      do {
        std::vector<bool> trial = active;
        for (int a = 0; a < k; ++a)
          if (pick[a]) trial[candidates[a]] = !trial[candidates[a]];
        Mode& md = mode(trial, signature);
        if (consistent(md, *Xt, nullptr, error, nullptr, slope_tol)) return &md;
      } while (std::prev_permutation(pick.begin(), pick.end()));
    }
    return nullptr;
  };
  // A pair that is not at zero in the LCP's mode may still have to change with one that is:
  // the voltage of an RON = 0 diode in an inductor's path jumps when the diode opens, and an
  // antiparallel one must close at the same instant. The switching LCP should say so, but its
  // O(eta) entries can sit at its own tolerance. Last resort for small circuits: every pair.
  std::vector<int> all;
  if (m <= 10 && static_cast<int>(near_zero.size()) < m)
    for (int i = 0; i < m; ++i) all.push_back(i);
  if (Mode* md = search(near_zero)) return *md;
  if (Mode* md = search(all)) return *md;
  // No mode fits with the slopes judged against kZeroTol of their terms. A stiff mode's rows
  // of z' and z'' add terms of V / (RON^2 C) that cancel: at a grazing contact (a multiplier
  // with no load near its steady state, two diodes touching their thresholds at the source's
  // peak) the closing diode's z' = -w' / RON = 1.52 A/s sat at exactly kZeroTol of its terms
  // (1.5e9), counted as zero, and z'' = -z' / (RON C) < 0 then refused the mode, while the
  // open mode's w' = -0.76 V/s, resolved, refused the others. The derivatives are then judged
  // against the rounding of their terms (kTol), the levels the values' own test uses, over the
  // same candidates, the LCP's own mode first (with RON = 0.02 it was the one that fits).
  if (consistent(first, *Xt, nullptr, error, nullptr, kTol)) return first;
  if (Mode* md = search(near_zero, kTol)) return *md;
  if (Mode* md = search(all, kTol)) return *md;
  if (!unresolved_note.empty()) throw NumericalFailure(t, unresolved_note);
  if (!lemke_failure.empty())
    throw NumericalFailure(t, "no next mode: the switching LCP has no solution (Lemke: " + lemke_failure +
                                  "), and no mode near " + guess + " continues the state");
  std::string pairs;
  for (int i : near_zero)
    pairs += (pairs.empty() ? "" : ", ") + model.pairs()[i].name;
  throw NumericalFailure(t, "no consistent mode after a switching event" +
                                (pairs.empty() ? std::string() : " (pairs at zero: " + pairs + ")"));
}

// The reduced problem's q for the pairs in `set` (pairs_at_zero_lcp.h): their w in the mode with
// them off and the others as in `active`, at the crossing, as the truncated Taylor series of
// Stewart 4.5 (the Laplace transform's expansion at s = 1/eta_r):
//   q = w + eta_r w' + eta_r^2 w'' + eta_r^3 w(3),
// each level zero within kZeroTol of its terms (|G M^k| |X| and the rounding floor; the value
// itself also within the crossing's error), so that the first nonzero level decides the sign
// (the lexicographic order of Lemma 4.14). Empty where that mode is not well posed.
Eigen::VectorXd EventDriven::Impl::rcp_levels(const std::vector<bool>& active, const std::vector<int>& set,
                                              const std::string& signature, const Eigen::VectorXd& Xs,
                                              const Eigen::MatrixXd* error) {
  std::vector<bool> off = active;
  for (int i : set) off[i] = false;
  Mode& base = mode(off, signature);
  if (!base.dyn.well_posed) return Eigen::VectorXd();
  const double xn = W.cwiseProduct(Xs).norm();
  Eigen::MatrixXd Gk(set.size(), base.q);
  for (size_t r = 0; r < set.size(); ++r) Gk.row(r) = base.G.row(set[r]);
  Eigen::VectorXd out = Eigen::VectorXd::Zero(set.size()), gk, sk;
  double weight = 1;
  for (int level = 0; level < kDerivativeLevels; ++level) {
    gk.noalias() = Gk * Xs;
    row_scales(Gk.cwiseAbs(), Gk.rowwise().norm(), Xs, xn, sk);
    for (size_t r = 0; r < set.size(); ++r) {
      double tol = kZeroTol * sk(r);
      if (level == 0 && error)
        for (Eigen::Index c = 0; c < error->cols(); ++c) tol += std::abs(Gk.row(r).dot(error->col(c)));
      if (std::abs(gk(r)) > tol) out(r) += weight * gk(r);
    }
    weight *= eta_r;
    Gk = Gk * base.M;
  }
  return out;
}

bool EventDriven::Impl::apply_impulse(Eigen::VectorXd& x, const Eigen::VectorXd& u) {
  if (impulsive.empty()) return false;
  const Eigen::VectorXd q = CJ * x + FJ * u;
  const double scale = (CJ.cwiseAbs() * x.cwiseAbs() + FJ.cwiseAbs() * u.cwiseAbs()).maxCoeff();
  if (q.minCoeff() >= -kZeroTol * scale) return false;
  const LcpSolution sol = solve_lemke(CBJ, q);
  if (sol.status != LcpStatus::Solved) return false;
  x += BJ * sol.z;
  return sol.z.maxCoeff() > 0;
}

// A constraint found below zero here (after a restart, or after a grid time reset the sources)
// is excused unless it is plainly falling: its slope below zero beyond the mode check's
// tolerance. The mode check admits a constraint at zero whose slope is zero within that
// tolerance and whose second derivative is positive (a clamp releasing at a peak of its
// source); a reset at a grid time checks nothing, and a falling one there is a switch it
// uncovered, which must end the next step as an event. (Excusing it too left it unwatched for
// good: 20 s of a VON = 0 rectifier whose source crosses zero at grid times, the waveform and
// the propagated sine differing by rounding there, lost a turn-off at 8.05 s and then printed
// a negative diode current for half a period, again and again.)
void EventDriven::Impl::refresh_constraints(bool mode_start) {
  ga.noalias() = cur->G * X;
  da.noalias() = cur->GM * X;
  const double xn = W.cwiseProduct(X).norm();
  row_scales(cur->Gabs, cur->Gnorm, X, xn, scale);
  row_scales(cur->GMabs, cur->GMnorm, X, xn, slope_scale);
  const bool kept = !mode_start && static_cast<int>(below_at_start.size()) == m && start_value.size() == m;
  below_at_start.resize(m);
  if (!kept) start_value = ga;
  for (int i = 0; i < m; ++i) {
    const bool excused = ga(i) < -kTol * scale(i) && da(i) >= -kZeroTol * slope_scale(i);
    // Excused at every grid time, a slow fall would start afresh each time and never reach
    // the band: one excused before keeps where it began.
    if (!(kept && excused && below_at_start[i])) start_value(i) = ga(i);
    below_at_start[i] = excused;
  }
  if (guard_count > 0 && cur->Guard.rows() == guard_count) {
    guard_values(X, gga, gscale);
    gda.noalias() = cur->GuardM * X;
  }
}

// A guard is below zero past the rounding of its terms (its threshold among them): the
// crossing is then located where the control is past its threshold by 1e-12 of its size.
void EventDriven::Impl::guard_values(const Eigen::VectorXd& Xv, Eigen::VectorXd& g, Eigen::VectorXd& scale) const {
  g.noalias() = cur->Guard * Xv;
  g -= cur->guard_offset;
  row_scales(cur->Guardabs, cur->Guardnorm, Xv, W.cwiseProduct(Xv).norm(), scale);
  scale += cur->guard_offset.cwiseAbs();
}

std::vector<int> EventDriven::Impl::guards_below(const Eigen::VectorXd& Xv) const {
  std::vector<int> out;
  if (guard_count == 0 || cur->Guard.rows() != guard_count) return out;
  Eigen::VectorXd g, sc;
  guard_values(Xv, g, sc);
  for (int k = 0; k < guard_count; ++k)
    if (g(k) < -(kTol * sc(k) + 1e-300)) out.push_back(k);
  return out;
}

void EventDriven::Impl::project() {
  if (cur->Pc.rows() == 0) return;
  X.head(n) -= cur->dyn.project * (cur->Pc * X);
}

// An excused constraint is violated once it falls below where it began by the mode check's
// band for zero (kZeroTol of its terms: past that the mode that excused it fails, so the event
// switches): its slope at the start is judged against the mode's fastest terms (a junction's
// CJE through its RON, 1e10 V/s), and a base recovering through 47k and 10 uF past the B-E
// junction's VON fell at 17 V/s, "not plainly falling", and was never watched again (an astable
// switched once and then held the base at 8 V with its junction off).
bool EventDriven::Impl::violated(const Eigen::VectorXd& Xv, Eigen::VectorXd& g, Eigen::VectorXd& scale) const {
  g.noalias() = cur->G * Xv;
  row_scales(cur->Gabs, cur->Gnorm, Xv, W.cwiseProduct(Xv).norm(), scale);
  for (int i = 0; i < m; ++i) {
    if (!(g(i) < -(kTol * scale(i) + 1e-300))) continue;
    if (!below_at_start[i] || g(i) < start_value(i) - kZeroTol * scale(i)) return true;
  }
  return !guards_below(Xv).empty();
}

// A constraint is violated when it ends the step below zero. One that starts the mode slightly
// below (within the mode check's tolerance, and rising, or the mode would not have been chosen)
// is not watched until it has come back above. A dip of the cubic through the end values and
// slopes is a possible double crossing: the step is halved, down to kSuspicionLevels below the
// mode's level (deeper dips are grazing contacts).
bool EventDriven::Impl::step(int j) {
  const double L = std::ldexp(h0, -j);
  Eigen::VectorXd& xb = Xb[j];
  Eigen::VectorXd& g = gb[j];
  Eigen::VectorXd& d = db[j];
  propagate(*cur, j, X, xb);
  ++stats.steps;
  if (violated(xb, g, sc[j])) {
    bisect(j);
    return false;
  }
  d.noalias() = cur->GM * xb;
  bool suspicious = false;
  if (j < std::min(stop_level, cur->level + kSuspicionLevels)) {
    for (int i = 0; i < m && !suspicious; ++i) {
      const double tol = kTol * sc[j](i) + 1e-300;
      suspicious = (da(i) < 0 || d(i) > 0) &&
                   hermite_min(ga(i), g(i), da(i) * L, d(i) * L) <
                       std::min(-tol, std::min(ga(i), g(i)) - tol);
    }
  }
  const bool guarded = guard_count > 0 && cur->Guard.rows() == guard_count;
  if (guarded) {
    // The guards' values and slopes at the step's end: a control that crosses its threshold
    // and comes back within the step dips like a pair's constraint.
    Eigen::VectorXd gsc;
    guard_values(xb, ggb, gsc);
    gdb.noalias() = cur->GuardM * xb;
    if (j < std::min(stop_level, cur->level + kSuspicionLevels))
      for (int k = 0; k < guard_count && !suspicious; ++k) {
        const double tol = kTol * gsc(k) + 1e-300;
        suspicious = (gda(k) < 0 || gdb(k) > 0) &&
                     hermite_min(gga(k), ggb(k), gda(k) * L, gdb(k) * L) < std::min(-tol, std::min(gga(k), ggb(k)) - tol);
      }
  }
  if (suspicious) return step(j + 1) && step(j + 1);
  X.swap(xb);
  ga.swap(g);
  da.swap(d);
  if (guarded) {
    gga.swap(ggb);
    gda.swap(gdb);
  }
  pos = pos.plus(j);
  for (int i = 0; i < m; ++i)
    if (below_at_start[i] && ga(i) >= -kTol * sc[j](i)) below_at_start[i] = 0;
  return true;
}

// Bisection (8.3.3) on [pos, pos + h0/2^j], whose right end Xb[j] is violated and left end X is
// not: each midpoint is one cached exponential away from the left end. Ends at the right end of
// a bracket of length h0/2^stop_level, the first point known to be past the event, and shorter
// while that point is still past zero by more than rtol (at least the mode check's 1e-9) times
// the size of a constraint's terms:
// in a mode that lasts less than the bracket (a transistor pair switching regeneratively through
// 10 pF, 0.49 A: 4.9e10 V/s for 98 ps, against 3.9 ns at --rtol 1e-3 and a 1 us step) the end
// of the bracket was 190 V past the collector's saturation.
bool EventDriven::Impl::far_past(const Eigen::VectorXd& g, const Eigen::VectorXd& scale) const {
  for (int i = 0; i < m; ++i)
    if (g(i) < -std::max(options.rtol, kZeroTol) * scale(i) &&
        (!below_at_start[i] || g(i) < start_value(i) - 2 * std::max(options.rtol, kZeroTol) * scale(i)))
      return true;
  return false;
}

void EventDriven::Impl::bisect(int j) {
  right = Xb[j];
  right_far = far_past(gb[j], sc[j]);
  while (j < stop_level || (right_far && j < kMaxLevel)) {
    ++j;
    Eigen::VectorXd& mid = Xb[j];
    propagate(*cur, j, X, mid);
    ++stats.steps;
    if (violated(mid, gb[j], sc[j])) {
      right.swap(mid);
      right_far = far_past(gb[j], sc[j]);
    } else {
      X.swap(mid);
      pos = pos.plus(j);
    }
  }
  X.swap(right);
  pos = pos.plus(j);
  event_left = right;  // the left end, swapped out of X
  event_width = std::ldexp(h0, -j);
}

void EventDriven::Impl::check_projected_steps(int level) {
  const double t = pos.seconds(h0);
  const long window = stats.steps - steps_at_last_check;
  const double elapsed = t - t_at_last_check;
  next_projection_check = stats.steps + (1L << 20);
  steps_at_last_check = stats.steps;
  t_at_last_check = t;
  if (!(elapsed > 0) || !(prepared_tstop > t)) return;
  const double projected = static_cast<double>(window) * (prepared_tstop - t) / elapsed;
  if (projected <= options.max_projected_steps) return;
  char buf[400];
  std::snprintf(buf, sizeof buf,
                "the event method would take about %.2g more steps to TSTOP %g s at the pace of its last "
                "%ld (now %.3g s each: a step is at most 0.5/omega of the fastest oscillation of the "
                "circuit and its sources); shorten the .tran or use a fixed step (--method euler --step H)",
                projected, prepared_tstop, window, std::ldexp(h0, -level));
  throw NumericalFailure(t, buf);
}

bool EventDriven::Impl::advance_to(const DyadicTime& target, const Progress& progress) {
  while (pos < target) {
    int j = pos.seconds(h0) - entered_at >= cur->settle_time ? cur->settled_level : cur->level;
    while (j < kMaxLevel && (!pos.aligned(j) || target < pos.plus(j))) ++j;
    if (!step(j)) return false;
    if (progress && (stats.steps & 4095) == 0) progress(pos.seconds(h0));
    if (stats.steps >= next_projection_check) check_projected_steps(j);
  }
  return true;
}

Eigen::VectorXd event_mode_z(const LcsProblem& model, double t0, double h_run, const Eigen::VectorXd& x,
                             const Eigen::VectorXd* op_z) {
  EventDriven::Impl r(model, EventOptions{});
  r.step_levels = false;         // no steps here
  r.prepare(h_run, t0 + h_run);  // sources' breakpoints only as far as the first step
  const std::string signature = r.sources->signature(t0);
  Eigen::VectorXd sigma;
  r.sources->sigma(t0, signature, sigma);
  Mode& md = r.select(t0, x, sigma, signature, nullptr, false, op_z && op_z->size() == r.m ? op_z : nullptr);
  Eigen::VectorXd Xs(r.n + sigma.size());
  Xs << x, sigma;
  return md.Z * Xs;
}

EventDriven::EventDriven(const LcsProblem& model, const EventOptions& options)
    : ContinuousMethod(model), impl_(std::make_unique<Impl>(model, options)) {}

EventDriven::~EventDriven() = default;

StepperStats EventDriven::stats() const {
  StepperStats s = impl_->stats;
  if (impl_->selector) s.lcp = impl_->selector->stats();
  s.cache_budget_bytes = static_cast<long>(impl_->exponentials.budget());
  s.cache_peak_bytes = static_cast<long>(impl_->exponentials.peak_bytes());
  s.cache_evictions = impl_->exponentials.evictions();
  s.mode_cache_budget_bytes = impl_->evict_modes ? static_cast<long>(impl_->options.mode_cache_bytes) : 0;
  s.mode_cache_peak_bytes = static_cast<long>(impl_->mode_bytes_peak);
  s.mode_evictions = impl_->mode_evictions;
  s.mode_rebuilds = impl_->mode_rebuilds;
  return s;
}

void EventDriven::set_guards(const SwitchGuards& guards) {
  impl_->guards = guards;
  impl_->guard_count = static_cast<int>(guards.threshold.size());
  impl_->prepared_tstop = -1;  // the modes are formed again, with their guard rows
}

void EventDriven::DoRun(const Eigen::VectorXd& x0, const OutputGrid& grid, const Emit& emit,
                        const Progress& progress) {
  SegmentStart start;
  start.x = x0;
  if (start_at_rest_) start.op_z = start_z_;
  RunSegment(start, grid, emit, progress);
}

std::optional<GuardCrossing> EventDriven::RunSegment(const SegmentStart& start, const OutputGrid& grid,
                                                     const Emit& emit, const Progress& progress) {
  Impl& r = *impl_;
  if (r.prepared_h0 != grid.tstep || r.prepared_tstop != grid.tstop) {
    r.prepare(grid.tstep, grid.tstop);
    r.prepared_h0 = grid.tstep;
    r.prepared_tstop = grid.tstop;
  }
  r.evict_modes = !r.sources->has_history();
  const double h0 = r.h0;
  const int n = r.n;

  // Stops: source breakpoints, extra output times, and TSTOP when it is not a multiple of TSTEP.
  // Grid times k*h0 are the dyadic times with f = 0. The same for every segment of one grid:
  // built once (a switch on a 100 kHz PULSE starts a segment at every crossing, and sorting the
  // run's 8000 breakpoints for each made the run's cost grow with the square of its length).
  const long kstop = static_cast<long>(std::floor(grid.tstop / h0 * (1 + 1e-12)));
  DyadicTime end{kstop, 0};
  const bool tstop_off_grid = grid.tstop - kstop * h0 > 1e-9 * h0;
  if (tstop_off_grid) end = DyadicTime::from(grid.tstop, h0);
  if (!(r.stops_h0 == h0 && r.stops_tstop == grid.tstop && r.stops_extra == grid.extra)) {
    std::vector<Stop>& stops = r.stops;
    stops.clear();
    for (double b : r.sources->breakpoints()) stops.push_back({DyadicTime::from(b, h0), b, true, false});
    for (double e : grid.extra)
      if (e > 0 && e <= grid.tstop) stops.push_back({DyadicTime::from(e, h0), e, false, true});
    if (tstop_off_grid) stops.push_back({end, grid.tstop, false, true});
    // At one instant the sources' breakpoint comes first, so an output there sees the jump.
    std::sort(stops.begin(), stops.end(), [](const Stop& a, const Stop& b) {
      return a.at < b.at || (a.at == b.at && a.breakpoint && !b.breakpoint);
    });
    r.stops_h0 = h0;
    r.stops_tstop = grid.tstop;
    r.stops_extra = grid.extra;
  }
  const std::vector<Stop>& stops = r.stops;

  Eigen::VectorXd x_out(n), z_out(r.m), sigma;
  // A conducting pair's z (a diode's current) negative beyond 1e-6 of the largest |z| of the run
  // so far means a turn-off was stepped over, not rounding: a 1 pF peak detector behind a 0.1 ohm
  // diode (RON C = 1e-13 s) kept its diode on past the peak and reported -2.9e-7 A and a capacitor
  // at -2.6 V where it holds 4.36 V. Stopped (exit 3; the default run falls back to euler).
  // A pair that has just closed is judged from where it closed: its z there is what the mode
  // check accepted as zero, to kZeroTol of the terms that make it up, and only a fall from
  // there counts. (Judged from zero, a 2-stage multiplier with no load, two diodes grazing their
  // thresholds near the steady state, stopped at 0.17 s on a closing diode's -1.5e-7 A, 9.9e-10
  // of its terms, whose current then rose, as the mode had it; tests/grazing_multiplier_test.cpp.
  // A pair that stays closed through an event keeps zero as its floor: exempting it too let the
  // peak detector with RON = 0.01 keep its diode on at -1.1e-9 A past the peak, 660 times the
  // bound, and end 5.5 mV off with exit 0.) A pair's floor goes back to zero once its current is
  // not negative: a turn-off stepped over after a pulse is judged from zero.
  double largest_z = 0;
  Eigen::VectorXd& z_floor = r.z_floor;
  std::vector<bool>& closed_before = r.closed_at_last_row;
  if (start.t == 0 || z_floor.size() != r.m) {
    z_floor = Eigen::VectorXd::Zero(r.m);
    closed_before.assign(r.m, false);
  }
  auto emit_now = [&](double t, bool event) {
    x_out = r.X.head(n);
    z_out.noalias() = r.cur->Z * r.X;
    for (int i = 0; i < r.m; ++i) largest_z = std::max(largest_z, std::abs(z_out(i)));
    const double tol = std::max(1e-6 * largest_z, 1e-15);
    for (int i = 0; i < r.m; ++i) {
      if (!r.cur->active[i] || z_out(i) >= 0) z_floor(i) = 0;
      else if (!closed_before[i]) z_floor(i) = z_out(i);
      closed_before[i] = r.cur->active[i];
    }
    for (int i = 0; i < r.m; ++i)
      if (r.cur->active[i] && z_out(i) < -tol && z_out(i) < z_floor(i) - tol) {
        char buf[300];
        std::snprintf(buf, sizeof buf,
                      "complementarity pair %d conducts %.3g where its law needs >= 0 (largest |z| of the run "
                      "%.3g): a turn-off was stepped over (a mode stiffer than its constraint rows resolve, e.g. "
                      "RON times a capacitance far below the step)",
                      i + 1, z_out(i), largest_z);
        throw NumericalFailure(t, buf);
      }
    emit(t, x_out, z_out, event);
  };
  // Jumps, then the mode that holds from t on (4.5); X is rebuilt with the sources' form at t.
  // At an event the sources keep the state the bisection propagated (`propagated`, the tail of
  // X, past the event by at most the bracket) when their form has not changed. Read from the
  // waveform at t, a double, they would be those of an instant up to the rounding of t away
  // (ulp(50 us) = 6.8e-21 s, more than the bracket, 2^-43 TSTEP = 5.7e-21 s at a 50 ns step),
  // which can lie before the crossing just located, out of step with x. A VON = 0, RON = 0 diode
  // in series with an inductor, closing where a 1.1e10 V/s PULSE edge crosses zero (w = i = 0,
  // i' = u/L = 0, i'' = u'/L > 0 decides), then read u = -4.4e-11 V where the bisection had
  // +1.8e-11 V: i' negative beyond rounding and the open diode's z falling, no mode fitted
  // (issue 9, circuits/flyback_converter.cir); or, where t rounded further, the open mode did
  // and the next step was the same event again.
  // The impulse (a jump of x) is taken against the same inputs: read at the rounded t, a 1 ps
  // edge (5e12 V/s) had u 8.6e-8 V below the propagated value, and the capacitor an RON = 0
  // diode clamps to it jumped to the read value, off the conducting mode's constraint by as much
  // (EventDriven.SteepEdgeDoesNotSwampTheConsistencyCheck).
  // A segment's start takes the sources' state its predecessor propagated (`from_signature`).
  auto restart = [&](double t, Eigen::VectorXd x, const Eigen::VectorXd* propagated,
                     const std::string* from_signature = nullptr, const Eigen::VectorXd* op_z = nullptr) {
    if (r.evict_modes) r.trim_modes();
    const std::string sig = r.sources->signature(t);
    Mode* before = r.cur;
    const std::string* had = before ? &before->signature : from_signature;
    Eigen::VectorXd sigma, u;
    if (propagated && had && *had == sig) {
      sigma = *propagated;
      u = r.sources->P(sig) * sigma;
    } else {
      r.sources->sigma(t, sig, sigma);
      u = r.model.input_values(t);
    }
    r.apply_impulse(x, u);
    r.cur = &r.select(t, x, sigma, sig, before, propagated != nullptr, op_z);
    r.entered_at = t;
    r.X.resize(n + sigma.size());
    r.X << x, sigma;
    r.project();
    r.refresh_constraints(true);
    return before != nullptr && before->active != r.cur->active;
  };

  // Where a guard is below zero the segment ends: the crossing is the point reached.
  auto crossing = [&](std::vector<int> crossed) {
    GuardCrossing c;
    c.at.at = r.pos;
    c.at.t = r.pos.seconds(h0);
    c.at.x = r.state();
    c.at.signature = r.cur->signature;
    c.at.sigma = r.X.tail(r.X.size() - n);
    c.crossed = std::move(crossed);
    ++r.stats.events;
    return c;
  };

  r.pos = start.at;
  r.cur = nullptr;
  restart(start.t, start.x, start.sigma.size() > 0 ? &start.sigma : nullptr, &start.signature,
          start.op_z.size() == r.m ? &start.op_z : nullptr);
  if (std::vector<int> crossed = r.guards_below(r.X); !crossed.empty()) {
    GuardCrossing c = crossing(std::move(crossed));
    c.at.t = start.t;
    return c;
  }
  emit_now(start.t, start.t > 0);

  // Lines (1.3.3): their history inputs are, on each step, polynomials fitted to the exact past
  // (SourceSystem::fit_history), and that past is this method's own: every advance is one
  // mode, X(s) = exp(M (s - t0)) X(t0), recorded for the waves (a = L X) as an exact segment.
  // A step is halved until the fit is within kHistoryTol of the waves' size; the instants where
  // the waves jump or bend (mode switches, source corners) arrive a delay later as breakpoints.
  DelayHistory* history = r.sources->has_history() ? &r.model.history() : nullptr;
  constexpr double kHistoryTol = 1e-11;
  struct Forget {
    DelayHistory* h;
    ~Forget() {
      if (h) h->forget_segments();  // the segments refer to this run's modes
    }
  } forget{history};
  std::map<const Mode*, Eigen::MatrixXd> wave_rows;  // L of each mode: a = L [x; σ]
  auto wave_row = [&](const Mode* md) -> const Eigen::MatrixXd& {
    auto it = wave_rows.find(md);
    if (it != wave_rows.end()) return it->second;
    const std::vector<DelayedWave>& waves = r.model.delayed();
    const Eigen::MatrixXd P = r.sources->P(md->signature);
    Eigen::MatrixXd L = Eigen::MatrixXd::Zero(waves.size(), md->q);
    for (size_t k = 0; k < waves.size(); ++k) {
      if (n > 0) L.block(k, 0, 1, n) = waves[k].g;
      if (r.m > 0) L.row(k) += waves[k].h * md->Z;
      L.block(k, n, 1, md->q - n) += waves[k].j * P;
    }
    return wave_rows.emplace(md, std::move(L)).first->second;
  };
  // X(s) = exp(M (s - t0)) X(t0) as the product of the mode's cached exp(M h0 / 2^j) over the
  // binary digits of (s - t0) / h0 (to 2^-52 of a step: the rounding of s itself); a segment is
  // at most one step h0 long. The history reads the waves of a segment as Taylor series about
  // anchors taken from that product (taylor_segment.h), or from the product itself where the
  // series would need too many pieces.
  Impl* impl = &r;
  auto record_segment = [&, impl](double t0, const Eigen::VectorXd& X0, Mode* mode, double t1) {
    if (!(t1 > t0)) return;
    const Eigen::MatrixXd* L = &wave_row(mode);
    auto state_at = [impl, mode, X0](double r_seconds) {
      Eigen::VectorXd X = X0, tmp;
      const DyadicTime d = DyadicTime::from(std::max(0.0, r_seconds), impl->h0);
      for (std::int64_t k = 0; k < d.k; ++k) {
        impl->propagate(*mode, 0, X, tmp);
        X.swap(tmp);
      }
      for (int j = 1; j <= 52; ++j)
        if (d.f & (std::uint64_t(1) << (64 - j))) {
          impl->propagate(*mode, j, X, tmp);
          X.swap(tmp);
        }
      return X;
    };
    std::optional<TaylorSegment> taylor;
    if (r.options.history_series) taylor = TaylorSegment::build(mode->M, *L, X0, t1 - t0, state_at);
    if (taylor) {
      auto seg = std::make_shared<const TaylorSegment>(std::move(*taylor));
      history->record_segment(t0, t1, [seg, t0](double s, std::vector<double>& a, std::vector<double>& da) {
        seg->eval(s - t0, a, da);
      });
      ++r.stats.taylor_segments;
      return;
    }
    history->record_segment(t0, t1, [state_at, mode, L, t0](double s, std::vector<double>& a, std::vector<double>& da) {
      const Eigen::VectorXd X = state_at(s - t0);
      const Eigen::VectorXd av = *L * X, dv = *L * (mode->M * X);
      a.assign(av.data(), av.data() + av.size());
      da.assign(dv.data(), dv.data() + dv.size());
    });
    ++r.stats.exact_segments;
  };
  auto next_at_level = [&](int level) {
    DyadicTime c = r.pos;
    if (level >= 64) return c.plus(64);
    if (level > 0) c.f &= ~((std::uint64_t(1) << (64 - level)) - 1);
    else c.f = 0;
    return c.plus(level);
  };

  // Devices with history (lines) cap the step: targets at most h0 / 2^cap_level apart.
  int cap_level = 0;
  while (cap_level < 62 && std::ldexp(h0, -cap_level) > r.model.max_step()) ++cap_level;
  auto accept_here = [&] {
    if (!r.model.has_history()) return;
    x_out = r.X.head(n);
    z_out.noalias() = r.cur->Z * r.X;
    r.model.accept(r.pos.seconds(h0), x_out, z_out);
  };
  accept_here();  // the waves at the start: the history's first sample
  if (history) history->mark_break(0.0);  // the waves start (from their past before the run)

  // The first stop not before the segment.
  size_t next_stop = std::partition_point(stops.begin(), stops.end(), [&](const Stop& s) { return s.at < r.pos; }) -
                     stops.begin();
  int events_here = 0, events_in_storm = 0;
  DyadicTime last_event{-1, 0};
  double last_event_t = -INFINITY;
  DyadicTime last_breakpoint{-1, 0};
  double last_breakpoint_t = 0;
  while (r.pos < end) {
    DyadicTime target{r.pos.k + 1, 0};
    if (next_stop < stops.size() && stops[next_stop].at < target) target = stops[next_stop].at;
    if (end < target) target = end;
    if (cap_level > 0) {
      DyadicTime capped = r.pos;
      capped.f &= ~((std::uint64_t(1) << (64 - cap_level)) - 1);
      capped = capped.plus(cap_level);
      if (capped < target) target = capped;
    }
    bool arrival = false;
    double t_start = 0;
    Eigen::VectorXd X_start;
    Mode* mode_start = nullptr;
    if (history) {
      t_start = r.pos.seconds(h0);
      // A bend that would spoil a fit (kHistoryTol) is a stop where it arrives.
      const double a = history->next_arrival(t_start, target.seconds(h0), 0.1 * kHistoryTol);
      if (std::isfinite(a)) {
        const DyadicTime at = DyadicTime::from(a, h0);
        if (r.pos < at && at <= target) {
          target = at;
          arrival = true;
        }
      }
      int level = 0;
      while (level < 62 && !(next_at_level(level) <= target)) ++level;
      // A step shorter than 1e-7 of the longest a line allows holds the history inputs at their
      // value (a polynomial's powers of its length would reach the double range; the error is
      // the waves' slope times that length). Longer ones are halved until the fit holds, down
      // to that length (a wavefront this method did not stop at).
      const int deepest = std::min(62, std::max(cap_level, 0) + 23);
      Eigen::Ref<Eigen::VectorXd> sigma_now = r.X.tail(r.X.size() - n);
      while (level >= deepest ||
             r.sources->fit_history(t_start, target.seconds(h0), r.cur->signature, sigma_now) > kHistoryTol) {
        if (level >= deepest) {
          r.sources->hold_history(t_start, target.seconds(h0), r.cur->signature, sigma_now);
          break;
        }
        ++level;
        const DyadicTime finer = next_at_level(level);
        if (finer < target) {
          target = finer;
          arrival = false;
        }
      }
      r.project();
      r.refresh_constraints(false);
      X_start = r.X;
      mode_start = r.cur;
    }
    const bool reached = r.advance_to(target, progress);
    if (history) record_segment(t_start, X_start, mode_start, r.pos.seconds(h0));
    accept_here();
    if (!reached) {
      if (std::vector<int> crossed = r.guards_below(r.X); !crossed.empty()) return crossing(std::move(crossed));
      const double t = r.pos.seconds(h0);
      ++r.stats.events;
      events_here = (r.pos.k == last_event.k && r.pos.f - last_event.f < (std::uint64_t(1) << 24))
                        ? events_here + 1
                        : 0;
      last_event = r.pos;
      if (events_here > r.options.max_events_at_one_time)
        throw NumericalFailure(t, "event chattering: more than " +
                                      std::to_string(r.options.max_events_at_one_time) +
                                      " switching events at one instant (grazing contact or a "
                                      "Zeno point)");
      events_in_storm = t - last_event_t < r.options.storm_spacing * h0 ? events_in_storm + 1 : 0;
      last_event_t = t;
      if (events_in_storm > r.options.max_events_in_a_storm) {
        char spacing[32];
        std::snprintf(spacing, sizeof spacing, "%.3g", r.options.storm_spacing * h0);
        throw NumericalFailure(t, "event chattering: more than " + std::to_string(r.options.max_events_in_a_storm) +
                                      " switching events in a row, each less than " + spacing +
                                      " s after the one before (rounding switching a mode back and forth)");
      }
      const Eigen::VectorXd propagated = r.X.tail(r.X.size() - n);
      if (restart(t, r.state(), &propagated)) ++r.stats.mode_switches;
      if (history) history->mark_break(t);
      emit_now(t, true);
      continue;
    }
    if (arrival) {  // a wavefront arrives: the history inputs jump or bend here
      const double t = r.pos.seconds(h0);
      history->mark_break(t);
      if (restart(t, r.state(), nullptr)) {
        ++r.stats.mode_switches;
        ++r.stats.events;
        emit_now(t, true);
      }
    }
    while (next_stop < stops.size() && stops[next_stop].at <= r.pos) {
      const Stop& st = stops[next_stop++];
      if (st.breakpoint) {
        last_breakpoint = r.pos;
        last_breakpoint_t = st.t;
        // The sources change form. The LCS state x = x_phys - Gamma u is continuous across a
        // jump of u (its derivative has no u' term: it is the charge of a capacitor/source
        // loop, the flux of an inductor/source cutset), and x_phys jumps by Gamma du
        // (circuit_model.h), as in the time-stepping methods.
        if (history) history->mark_break(st.t);
        const bool switched = restart(st.t, r.state(), nullptr);
        // A jump of a source can put a switch's control past its threshold: the configuration
        // changes at the breakpoint itself (the next segment takes this stop again).
        if (std::vector<int> crossed = r.guards_below(r.X); !crossed.empty()) {
          GuardCrossing c = crossing(std::move(crossed));
          c.at.t = st.t;
          return c;
        }
        if (switched) {
          ++r.stats.mode_switches;
          ++r.stats.events;
          emit_now(st.t, true);
        }
      }
      if (st.output && !(r.pos.f == 0)) emit_now(st.t, false);
    }
    if (r.pos.f == 0 && r.pos.k <= kstop) {
      // Grid time: the sources' state is reset from the waveforms (no drift over long runs).
      // A breakpoint here has just done so at its own time, which may differ from k h0 in the
      // last bits (5e-6 and 5 * 1e-6): the waveform read at k h0 could be the value before the
      // jump, so the row is that of the breakpoint.
      if (r.pos == last_breakpoint) {
        emit_now(last_breakpoint_t, false);
      } else {
        // The last row is at TSTOP itself: kstop * h0 may differ from it in the last bits
        // (650 * 1e-5 > 6.5e-3).
        const double tg = r.pos == end ? grid.tstop : r.pos.seconds(h0);
        r.sources->sigma(tg, r.cur->signature, sigma);
        r.X.tail(sigma.size()) = sigma;
        r.project();
        r.refresh_constraints(false);
        emit_now(tg, false);
      }
    }
  }
  return std::nullopt;
}

}  // namespace lcs
