#include "solver/integrators/transient.h"

#include <Eigen/Sparse>

#include "solver/integrators/distinct_rows.h"
#include "solver/integrators/row_writer.h"
#include "solver/integrators/switched_adaptive.h"
#include "solver/integrators/unstable_start.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <map>
#include <memory>
#include <optional>

#include "solver/model/initial_state.h"
#include "solver/model/numerical_failure.h"
#include "solver/model/sparse_lcs.h"
#include "solver/model/switch_family.h"

namespace lcs {

double process_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

bool TransientOptions::IsValid(std::string* why) const {
  auto fail = [why](const std::string& m) {
    if (why) *why = m;
    return false;
  };
  const MethodEntry* entry = find_method(method);
  if (!entry) return fail("unknown method '" + method + "' (known: " + method_names() + ")");
  if (!(step > 0) || !std::isfinite(step)) return fail("the step must be positive");
  if (substeps < 1) return fail("substeps per output step must be at least 1");
  if (!(tstop > 0) || !std::isfinite(tstop)) return fail("TSTOP must be positive");
  if (!(tstart >= 0) || tstart >= tstop) return fail("TSTART must be in [0, TSTOP)");
  if (entry->uses_theta && !(method_options.theta >= 0 && method_options.theta <= 1))
    return fail("--theta must be in [0, 1]");
  if (tstop / step > 2e9) return fail("TSTOP/step is too large (more than 2e9 steps)");
  if (!(method_options.rtol >= 0 && method_options.rtol < 1) || !(method_options.atol >= 0) ||
      !std::isfinite(method_options.atol))
    return fail("--rtol must be in [0, 1) and --atol non-negative");
  return true;
}

std::string TransientSummary::BriefReport() const {
  char buf[512];
  const double hit_rate =
      stepper.lcp.solves > 0 ? 100.0 * stepper.lcp.warm_hits / stepper.lcp.solves : 0.0;
  std::snprintf(buf, sizeof buf, "method %s: %ld steps, %ld rows", method.c_str(), stepper.steps, rows);
  std::string out = buf;
  if (stepper.lcp.solves > 0 || stepper.factorisations > 0) {  // not for the smooth method
    std::snprintf(buf, sizeof buf,
                  ", %ld LCP solves (%.1f%% warm-start hits, %ld Lemke calls, %ld pivots), %d "
                  "factorisations",
                  stepper.lcp.solves, hit_rate, stepper.lcp.lemke_calls, stepper.lcp.lemke_pivots,
                  stepper.factorisations);
    out += buf;
    if (stepper.lcp.pivoted > 0) {  // warm hits missed, answered from the last basis (LcpWarmSolver)
      std::snprintf(buf, sizeof buf, ", %ld pivoted from the last basis (%ld pivots)", stepper.lcp.pivoted,
                    stepper.lcp.pivoted_pivots);
      out += buf;
    }
    if (stepper.lcp.lemke_restarts > 0) {  // rounding broke a path (solve_lemke)
      std::snprintf(buf, sizeof buf, ", %ld Lemke paths restarted on a shifted q", stepper.lcp.lemke_restarts);
      out += buf;
    }
  }
  if (stepper.switching_steps_by_euler > 0) {  // euler_at_switching.h
    std::snprintf(buf, sizeof buf, "\nsteps taken by implicit Euler at stiff mode changes (and the steps after): %ld",
                  stepper.switching_steps_by_euler);
    out += buf;
  }
  if (stepper.sparse.solves > 0 && stepper.descriptor_unknowns > 0) {  // sparse_descriptor.h
    std::snprintf(buf, sizeof buf, "\nstep path: descriptor (node) form, %d unknowns",
                  stepper.descriptor_unknowns);
    out += buf;
  }
  if (stepper.sparse.solves > 0) {
    std::snprintf(buf, sizeof buf,
                  "\nsparse active-set LCP: %ld solves (%.1f%% warm-start hits), %ld pairs flipped, "
                  "%ld factorisations, %.1f MB cached (%ld evicted), %ld steps left to Lemke",
                  stepper.sparse.solves, 100.0 * stepper.sparse.warm_hits / stepper.sparse.solves,
                  stepper.sparse.flips, stepper.sparse.factorisations,
                  stepper.sparse.cache_bytes / 1048576.0, stepper.sparse.evictions,
                  stepper.sparse_fallbacks);
    out += buf;
  }
  if (stepper.events > 0 || stepper.modes > 0) {
    std::snprintf(buf, sizeof buf, "\nevents %ld", stepper.events);
    out += buf;
  }
  if (stepper.modes > 0) {
    std::snprintf(buf, sizeof buf, ", mode switches %ld, distinct modes %d", stepper.mode_switches,
                  stepper.modes);
    out += buf;
  }
  if (stepper.cache_budget_bytes > 0) {
    std::snprintf(buf, sizeof buf, "\nexponential cache: peak %.1f MB of a %.1f MB budget, %ld evictions",
                  stepper.cache_peak_bytes / 1048576.0, stepper.cache_budget_bytes / 1048576.0,
                  stepper.cache_evictions);
    out += buf;
    if (stepper.exponential_actions > 0) {
      std::snprintf(buf, sizeof buf, "; %ld steps by the exponential's action (%ld products)",
                    stepper.exponential_actions, stepper.action_products);
      out += buf;
    }
  }
  if (stepper.mode_cache_peak_bytes > 0) {
    if (stepper.mode_cache_budget_bytes > 0)
      std::snprintf(buf, sizeof buf, "\nmode cache: peak %.1f MB of a %.1f MB budget, %ld evictions, %ld modes built again",
                    stepper.mode_cache_peak_bytes / 1048576.0, stepper.mode_cache_budget_bytes / 1048576.0,
                    stepper.mode_evictions, stepper.mode_rebuilds);
    else
      std::snprintf(buf, sizeof buf, "\nmode cache: peak %.1f MB, no budget (the line history reads every mode)",
                    stepper.mode_cache_peak_bytes / 1048576.0);
    out += buf;
  }
  if (stepper.taylor_segments + stepper.exact_segments > 0) {
    std::snprintf(buf, sizeof buf, "\nline history: %ld segments kept as Taylor series, %ld as exact products",
                  stepper.taylor_segments, stepper.exact_segments);
    out += buf;
  }
  if (stepper.residual_evals > 0) {
    std::snprintf(buf, sizeof buf,
                  "\nresidual evaluations %ld, Jacobians %ld, Newton iterations %ld, rejected steps %ld",
                  stepper.residual_evals, stepper.jacobian_evals, stepper.newton_iterations,
                  stepper.rejected_steps);
    out += buf;
    if (stepper.restarts > 0) {
      std::snprintf(buf, sizeof buf, ", restarts after failed steps %ld", stepper.restarts);
      out += buf;
    }
  }
  std::snprintf(buf, sizeof buf,
                "\nCPU time: setup %.6f s, steps with output %.6f s (%.3f us/step including the "
                "row written at each step)",
                cpu_setup, cpu_steps, stepper.steps > 0 ? 1e6 * cpu_steps / stepper.steps : 0.0);
  return out + buf;
}

namespace {

// Adaptive methods: they step and emit on their own; rows at the same or an earlier time than
// the last (an event on a grid time), or printing alike (DistinctRows), and before TSTART are
// dropped.
void run_adaptive(const CircuitModel& model, const OutputMap& outputs, const TransientOptions& options,
                  const MethodEntry& entry, const InitialState& init, OutputSink& sink,
                  TransientSummary& summary, double cpu0) {
  const Eigen::VectorXd& x0 = init.x;
  std::unique_ptr<ContinuousMethod> method = entry.make_continuous(model, options.method_options);
  if (!options.uic) method->StartAtOperatingPoint(init.held, init.other_starts, init.z);
  OutputGrid grid;
  grid.tstep = options.step;
  grid.tstop = options.tstop;
  grid.extra = options.extra_output_times;
  RowWriter writer(model, outputs, sink);
  DistinctRows rows([&](double t, const Eigen::VectorXd& x, const Eigen::VectorXd& z) {
    writer.write(t, x, z);
    ++summary.rows;
  });
  auto emit = [&](double t, const Eigen::VectorXd& x, const Eigen::VectorXd& z, bool event) {
    if (t >= options.tstart * (1 - 1e-12)) rows.add(t, x, z, event);
  };
  ContinuousMethod::Progress progress;
  if (options.progress) progress = [&](double t) { options.progress(t / options.tstop); };
  const double loop0 = process_cpu_seconds();
  summary.cpu_setup = loop0 - cpu0;
  try {
    method->Run(x0, grid, emit, progress);
    rows.flush();
  } catch (const NumericalFailure&) {
    rows.flush();
    summary.cpu_steps = process_cpu_seconds() - loop0;
    summary.stepper = method->stats();  // the statistics up to the failure
    throw;
  }
  summary.cpu_steps = process_cpu_seconds() - loop0;
  summary.stepper = method->stats();
  for (const std::string& note : method->notes()) summary.warnings.push_back(note);
}

// Fixed-step methods: step k ends at k*h (no accumulated rounding); a last shorter step lands
// on tstop. Devices with history are told of every step, and a step longer than they allow is
// taken as equal substeps (rows stay at the steps), as are `options.substeps` steps per row.
void run_fixed_step(const CircuitModel& model, const OutputMap& outputs, const TransientOptions& options,
                    const MethodEntry& entry, Eigen::VectorXd x, const Eigen::VectorXd& z0,
                    OutputSink& sink, TransientSummary& summary, double cpu0) {
  std::unique_ptr<TimeStepper> stepper = entry.make_stepper(model, options.method_options);
  Eigen::VectorXd z = z0.size() == model.pair_count() ? z0 : Eigen::VectorXd::Zero(model.pair_count());
  auto notes = [&] {
    for (const std::string& n : stepper->notes()) summary.warnings.push_back(n);
  };
  try {
    stepper->Start(0.0, options.step, x, z);
  } catch (const NumericalFailure&) {
    notes();
    throw;
  }
  summary.cpu_setup = process_cpu_seconds() - cpu0;
  const bool history = model.has_history();
  if (history) {
    model.accept(0.0, x, z);  // the lines' first sample: their waves at the start
    std::vector<double> corners = model.inputs().breakpoints(0.0, options.tstop);
    corners.insert(corners.begin(), 0.0);
    model.history().add_kinks(corners, options.tstop);
  }
  RowWriter writer(model, outputs, sink);
  auto emit = [&](double t) {
    writer.write(t, x, z);
    ++summary.rows;
  };
  const double h = options.step;
  const long full_steps = static_cast<long>(std::floor(options.tstop / h * (1 + 1e-12)));
  const bool partial = options.tstop - full_steps * h > 1e-9 * h;
  const long total = full_steps + (partial ? 1 : 0);
  // Lines: no step longer than the shortest delay (max_step). Counted on the longest step taken,
  // min(h, TSTOP), in double: a step of 10 s on a 24 ns run with a 1 ns line asked for 1e10
  // substeps of the step given, past int (a fuzz finding: UBSan's float-cast overflow).
  const double inner = std::min(h, options.tstop) / options.substeps;
  const double per_step = inner > model.max_step() ? std::ceil(inner / model.max_step()) : 1.0;
  if (!(per_step * options.substeps <= 1e9))
    throw NumericalFailure(0.0, "a step of " + std::to_string(std::min(h, options.tstop)) +
                                    " s would take more than 1e9 substeps of the shortest line delay (" +
                                    std::to_string(model.max_step()) + " s)");
  const int substeps = options.substeps * static_cast<int>(per_step);
  const double loop0 = process_cpu_seconds();
  if (options.tstart <= 0) emit(0.0);
  double t = 0.0;
  try {
    for (long k = 1; k <= total; ++k) {
      // Full steps use h itself: k*h - (k-1)*h differs from h in the last bits, and every
      // distinct step size costs a factorisation and a cold warm start.
      const double t_next = k <= full_steps ? k * h : options.tstop;
      const double step = k <= full_steps ? h : t_next - t;
      if (substeps == 1) {
        stepper->Step(t, step, x, z);
        if (history) model.accept(t_next, x, z);
      } else {
        for (int j = 0; j < substeps; ++j) {
          const double tj = j + 1 == substeps ? t_next : t + (j + 1) * (step / substeps);
          stepper->Step(t + j * (step / substeps), step / substeps, x, z);
          if (history) model.accept(tj, x, z);
        }
      }
      t = t_next;
      if (t >= options.tstart * (1 - 1e-12)) emit(t);
      if (options.progress && (k & 4095) == 0) options.progress(t / options.tstop);
    }
  } catch (const NumericalFailure&) {
    summary.cpu_steps = process_cpu_seconds() - loop0;
    summary.stepper = stepper->stats();  // the statistics up to the failure
    notes();
    throw;
  }
  summary.cpu_steps = process_cpu_seconds() - loop0;
  summary.stepper = stepper->stats();
  notes();
}

// The sources' corners within rounding of the grid times a fixed-step run reaches, read a chunk
// of steps at a time (a fast PULSE over 1e7 steps has 2e7 of them).
class SourceCorners {
 public:
  SourceCorners(const InputProvider& inputs, double h) : inputs_(inputs), h_(h) {}
  // The last corner within rounding of tq, and the first.
  std::optional<double> last_near(double tq) { return near(tq, true); }
  std::optional<double> first_near(double tq) { return near(tq, false); }

