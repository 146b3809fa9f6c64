#include "solver/integrators/unstable_start.h"

#include <algorithm>
#include <cstdio>

#include <Eigen/Eigenvalues>

#include "solver/integrators/mode_dynamics.h"

namespace lcs {

std::optional<std::string> unstable_start_warning(const CircuitModel& model, const InitialState& init,
                                                  bool uic, double t0, double tstop,
                                                  const UnstableStartOptions& options) {
  const int n = model.state_count(), m = model.pair_count();
  if (uic || n == 0 || n > options.max_states || init.z.size() != m || init.x.size() != n) return std::nullopt;
  if (model.dense_deferred()) return std::nullopt;  // its dense LCS is never formed for a run (issue 12)
  if (std::any_of(init.held.begin(), init.held.end(), [](bool h) { return h; })) return std::nullopt;
  // The mode: the pairs that carry z > 0 (a pair at z = 0 with w = 0 is degenerate; it is taken
  // off, as the event method's basis would leave it when its w is not pushed negative).
  const double zmax = m > 0 ? init.z.cwiseAbs().maxCoeff() : 0.0;
  std::vector<bool> active(m, false);
  std::vector<std::string> conducting;
  for (int i = 0; i < m; ++i)
    if (init.z(i) > 1e-12 * zmax && init.z(i) > 0) {
      active[i] = true;
      conducting.push_back(model.pairs()[i].name);
    }
  const ModeDynamics mode = ModeDynamics::build(model.lcs(), active);
  if (!mode.well_posed || mode.Ax.rows() != n) return std::nullopt;
  Eigen::EigenSolver<Eigen::MatrixXd> es(mode.Ax, false);
  if (es.info() != Eigen::Success) return std::nullopt;
  const Eigen::VectorXcd lambda = es.eigenvalues();
  const double largest = lambda.cwiseAbs().maxCoeff();
  double growth = 0;
  for (Eigen::Index k = 0; k < lambda.size(); ++k) growth = std::max(growth, lambda(k).real());
  if (!(growth > 1e-9 * largest) || !(growth * (tstop - t0) > options.visible_growth)) return std::nullopt;
  std::string names;
  const size_t shown = std::min<size_t>(conducting.size(), 6);
  for (size_t k = 0; k < shown; ++k) names += (k ? ", " : "") + conducting[k];
  if (conducting.size() > shown) names += ", ...";
  if (names.empty()) names = "none";
  char rate[96];
  std::snprintf(rate, sizeof rate, "%.3g/s (time constant %.3g s)", growth, 1 / growth);
  return "the operating point is an unstable equilibrium: in its mode (conducting: " + names +
         ") a deviation grows at " + rate +
         "; the run leaves it where the sources push it or where rounding does, and rounding's "
         "time and direction are arbitrary (in ngspice too): give .ic values that start the circuit "
         "for a reproducible answer";
}

}  // namespace lcs
