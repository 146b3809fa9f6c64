#include "solver/integrators/diode_refit.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "solver/devices/diode.h"
#include "solver/model/netlist_options.h"
#include "solver/model/numerical_failure.h"

namespace lcs {

CurrentRange conducting_range(std::vector<double> samples, double low_quantile) {
  double peak = 0;
  for (double i : samples) peak = std::max(peak, i);
  const double floor = std::max(1e-6 * peak, 1e-13);
  samples.erase(std::remove_if(samples.begin(), samples.end(), [&](double i) { return !(i > floor); }),
                samples.end());
  if (samples.empty()) return {};
  const size_t k = static_cast<size_t>(low_quantile * static_cast<double>(samples.size() - 1));
  std::nth_element(samples.begin(), samples.begin() + k, samples.end());
  return {samples[k], peak};
}

namespace {

struct Refitted {
  const Diode* diode;
  int column;  // of i(diode) in the pass's rows
};

bool moved(const ResolvedDiodeLaw& before, const ResolvedDiodeLaw& after, const DiodeRefitOptions& o) {
  if (!before.fitted) return false;
  return std::abs(after.law.von - before.law.von) > o.von_tolerance ||
         std::abs(after.law.ron - before.law.ron) > o.ron_tolerance * std::abs(before.law.ron);
}

}  // namespace

DiodeRefitResult refit_diodes(const Netlist& netlist, const ModelOptions& model_options,
                              const TransientOptions& options, const DiodeRefitOptions& refit) {
  DiodeRefitResult result;
  // No D card without VON/RON (or with BV and no VON/RON/Rrev): nothing to fit, no model to form.
  const bool any = std::any_of(netlist.elements.begin(), netlist.elements.end(), [&](const Element& el) {
    if (el.kind != ElementKind::Diode) return false;
    const auto card = netlist.diode_models.find(el.model);
    return card != netlist.diode_models.end() && !card->second.von && !card->second.ron;
  });
  if (!any) return result;
  const double cpu0 = process_cpu_seconds();
  ModelOptions mo = model_options;
  mo.ifit = read_netlist_options(netlist).ifit.value_or(mo.ifit);  // as CircuitModel::build reads it
  for (int pass = 1; pass <= refit.max_passes; ++pass) {
    const CircuitModel model = CircuitModel::build(netlist, mo);
    std::vector<Refitted> diodes;
    std::vector<Probe> probes;
    for (const std::shared_ptr<Device>& d : model.devices()) {
      const auto* diode = dynamic_cast<const Diode*>(d.get());
      if (!diode || !(diode->law().fitted || (diode->breakdown() && diode->breakdown()->fitted))) continue;
      Probe p;
      p.kind = Probe::Kind::ElementCurrent;
      p.a = diode->name();
      diodes.push_back({diode, static_cast<int>(probes.size())});
      probes.push_back(p);
    }
    if (diodes.empty()) break;
    const OutputMap outputs = model.output_map(probes);
    MemorySink sink;
    TransientOptions quiet = options;
    quiet.progress = nullptr;
    ++result.passes;
    try {
      run_transient(model, outputs, quiet, sink);
    } catch (const NumericalFailure& e) {
      result.failure = e.what();
      break;
    }
    // i(d) is the forward minus the breakdown current; the two never conduct together.
    bool any_moved = false;
    for (const Refitted& r : diodes) {
      std::vector<double> forward, reverse;
      for (const Eigen::VectorXd& row : sink.rows) {
        forward.push_back(row(r.column));
        reverse.push_back(-row(r.column));
      }
      DiodeCurrentRanges& ranges = mo.diode_ranges[r.diode->name()];
      if (r.diode->law().fitted) {
        const CurrentRange f = conducting_range(forward, refit.low_quantile);
        if (!f.empty()) ranges.forward = f;
      }
      if (r.diode->breakdown() && r.diode->breakdown()->fitted) {
        const CurrentRange b = conducting_range(reverse, refit.low_quantile);
        if (!b.empty()) ranges.reverse = b;
      }
      const DiodeModel& card = r.diode->card();
      if (moved(r.diode->law(), resolve_diode_law(card, mo.ifit, ranges.forward), refit)) any_moved = true;
      if (r.diode->breakdown() &&
          moved(*r.diode->breakdown(), resolve_breakdown_law(card, mo.ifit, ranges.reverse), refit))
        any_moved = true;
    }
    if (!any_moved) {
      result.converged = true;
      break;
    }
  }
  result.ranges = mo.diode_ranges;
  result.cpu_seconds = process_cpu_seconds() - cpu0;
  return result;
}

std::string DiodeRefitResult::BriefReport() const {
  char buf[200];
  std::snprintf(buf, sizeof buf, "diode refit: %d transient pass%s, %s, %.3g s CPU", passes,
                passes == 1 ? "" : "es", converged ? "converged" : "not converged", cpu_seconds);
  return buf;
}

// 5 % of a junction's voltage is about 30 mV at 0.6 V, 1.2 Vt: an exponential junction's
// current changes e^1.2 = 3.3-fold over that, so a line this far off puts the current it claims
// more than three times away from the curve's somewhere in the range; and in a circuit whose
// sources are a volt or two, 30 mV is already 1.5-3 % of every node voltage.
std::vector<std::string> poorly_fitted_pairs(const CircuitModel& model) {
  std::vector<std::string> out;
  for (const PairInfo& p : model.pairs())
    if (p.fitted && p.circuit_fit && p.fit_error_fraction > kPoorFitFraction) out.push_back(p.name);
  return out;
}

std::string poor_fit_message(const CircuitModel& model) {
  std::string names;
  double worst = 0, worst_mv = 0;
  for (const PairInfo& p : model.pairs()) {
    if (!(p.fitted && p.circuit_fit && p.fit_error_fraction > kPoorFitFraction)) continue;
    names += (names.empty() ? "" : ", ") + p.name;
    if (p.fit_error_fraction > worst) {
      worst = p.fit_error_fraction;
      worst_mv = p.fit_error * 1e3;
    }
  }
  if (names.empty()) return "";
  char buf[160];
  std::snprintf(buf, sizeof buf, " (worst %.3g mV, %.3g %% of the diode's voltage; bound %g %%)",
                worst_mv, 100 * worst, 100 * kPoorFitFraction);
  return "the ideal law fitted to the currents of " + names +
         " is poor over the range they carry" + buf +
         ": use --diode auto (Shockley diodes where the fit is poor), --diode shockley, or give "
         "VON/RON on the card";
}

}  // namespace lcs
