#include "solver/integrators/switched_adaptive.h"

#include <algorithm>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include "solver/integrators/distinct_rows.h"
#include "solver/integrators/guarded_method.h"
#include "solver/integrators/row_writer.h"
#include "solver/model/numerical_failure.h"

namespace lcs {

namespace {

// More switch changes than this at one instant are chattering (as run_switched_fixed_step).
constexpr int kMaxChangesAtOneInstant = 64;
// Crossings closer than 2^24 / 2^64 of the output step (2^-40 TSTEP) are one instant: a
// configuration that asks back at once ends its segment a bisection bracket (2^-43 TSTEP at the
// default --rtol) after it began, not at the same dyadic time (the event method's own measure).
constexpr std::uint64_t kSameInstant = std::uint64_t(1) << 24;

// The guards of one configuration: each switch's control, as the model of that configuration
// reads it, against the threshold that would change its state.
SwitchGuards guards_of(const SwitchFamily& family, const CircuitModel& model, const SwitchConfig& config) {
  const std::vector<SwitchControl>& sw = family.switches();
  std::vector<Probe> probes;
  for (const SwitchControl& s : sw) probes.push_back(s.control);
  const OutputMap o = model.output_map(probes);
  const Eigen::Index k = static_cast<Eigen::Index>(sw.size()), inputs = model.input_count();
  SwitchGuards g;
  g.G = Eigen::MatrixXd(o.G);
  g.H = Eigen::MatrixXd(o.H);
  g.J = o.J.rows() == k && o.J.cols() == inputs ? o.J : Eigen::MatrixXd::Zero(k, inputs);
  g.K = o.K.rows() == k && o.K.cols() == inputs ? o.K : Eigen::MatrixXd::Zero(k, inputs);
  g.threshold.resize(k);
  g.sign.resize(k);
  for (Eigen::Index s = 0; s < k; ++s) {
    // The control as the thresholds read it (a matrix without columns has no rows to scale:
    // its data pointer is null, and a row block of it is undefined behaviour).
    for (Eigen::MatrixXd* a : {&g.G, &g.H, &g.J, &g.K})
      if (a->rows() == k && a->cols() > 0) a->row(s) *= sw[s].sign;
    g.threshold(s) = config[s] ? sw[s].off_below : sw[s].on_above;
    g.sign(s) = config[s] ? 1.0 : -1.0;
  }
  return g;
}

}  // namespace

void run_switched_adaptive(SwitchFamily& family, const SwitchConfig& start_config, const OutputMap& outputs,
                           const TransientOptions& options, const MethodEntry& entry, const InitialState& init,
                           OutputSink& sink, TransientSummary& summary, double cpu0) {
  const Eigen::VectorXd& x0 = init.x;
  std::vector<Probe> probes;
  for (const std::string& name : outputs.names) probes.push_back(parse_probe(name, {}));
  // One guarded method per configuration visited: the event method's modes and exponentials
  // serve every later visit (an oscillator cycles through a few configurations).
  struct Configuration {
    const CircuitModel* model = nullptr;
    std::unique_ptr<GuardedMethod> method;
    OutputMap outputs;
    std::unique_ptr<RowWriter> writer;
  };
  std::map<SwitchConfig, std::unique_ptr<Configuration>> visited;
  auto configuration = [&](const SwitchConfig& c) -> Configuration& {
    auto it = visited.find(c);
    if (it != visited.end()) return *it->second;
    auto v = std::make_unique<Configuration>();
    v->model = &family.model(c);
    v->method = entry.make_guarded(*v->model, options.method_options);
    v->method->set_guards(guards_of(family, *v->model, c));
    v->outputs = v->model->output_map(probes);
    v->writer = std::make_unique<RowWriter>(*v->model, v->outputs, sink);
    return *visited.emplace(c, std::move(v)).first->second;
  };
  long changes = 0;
  auto collect = [&] {
    StepperStats total;
    for (const auto& [c, v] : visited) {
      const StepperStats s = v->method->stats();
      total.steps += s.steps;
      total.lcp += s.lcp;
      total.factorisations += s.factorisations;
      total.events += s.events;  // guard crossings among them
      total.mode_switches += s.mode_switches;
      total.modes += s.modes;
      total.cache_budget_bytes = std::max(total.cache_budget_bytes, s.cache_budget_bytes);
      total.cache_peak_bytes += s.cache_peak_bytes;
      total.cache_evictions += s.cache_evictions;
      total.exponential_actions += s.exponential_actions;
      total.action_products += s.action_products;
      total.mode_cache_budget_bytes = std::max(total.mode_cache_budget_bytes, s.mode_cache_budget_bytes);
      total.mode_cache_peak_bytes += s.mode_cache_peak_bytes;
      total.mode_evictions += s.mode_evictions;
      total.mode_rebuilds += s.mode_rebuilds;
      total.taylor_segments += s.taylor_segments;
      total.exact_segments += s.exact_segments;
    }
    total.mode_switches += changes;  // a configuration change is a mode change
    summary.stepper = total;
    for (const auto& [c, v] : visited)
      for (const std::string& note : v->method->run_notes())
        if (std::find(summary.warnings.begin(), summary.warnings.end(), note) == summary.warnings.end())
          summary.warnings.push_back(note);
  };

  SwitchConfig config = start_config;
  Configuration* cur = &configuration(config);
  if (!options.uic) cur->method->start_at_operating_point(init.held, init.other_starts);
  DistinctRows rows([&](double t, const Eigen::VectorXd& x, const Eigen::VectorXd& z) {
    cur->writer->write(t, x, z);
    ++summary.rows;
  });
  auto emit = [&](double t, const Eigen::VectorXd& x, const Eigen::VectorXd& z, bool event) {
    if (t >= options.tstart * (1 - 1e-12)) rows.add(t, x, z, event);
  };
  ContinuousMethod::Progress progress;
  if (options.progress) progress = [&](double t) { options.progress(t / options.tstop); };
  OutputGrid grid;
  grid.tstep = options.step;
  grid.tstop = options.tstop;
  grid.extra = options.extra_output_times;

  const double loop0 = process_cpu_seconds();
  summary.cpu_setup = loop0 - cpu0;
  SegmentStart start;
  start.x = x0;
  if (!options.uic) start.op_z = init.z;
  DyadicTime instant{-1, 0};
  int changes_here = 0;
  try {
    for (;;) {
      std::optional<GuardCrossing> crossing = cur->method->RunSegment(start, grid, emit, progress);
      rows.flush();  // a held row is read through this configuration's outputs
      if (!crossing) break;
      const DyadicTime at = crossing->at.at;
      changes_here = at.k == instant.k && at.f - instant.f < kSameInstant ? changes_here + 1 : 0;
      if (changes_here == 0) instant = at;
      if (changes_here >= kMaxChangesAtOneInstant)
        throw NumericalFailure(crossing->at.t, "the switches change more than " +
                                                   std::to_string(kMaxChangesAtOneInstant) +
                                                   " times at one instant (chattering: " +
                                                   family.describe(config) + ")");
      for (int s : crossing->crossed) config[s] = !config[s];
      ++changes;
      cur = &configuration(config);
      start = std::move(crossing->at);
    }
  } catch (const NumericalFailure&) {
    rows.flush();
    summary.cpu_steps = process_cpu_seconds() - loop0;
    collect();
    throw;
  }
  summary.cpu_steps = process_cpu_seconds() - loop0;
  collect();
}

}  // namespace lcs
