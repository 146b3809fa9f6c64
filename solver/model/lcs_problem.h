// What the integrators see (chapter 8): the linear complementarity system, its inputs u(t), what
// its states and pairs are, and the hooks of devices with history. Never the netlist: the
// devices (solver/devices) and model formation (circuit_model.h) have turned it into this.
//
//   dx/dt = A x + B z + E u(t),   w = C x + D z + F u(t),   0 <= w ⟂ z >= 0
#pragma once

#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Dense>

#include "solver/model/input_provider.h"
#include "solver/model/pair_law.h"

namespace lcs {

class Device;
struct SparseLcs;
struct SparseDescriptor;

struct Lcs {
  Eigen::MatrixXd A, B, E, C, D, F;
  Eigen::MatrixXd Gamma;  // physical state = x + Gamma u
  int states() const { return static_cast<int>(A.rows()); }
  int pairs() const { return static_cast<int>(D.rows()); }
  int inputs() const { return static_cast<int>(E.cols()); }
};

struct StateInfo {
  int element = -1;
  int branch = -1;
  std::string label;       // "v(c1)", "i(l1)", or "imag(l1)" (below)
  bool capacitor = true;   // a capacitor voltage; else an inductor current
  // Perfectly coupled windings (K ... 1) share one state, the magnetising current referred to
  // `branch`: the sum over `windings` of ratio * i(branch) (the first is `branch` itself, ratio
  // 1; for two windings the second ratio is sqrt(L2/L1)). Empty for every other state.
  std::vector<std::pair<int, double>> windings;  // (inductor branch, ratio)
};

// A wave a line port sends down the line (DelayHistory): a = g x + h z + j u, read back as the
// history input `input` of the LCS `delay` seconds later.
struct DelayedWave {
  int input = -1;
  double delay = 0;
  Eigen::RowVectorXd g, h, j;
  double before = 0;  // its value before a run from rest (UIC): the line's IC=
};

struct PairInfo : PairLaw {
  int branch = -1;
  bool voltage_type = false;  // tree diode: z is the reverse-voltage margin, w the current
};

class LcsProblem {
 public:
  // Polymorphic so that a method's `applies` can ask a circuit (CircuitModel) for its switches.
  LcsProblem() = default;
  LcsProblem(const LcsProblem&) = default;
  LcsProblem(LcsProblem&&) = default;
  LcsProblem& operator=(const LcsProblem&) = default;
  LcsProblem& operator=(LcsProblem&&) = default;
  virtual ~LcsProblem() = default;

  // The dense LCS. A large circuit's A, B, C and D are formed from formation's sparse ones at the
  // first call (O(n^2) bytes: 32 MB at 1000 diodes), so runs that read only the sparse LCS (the
  // sparse step, start and operating point) or the descriptor form (its step and start) never pay
  // for them. E, F and Gamma are always there, except for a circuit whose formation deferred the
  // elimination itself (a multiplier that steps on its descriptor form, circuit_model.cpp): its
  // first call eliminates, then forms. Not thread-safe.
  const Lcs& lcs() const {
    if (!dense_formed_) form_dense();
    return lcs_;
  }
  // The LCS's sizes, without forming the dense matrices.
  int state_count() const;
  int pair_count() const;
  int input_count() const { return make_deferred_ && !deferred_ ? inputs_.size() : lcs_.inputs(); }
  const Eigen::MatrixXd& gamma() const { return lcs_.Gamma; }
  // Whether lcs() has formed the dense A, B, C, D of a circuit whose formation deferred them (a
  // sparse LCS or a descriptor form; tests).
  bool dense_formed_from_sparse() const { return dense_formed_ && deferred_ && !dense_at_formation_; }
  // Whether formation deferred them: false for small circuits, formed dense at once.
  bool dense_deferred() const { return deferred_ != nullptr || make_deferred_ != nullptr; }
  // Whether the elimination to the LCS has run (false only for a circuit whose formation deferred
  // it and that nothing has asked for its LCS yet; tests).
  bool eliminated() const { return !make_deferred_ || deferred_; }
  const std::vector<StateInfo>& states() const { return states_; }
  const std::vector<PairInfo>& pairs() const { return pairs_; }
  const InputProvider& inputs() const { return inputs_; }