 private:
  std::optional<double> near(double tq, bool last) {
    // Rounding of the grid times: k h is within some ulps of t, and those grow with t.
    const double w = std::max(1e-9 * h_, 64 * DBL_EPSILON * std::abs(tq));
    if (tq - w <= from_ || tq + w >= to_) {  // breakpoints() gives the open interval
      from_ = tq - 2 * w;
      to_ = tq + 4096 * h_ + 2 * w;
      corners_ = inputs_.breakpoints(from_, to_);
    }
    const auto lo = std::lower_bound(corners_.begin(), corners_.end(), tq - w);
    const auto hi = std::upper_bound(lo, corners_.end(), tq + w);
    if (lo == hi) return std::nullopt;
    return last ? *(hi - 1) : *lo;
  }

  const InputProvider& inputs_;
  double h_;
  double from_ = 0, to_ = -1;
  std::vector<double> corners_;
};

// The fastest rate of a configuration's dynamics with its pairs off, the row-sum norm of A (a
// bound on its spectral radius); infinite where neither A is formed.
double fastest_rate(const CircuitModel& model) {
  if (const std::shared_ptr<const SparseLcs>& s = model.sparse_lcs()) {
    Eigen::VectorXd rows = Eigen::VectorXd::Zero(s->A.rows());
    for (int j = 0; j < s->A.outerSize(); ++j)
      for (Eigen::SparseMatrix<double>::InnerIterator it(s->A, j); it; ++it) rows(it.row()) += std::abs(it.value());
    return rows.size() > 0 ? rows.maxCoeff() : 0.0;
  }
  if (model.dense_deferred()) return INFINITY;
  const Eigen::MatrixXd& A = model.lcs().A;
  return A.size() > 0 ? A.cwiseAbs().rowwise().sum().maxCoeff() : 0.0;
}

// Switches (S, W) with a fixed-step method. Each configuration of the switches is its own model
// (SwitchFamily) with the same states x. After every step the controls are evaluated; when one
// crossed its threshold (VT + VH turning on, VT - VH turning off) the crossing time is located by
// linear interpolation of that control over the step, the step is taken again from its start to
// that time, a row is written there (as for an event), and the run continues in the new
// configuration from the same x (its stepper restarted, so z is consistent with x); one shorter
// step then brings the run back onto the grid of multiples of h. The switching time is exact to
// the linear interpolation of the control over one step (an error of order h^2 where the control
// is smooth), not to a tolerance.
void run_switched_fixed_step(SwitchFamily& family, SwitchConfig config, const OutputMap& base_outputs,
                             const TransientOptions& options, const MethodEntry& entry, Eigen::VectorXd x,
                             const Eigen::VectorXd& z0, OutputSink& sink, TransientSummary& summary,
                             double cpu0) {
  std::vector<Probe> probes;
  for (const std::string& name : base_outputs.names) probes.push_back(parse_probe(name, {}));
  struct Mode {
    const CircuitModel* model = nullptr;
    std::unique_ptr<TimeStepper> stepper;
    // θ < 1: implicit Euler for the steps just after a switching into this configuration, where
    // its dynamics are stiff at h (below); null where they are not.
    std::unique_ptr<TimeStepper> euler;
    OutputMap outputs;
    std::unique_ptr<RowWriter> writer;
  };
  std::map<SwitchConfig, std::unique_ptr<Mode>> modes;
  auto mode = [&](const SwitchConfig& c) -> Mode& {
    auto it = modes.find(c);
    if (it != modes.end()) return *it->second;
    auto m = std::make_unique<Mode>();
    m->model = &family.model(c);
    m->stepper = entry.make_stepper(*m->model, options.method_options);
    const double theta = options.method_options.theta;
    if (entry.uses_theta && theta < 1 && options.step * fastest_rate(*m->model) > 1 / (1 - theta))
      m->euler = find_method("euler")->make_stepper(*m->model, options.method_options);
    m->outputs = m->model->output_map(probes);
    m->writer = std::make_unique<RowWriter>(*m->model, m->outputs, sink);
    return *modes.emplace(c, std::move(m)).first->second;
  };
  long switchings = 0;
  auto collect = [&] {
    StepperStats total;
    for (const auto& [c, m] : modes) {
      const StepperStats s = m->stepper->stats();
      total.steps += s.steps;
      total.lcp += s.lcp;
      total.factorisations += s.factorisations;
      for (const std::string& n : m->stepper->notes()) summary.warnings.push_back(n);
    }
    total.events = switchings;
    total.mode_switches = switchings;
    total.modes = static_cast<int>(modes.size());
    summary.stepper = total;
  };
  Mode* cur = &mode(config);
  const double h = options.step, tstop = options.tstop;
  Eigen::VectorXd z = z0.size() == cur->model->pair_count() ? z0 : Eigen::VectorXd::Zero(cur->model->pair_count());
  double last_row = -1;
  auto emit = [&](double t) {
    if (t <= last_row || t < options.tstart * (1 - 1e-12)) return;
    cur->writer->write(t, x, z);
    last_row = t;
    ++summary.rows;
  };
  const double loop0 = process_cpu_seconds();
  try {
    cur->stepper->Start(0.0, h, x, z);
    summary.cpu_setup = process_cpu_seconds() - cpu0;
    emit(0.0);
    double t = 0.0, switched_at = -1;
    int switches_here = 0, switches_in_step = 0;  // at one instant; since the last grid time
    SourceCorners corners(cur->model->inputs(), h);
    long k = 0;  // the run has reached the grid time k h
    // The steps after a switching into a configuration that is stiff at h are implicit Euler's
    // until one at least h/2 long: the θ-method (θ < 1) is not L-stable, and the fast components
    // a switching starts off their slow manifold ring at R(hλ) near -1 (a flyback whose switch
    // opens with ROFF = 1 Meg against 1 uH of leakage: 58 V for 20 V, i(l1) flipping 10 A each
    // step). SPICE takes the step after a breakpoint by backward Euler for the same reason.
    bool euler_due = false;
    while (t < tstop) {
      const long knext = k + 1;
      // A grid time within rounding of TSTOP is TSTOP: 500000 * 1e-7 is 0.049999999999999996, and
      // a last step of 4e-18 s wrote a second row that prints as t = 0.05 (SPEC 3: times increase).
      const double t_next = knext * h > tstop - 1e-9 * h ? tstop : knext * h;
      const double step = t_next - t;
      Eigen::VectorXd x1 = x, z1 = z;
      const bool by_euler = euler_due && cur->euler;
      auto take_step = [&](double dt, Eigen::VectorXd& xs, Eigen::VectorXd& zs) {
        if (!by_euler) return cur->stepper->Step(t, dt, xs, zs);
        cur->euler->Start(t, h, xs, zs);
        cur->euler->Step(t, dt, xs, zs);
      };
      take_step(step, x1, z1);
      const Eigen::VectorXd c1 = family.controls(config, x1, z1, t_next);
      const SwitchConfig wanted = family.next(config, c1);
      if (wanted == config) {
        x = x1, z = z1, t = t_next, k = knext;
        if (by_euler && step >= 0.5 * h) {  // Euler's steps end: theta from here
          euler_due = false;
          cur->stepper->Start(t, h, x, z);
        }
        switches_in_step = 0;
        emit(t);
        if (options.progress && (k & 4095) == 0) options.progress(t / tstop);
        continue;
      }
      // A source's corner within rounding of a step's end (k h is 4.9999999999999996e-6 where a
      // PULSE's zero-width edge is at 5e-6, and its periods' edges land on either side of the
      // grid): the controls at the step's start are read after the corner's jump, at its end
      // before it, so a switch such an edge turns changes at the edge, not half a step off.
      const std::optional<double> at_start = corners.last_near(t), at_end = corners.first_near(t_next);
      const Eigen::VectorXd c0 = family.controls(config, x, z, at_start ? std::max(t, *at_start) : t);
      const Eigen::VectorXd c1_before =
          at_end ? family.controls(config, x1, z1, std::min(t_next, *at_end), true) : c1;
      const SwitchConfig wanted_before = at_end ? family.next(config, c1_before) : wanted;
      // The earliest crossing among the switches that change, and every switch crossing there.
      const std::vector<SwitchControl>& sw = family.switches();
      std::vector<double> at(sw.size(), INFINITY);
      double tau = t_next;
      for (size_t s = 0; s < sw.size(); ++s) {
        if (wanted[s] == config[s]) continue;
        if (wanted_before[s] == config[s]) {  // turned by the jump at the step's end
          at[s] = t_next;
          continue;
        }
        const double threshold = config[s] ? sw[s].off_below : sw[s].on_above;
        const bool beyond = config[s] ? c0(s) < threshold : c0(s) > threshold;
        const double frac =
            beyond ? 0.0 : std::clamp((c0(s) - threshold) / (c0(s) - c1_before(s)), 0.0, 1.0);
        at[s] = t + frac * step;
        tau = std::min(tau, at[s]);
      }
      if (tau - t > 1e-9 * h) {
        take_step(tau - t, x, z);
        t = tau;
      }
      if (t > switched_at) switched_at = t, switches_here = 0;
      if (++switches_here > 64)
        throw NumericalFailure(t, "the switches change more than 64 times at one instant (chattering: " +
                                      family.describe(config) + ")");
      if (++switches_in_step > 64 * static_cast<int>(config.size()))
        throw NumericalFailure(t, "the switches change more than 64 times each within one step (chattering: " +
                                      family.describe(config) + ")");
      for (size_t s = 0; s < sw.size(); ++s)
        if (at[s] <= tau + 1e-9 * h) config[s] = wanted[s];
      ++switchings;
      cur = &mode(config);
      cur->stepper->Start(t, h, x, z);
      euler_due = true;
      emit(t);
      if (t >= t_next) k = knext, switches_in_step = 0;
    }
  } catch (const NumericalFailure&) {
    summary.cpu_steps = process_cpu_seconds() - loop0;
    collect();
    throw;
  }
  summary.cpu_steps = process_cpu_seconds() - loop0;
  collect();
}

}  // namespace

TransientSummary run_transient(const CircuitModel& model, const OutputMap& outputs,
                               const TransientOptions& options, OutputSink& sink,
                               TransientSummary* failed) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument(why);
  TransientSummary summary;
  summary.method = options.method;
  const double cpu0 = process_cpu_seconds();
  const MethodEntry& entry = *find_method(options.method);
  sink.begin(outputs.names);  // a failure from here on still leaves a (header-only) file
  try {
    SwitchFamily switches(model);
    if (!switches.empty()) {
      if (entry.adaptive() && !entry.make_guarded)
        throw NumericalFailure(0.0, "method " + options.method + " does not locate switch changes (switches: " +
                                        switches.describe(switches.config_of(model)) +
                                        "); use event or a fixed-step method: euler, theta, radau3 or radau5");
      const SwitchConfig start = initial_configuration(switches, switches.config_of(model), options.uic);
      InitialState init = initial_state(switches.model(start), options.uic, 0.0);
      summary.warnings = init.warnings;
      if (entry.make_guarded)
        run_switched_adaptive(switches, start, outputs, options, entry, init, sink, summary, cpu0);
      else
        run_switched_fixed_step(switches, start, outputs, options, entry, init.x, init.z, sink, summary, cpu0);
      sink.finish();
      return summary;
    }
    InitialState init = initial_state(model, options.uic, 0.0);  // also the lines' past
    if (model.has_history()) model.history().set_degree(entry.history_degree);
    summary.warnings = init.warnings;
    if (std::optional<std::string> w = unstable_start_warning(model, init, options.uic, 0.0, options.tstop))
      summary.warnings.push_back(*w);
    if (entry.adaptive())
      run_adaptive(model, outputs, options, entry, init, sink, summary, cpu0);
    else
      run_fixed_step(model, outputs, options, entry, init.x, init.z, sink, summary, cpu0);
  } catch (const NumericalFailure&) {
    if (summary.cpu_setup == 0)  // failed before the stepping loop
      summary.cpu_setup = process_cpu_seconds() - cpu0;
    if (failed) *failed = summary;
    sink.finish();  // the rows computed so far are kept (SPEC §4)
    throw;
  }
  sink.finish();
  return summary;
}

}  // namespace lcs
