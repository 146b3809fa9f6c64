// libFuzzer target: the first byte picks a method from the registry, the rest is a netlist run
// for at most kMaxSteps output steps. Every row must be finite and times strictly increasing.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string>

#include <Eigen/Eigenvalues>

#include "solver/integrators/method_registry.h"
#include "solver/integrators/transient.h"
#include "solver/model/smooth_netlist.h"
#include "tests/fuzz/fuzz_outcome.h"

namespace {
constexpr double kMaxSteps = 400;
// The event method on a line deck reads its own exact history at every fit. Before those reads
// became Taylor series (taylor_segment.h) they took 1.3-1.4 s per line delay in this build, 97 s
// for tline_diode_termination's 24 delays (a CI timeout); with them, and its runs cut to this many
// delays of the shortest line, the circuits/tline_*.cir seeds take 0.2-3.2 s, an eighth of the
// 25 s hang limit (scripts/fuzz.sh), with their wavefronts, reflections and switchings fuzzed. A
// stiff mode's segments are still read through the exact product (ltra4_1_line.sp).
constexpr double kEventLineDelays = 6;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1 || size > lcs::fuzz::kMaxInputBytes) return 0;
  const std::vector<lcs::MethodEntry>& methods = lcs::method_registry();
  const lcs::MethodEntry& entry = methods[data[0] % methods.size()];
  const std::string text(reinterpret_cast<const char*>(data + 1), size - 1);
  lcs::fuzz::run_expecting_documented_errors([&] {
    lcs::Netlist netlist = lcs::parse_netlist_string(text, "/nonexistent-fuzz-dir/deck.cir");
    if (netlist.elements.size() > lcs::fuzz::kMaxElements || !netlist.tran) return;
    // Methods that keep the dense path on large circuits (radau; the sparse and descriptor steps
    // are the θ-method's) and the adaptive ones get work, not coverage, from the large decks:
    // radau5 on the 64-stage multiplier seed took 6.6 s in this build.
    if (!entry.large_circuit_steps && netlist.elements.size() > lcs::fuzz::kMaxElementsAdaptive) return;
    // The event and smooth methods stop at every source corner: a PULSE train of more periods
    // than this is work in proportion to the deck (1e7 periods: minutes), not a hang to find.
    for (const lcs::Element& e : netlist.elements) {
      const lcs::Waveform& w = e.waveform;
      if (w.kind == lcs::Waveform::Kind::Pulse && w.params.size() >= 7 && w.params[6] > 0 &&
          !(netlist.tran->tstop / w.params[6] <= 10000))
        return;
    }
    // The adaptive methods follow every period of a sine-like source (SIN, AM carrier, SFFM):
    // more than 1000 periods (ngspice's AM/FM example: 6400 of a 100 kHz carrier) is minutes
    // of IDA steps in this build, work in proportion to the deck.
    if (entry.adaptive())
      for (const lcs::Element& e : netlist.elements) {
        const lcs::Waveform& w = e.waveform;
        double f = 0;
        if (w.kind == lcs::Waveform::Kind::Sin && w.params.size() >= 3) f = w.params[2];
        if (w.kind == lcs::Waveform::Kind::Am && w.params.size() >= 5) f = w.params[4] + std::abs(w.params[3]);
        if (w.kind == lcs::Waveform::Kind::Sffm && w.params.size() >= 5)
          f = w.params[2] + std::abs(w.params[3] * w.params[4]);
        if (!(std::abs(f) * netlist.tran->tstop <= 1000)) return;
      }
    // Every method steps at most one line delay at a time: the same for a delay 1e4 times
    // shorter than the run.
    double shortest_delay = std::numeric_limits<double>::infinity();
    for (const lcs::Element& e : netlist.elements) {
      if (e.kind != lcs::ElementKind::Line && e.kind != lcs::ElementKind::LossyLine) continue;
      double delay = e.delay;
      if (e.kind == lcs::ElementKind::LossyLine) {
        const auto it = netlist.line_models.find(e.model);
        if (it != netlist.line_models.end()) delay = it->second.len * std::sqrt(it->second.l * it->second.c);
      }
      const double round_trips = netlist.tran->tstop / delay;
      if (!(round_trips <= 10000)) return;
      shortest_delay = std::min(shortest_delay, delay);
      // A lossy line's fitted kernel is a history read at every step: the adaptive methods'
      // small steps near switchings make that seconds per deck in this build
      // (circuits/tline_lossy_rectifier.cir, 500 round trips, smooth: past the 10 s timeout).
      if (e.kind == lcs::ElementKind::LossyLine && entry.adaptive() && !(round_trips <= 30)) return;
    }
    // Radau's stage LCP on a transistor circuit is checked for several solutions by enumeration
    // at every cold step (warm_solver.cpp, up to 2^(stages x pairs)); with the fuzz step over
    // TSTOP/400 every step is cold: seconds per deck in this build (ngspice's jimi_fuzz.cir with
    // radau5: past the 15 s timeout; 0.33 s for 2400 steps in Release), work, not a hang.
    if (entry.name.rfind("radau", 0) == 0)
      for (const lcs::Element& e : netlist.elements)
        if (e.kind == lcs::ElementKind::Bjt) return;
    lcs::TransientOptions o;
    o.method = entry.name;
    o.tstop = netlist.tran->tstop;
    if (entry.exact_reference && std::isfinite(shortest_delay))  // the event method
      o.tstop = std::min(o.tstop, kEventLineDelays * shortest_delay);
    o.step = std::max(netlist.tran->tstep, o.tstop / kMaxSteps);
    o.uic = netlist.tran->uic;
    std::string why;
    if (!o.IsValid(&why)) return;  // `run` reports these as errors before simulating
    if (entry.smooth_model) netlist = lcs::smooth_netlist(netlist, lcs::SmoothingOptions{});
    lcs::ModelOptions mo;
    mo.t1 = o.tstop;
    const lcs::CircuitModel model = lcs::CircuitModel::build(netlist, mo);
    if (entry.applies && !entry.applies(model, nullptr)) return;  // `run` refuses it (exit 1): SFFM and event
    // IDA follows every period of the circuit's own oscillations too: a lossless LC tank grazing
    // a sharp clamp for 15,900 periods (a seed's TSTOP fuzzed to 1 s) took 8 s in Release and
    // past the 25 s limit here, work in proportion to the deck, as for the sources above.
    if (entry.smooth_model && model.lcs().states() > 0) {
      const Eigen::EigenSolver<Eigen::MatrixXd> modes(model.lcs().A, false);
      const double fastest = modes.eigenvalues().imag().cwiseAbs().maxCoeff();
      if (!(fastest / (2 * M_PI) * o.tstop <= 1000)) return;
    }
    lcs::MemorySink sink;
    lcs::run_transient(model, model.output_map(model.default_probes()), o, sink);
    for (size_t k = 0; k < sink.times.size(); ++k) {
      if (!sink.rows[k].allFinite() || (k > 0 && !(sink.times[k] > sink.times[k - 1]))) {
        std::fprintf(stderr, "fuzz finding: row %zu (t = %g) is not finite or not after the last\n", k,
                     sink.times[k]);
        std::abort();
      }
    }
  });
  return 0;
}