  Eigen::VectorXd input_values(double t) const { return inputs_.values(t); }
  void input_values(double t, Eigen::Ref<Eigen::VectorXd> u) const { inputs_.values(t, u); }
  Eigen::VectorXd input_derivatives(double t) const { return inputs_.derivatives(t); }
  Eigen::VectorXd physical_state(const Eigen::VectorXd& x, double t) const;
  Eigen::VectorXd lcs_state(const Eigen::VectorXd& physical, double t) const;

  // Devices with history (transmission lines): the integrators call accept() after every
  // accepted step (it records the waves the line ports send) and never step further than
  // max_step() (the shortest delay). Without lines accept() does nothing and max_step() is
  // infinite. begin_history() sets the waves' past before a run (their values before t0).
  bool has_history() const { return !delayed_.empty(); }
  const std::vector<DelayedWave>& delayed() const { return delayed_; }
  const std::vector<DelayedWave>& dc_relations() const { return dc_relations_; }
  DelayHistory& history() const { return *inputs_.history(); }
  void begin_history(const std::vector<double>& before) const;
  // The waves' values at (t, x, z).
  std::vector<double> waves(double t, const Eigen::VectorXd& x, const Eigen::VectorXd& z) const;
  // Transistor junctions among the pairs: the LCPs may have several solutions (5.4.7).
  bool has_transfer_pairs() const {
    for (const PairInfo& p : pairs_)
      if (p.transfer) return true;
    return false;
  }
  void accept(double t, const Eigen::VectorXd& x, const Eigen::VectorXd& z) const;
  double max_step() const;
  // The LCS stored sparse when it pays (sparse_lcs.h), made once by formation; null for small or
  // dense systems.
  const std::shared_ptr<const SparseLcs>& sparse_lcs() const { return sparse_lcs_; }
  // The circuit in descriptor (node) form when its LCS is dense but the circuit is large and
  // sparse (sparse_descriptor.h): the θ-method steps on it. Null otherwise.
  const std::shared_ptr<const SparseDescriptor>& sparse_descriptor() const { return sparse_descriptor_; }

 protected:
  mutable Lcs lcs_;  // mutable: lcs() forms A, B, C, D of a sparse circuit on first use
  std::vector<StateInfo> states_;
  std::vector<PairInfo> pairs_;
  InputProvider inputs_;
  std::vector<DelayedWave> delayed_;  // one per history input, in DelayHistory order
  std::vector<DelayedWave> dc_relations_;  // as many: rows that vanish at DC (g, h, j; input unused)
  double max_step_ = std::numeric_limits<double>::infinity();
  std::shared_ptr<const SparseLcs> sparse_lcs_;
  std::shared_ptr<const SparseDescriptor> sparse_descriptor_;
  // Formation leaves lcs_.A, B, C, D empty and hands their sparse form (sparse_lcs_, or the LCS
  // of a circuit that steps on its descriptor) to defer_dense; lcs() forms them from it.
  void defer_dense(std::shared_ptr<const SparseLcs> source) {
    deferred_ = std::move(source);
    dense_formed_ = dense_at_formation_ = false;
  }
  // The same with the sparse LCS itself made on first use by `make` (its E and F too).
  void defer_elimination(std::function<std::shared_ptr<const SparseLcs>()> make) {
    make_deferred_ = std::move(make);
    dense_formed_ = dense_at_formation_ = false;
  }

 private:
  void form_dense() const;
  // What lcs() forms A, B, C, D from; null: formed, or not made yet (make_deferred_).
  mutable std::shared_ptr<const SparseLcs> deferred_;
  std::function<std::shared_ptr<const SparseLcs>()> make_deferred_;
  mutable bool dense_formed_ = true;
  bool dense_at_formation_ = true;
};

}  // namespace lcs
