#include "solver/integrators/diode_refit.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "solver/devices/bjt.h"
#include "solver/devices/diode.h"
#include "solver/model/netlist_options.h"
#include "solver/model/numerical_failure.h"

namespace lcs {

CurrentRange conducting_range(std::vector<double> samples, double low_quantile) {
  double peak = 0;
  for (double i : samples) peak = std::max(peak, i);
  const double floor = std::max(1e-6 * peak, 1e-13);
  const size_t all = samples.size();
  samples.erase(std::remove_if(samples.begin(), samples.end(), [&](double i) { return !(i > floor); }),
                samples.end());
  if (samples.empty()) return {};
  CurrentRange range;
  range.always_on = samples.size() == all;
  range.least = *std::min_element(samples.begin(), samples.end());
  const size_t k = static_cast<size_t>(low_quantile * static_cast<double>(samples.size() - 1));
  std::nth_element(samples.begin(), samples.begin() + k, samples.end());
  range.lo = samples[k];
  range.hi = peak;
  return range;
}

namespace {

bool moved(const IdealDiodeLaw& before, const IdealDiodeLaw& after, const DiodeRefitOptions& o) {
  return std::abs(after.von - before.von) > o.von_tolerance ||
         std::abs(after.ron - before.ron) > o.ron_tolerance * std::abs(before.ron);
}

ResolvedDiodeLaw resolve(const FittedJunction& j, double ifit, const CurrentRange& range) {
  return j.breakdown ? resolve_breakdown_law(j.card, ifit, range) : resolve_diode_law(j.card, ifit, range);
}

// A D card with neither VON nor RON, or a transistor card whose junction has neither: the only
// cards whose laws are fitted (no model is formed for a circuit without any).
bool has_fitted_card(const Netlist& netlist) {
  return std::any_of(netlist.elements.begin(), netlist.elements.end(), [&](const Element& el) {
    if (el.kind == ElementKind::Diode) {
      const auto card = netlist.diode_models.find(el.model);
      return card != netlist.diode_models.end() && !card->second.von && !card->second.ron;
    }
    if (el.kind == ElementKind::Bjt) {
      const auto card = netlist.bjt_models.find(el.model);
      if (card == netlist.bjt_models.end()) return false;
      for (Junction j : {Junction::BaseEmitter, Junction::BaseCollector}) {
        const DiodeModel d = junction_card(card->second, j, 1.0);
        if (!d.von && !d.ron) return true;
      }
    }
    return false;
  });
}

}  // namespace

DiodeRefitResult refit_diodes(const Netlist& netlist, const ModelOptions& model_options,
                              const TransientOptions& options, const DiodeRefitOptions& refit) {
  DiodeRefitResult result;
  if (!has_fitted_card(netlist)) return result;
  const double cpu0 = process_cpu_seconds();
  ModelOptions mo = model_options;
  mo.ifit = read_netlist_options(netlist).ifit.value_or(mo.ifit);  // as CircuitModel::build reads it
  // The ranges the last pass that reached TSTOP ran with: the fallback when a later pass fails.
  std::map<std::string, DiodeCurrentRanges> completed = mo.diode_ranges;
  for (int pass = 1; pass <= refit.max_passes; ++pass) {
    const CircuitModel model = CircuitModel::build(netlist, mo);
    std::vector<FittedJunction> junctions;
    std::vector<Probe> probes;
    for (const std::shared_ptr<Device>& d : model.devices())
      for (FittedJunction& j : d->fitted_junctions()) {
        Probe p;
        p.kind = Probe::Kind::ElementCurrent;
        p.a = j.probe;
        probes.push_back(p);
        junctions.push_back(std::move(j));
      }
    if (junctions.empty()) break;
    const OutputMap outputs = model.output_map(probes);
    MemorySink sink;
    TransientOptions quiet = options;
    quiet.progress = nullptr;
    ++result.passes;
    try {
      run_transient(model, outputs, quiet, sink);
    } catch (const NumericalFailure& e) {
      bool recovered = false;
      if (refit.fallback) {
        TransientOptions again = *refit.fallback;
        again.progress = nullptr;
        sink = MemorySink();
        try {
          run_transient(model, outputs, again, sink);
          recovered = true;
          ++result.fallbacks;
        } catch (const NumericalFailure&) {
        }
      }
      if (!recovered) {
        result.failure = e.what();
        break;
      }
    }
    completed = mo.diode_ranges;  // before this pass's refit
    bool any_moved = false;
    for (size_t k = 0; k < junctions.size(); ++k) {
      const FittedJunction& j = junctions[k];
      std::vector<double> carried;
      carried.reserve(sink.rows.size());
      for (const Eigen::VectorXd& row : sink.rows) carried.push_back(j.sign * row(static_cast<int>(k)));
      const CurrentRange range = conducting_range(carried, refit.low_quantile);
      if (range.empty()) continue;  // it did not conduct: its previous range stays
      DiodeCurrentRanges& ranges = mo.diode_ranges[j.range_key];
      (j.breakdown ? ranges.reverse : ranges.forward) = range;
      if (moved(j.law, resolve(j, mo.ifit, range).law, refit)) any_moved = true;
    }
    if (!any_moved) {
      result.converged = true;
      break;
    }
  }
  // Not converged: the refitted ranges never ran (and a TTL adder's have no operating point).
  result.ranges = result.converged ? mo.diode_ranges : completed;
  result.cpu_seconds = process_cpu_seconds() - cpu0;
  return result;
}

std::string DiodeRefitResult::BriefReport() const {
  char buf[200];
  std::snprintf(buf, sizeof buf, "diode refit: %d transient pass%s, %s, %.3g s CPU", passes,
                passes == 1 ? "" : "es", converged ? "converged" : "not converged", cpu_seconds);
  std::string out = buf;
  if (fallbacks > 0) out += "; " + std::to_string(fallbacks) + " pass" + (fallbacks == 1 ? "" : "es") + " by the fallback method";
  return out + (failure.empty() ? "" : "; a pass failed (" + failure + ")");
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
