// One output row of a transient run (y = G x + H z + J u(t) + K u'(t)) written to its sink.
#pragma once

#include <cmath>

#include <Eigen/Dense>

#include "solver/integrators/output_sink.h"
#include "solver/model/circuit_model.h"
#include "solver/model/numerical_failure.h"

namespace lcs {

// One output row y = G x + H z + J u(t) + K u'(t), without allocating.
class RowWriter {
 public:
  RowWriter(const LcsProblem& model, const OutputMap& outputs, OutputSink& sink)
      : model_(model), outputs_(outputs), sink_(sink), y_(outputs.names.size()),
        u_(model.input_count()), has_k_(outputs.K.size() > 0 && !outputs.K.isZero()) {
    // Small output maps are multiplied dense (faster at a handful of entries); large ones sparse,
    // O(probes) per row.
    dense_ = outputs.G.rows() * (outputs.G.cols() + outputs.H.cols()) < kSparseOutputSize;
    if (dense_) {
      Gd_ = Eigen::MatrixXd(outputs.G);
      Hd_ = Eigen::MatrixXd(outputs.H);
    }
  }
  void write(double t, const Eigen::VectorXd& x, const Eigen::VectorXd& z) {
    model_.input_values(t, u_);
    if (dense_) {
      y_.noalias() = Gd_ * x;
      y_.noalias() += Hd_ * z;
    } else {
      y_.noalias() = outputs_.G * x;
      y_.noalias() += outputs_.H * z;
    }
    y_.noalias() += outputs_.J * u_;
    if (has_k_) y_.noalias() += outputs_.K * model_.input_derivatives(t);
    if (!y_.allFinite()) {  // never written: SPEC §3 rows hold numbers
      Eigen::Index k = 0;
      while (std::isfinite(y_(k))) ++k;
      throw NumericalFailure(t, outputs_.names[k] + " is not a finite number");
    }
    sink_.row(t, y_);
  }

 private:
  const LcsProblem& model_;
  static constexpr Eigen::Index kSparseOutputSize = 1 << 16;
  const OutputMap& outputs_;
  Eigen::MatrixXd Gd_, Hd_;
  bool dense_ = true;
  OutputSink& sink_;
  Eigen::VectorXd y_, u_;
  bool has_k_;
};

}  // namespace lcs
