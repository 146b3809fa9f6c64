// A large sparse circuit's dense A, B, C, D are formed only when something asks for them (issue
// 12: at 1000 diodes they were 32 MB and a third of a run): formation, the operating point, the
// start, implicit Euler's sparse steps, the output rows and the index report read the sparse
// LCS alone; the dense path forms them on first use, with the same numbers and results.
#include <algorithm>
#include <string>

#include <gtest/gtest.h>

#include "netlist/netlist.h"
#include "solver/integrators/transient.h"
#include "solver/model/circuit_model.h"
#include "solver/model/lcs_index.h"
#include "solver/model/operating_point.h"
#include "solver/model/sparse_lcs.h"

namespace lcs {
namespace {

// An RC line of `n` sections, a clamp diode to 2 V at every node (as `bench --scale ladder`).
std::string clamped_line(int n, bool uic) {
  std::string s = "clamped line\nV1 in 0 SIN(0 5 1k)\nVCL clamp 0 DC 2\n";
  for (int k = 1; k <= n; ++k) {
    const std::string prev = k == 1 ? "in" : "n" + std::to_string(k - 1), node = "n" + std::to_string(k);
    s += "R" + std::to_string(k) + " " + prev + " " + node + " 10\n";
    s += "C" + std::to_string(k) + " " + node + " 0 10p\n";
    s += "D" + std::to_string(k) + " " + node + " clamp dcl\n";
  }
  s += ".model dcl D(VON=0.6 RON=100k)\n.tran 5u 2m" + std::string(uic ? " UIC" : "") + "\n.end\n";
  return s;
}

// `n` half-wave rectifiers on one source, starting from the operating point (DC offset 3 V).
std::string rectifiers(int n) {
  std::string s = "rectifiers\nV1 in 0 SIN(3 10 50)\n";
  for (int k = 1; k <= n; ++k) {
    const std::string id = std::to_string(k);
    s += "RS" + id + " in a" + id + " 1\nD" + id + " a" + id + " o" + id + " drect\n";
    s += "C" + id + " o" + id + " 0 100u\nRL" + id + " o" + id + " 0 " + std::to_string(1000 + 100 * (k % 10)) + "\n";
  }
  s += ".model drect D(VON=0.7 RON=0.1)\n.tran 0.1m 40m\n.end\n";
  return s;
}

CircuitModel model_of(const std::string& text) {
  const Netlist netlist = parse_netlist_string(text, "generated.cir");
  ModelOptions mo;
  mo.t1 = netlist.tran->tstop;
  return CircuitModel::build(netlist, mo);
}

MemorySink run(const CircuitModel& model, bool sparse, TransientSummary* summary = nullptr) {
  TransientOptions o;
  o.method = "euler";
  o.method_options.sparse = sparse;
  o.step = model.netlist().tran->tstep;
  o.tstop = model.netlist().tran->tstop;
  o.uic = model.netlist().tran->uic;
  MemorySink sink;
  const TransientSummary s = run_transient(model, model.output_map(model.default_probes()), o, sink);
  if (summary) *summary = s;
  return sink;
}

double relative_difference(const MemorySink& a, const MemorySink& b) {
  EXPECT_EQ(a.rows.size(), b.rows.size());
  double diff = 0, size = 0;
  for (size_t r = 0; r < std::min(a.rows.size(), b.rows.size()); ++r) {
    diff = std::max(diff, (a.rows[r] - b.rows[r]).cwiseAbs().maxCoeff());
    size = std::max(size, a.rows[r].cwiseAbs().maxCoeff());
  }
  return diff / size;
}

TEST(LazyDenseLcs, ASparseRunNeverFormsTheDenseMatrices) {
  for (const std::string& text : {clamped_line(150, true), clamped_line(150, false), rectifiers(200)}) {
    const CircuitModel model = model_of(text);
    ASSERT_NE(model.sparse_lcs(), nullptr);
    EXPECT_FALSE(model.dense_formed_from_sparse());
    EXPECT_EQ(model.state_count(), model.sparse_lcs()->A.rows());
    EXPECT_EQ(model.pair_count(), model.sparse_lcs()->D.rows());
    TransientSummary summary;
    const MemorySink rows = run(model, true, &summary);
    EXPECT_GE(summary.stepper.sparse.solves, 400);
    EXPECT_EQ(summary.stepper.sparse_fallbacks, 0);
    EXPECT_EQ(rows.rows.size(), 401u);
    EXPECT_FALSE(model.dense_formed_from_sparse()) << model.netlist().title;
    const LcsIndex index = lcs_index(model);
    EXPECT_EQ(index.index, 0);
    EXPECT_EQ(std::count(index.pair_index.begin(), index.pair_index.end(), 0), model.pair_count());
    EXPECT_FALSE(model.dense_formed_from_sparse());
  }
}

TEST(LazyDenseLcs, TheDensePathFormsThemOnFirstUseWithTheSameNumbersAndWaveforms) {
  for (const std::string& text : {clamped_line(150, true), clamped_line(150, false), rectifiers(200)}) {
    const CircuitModel sparse_model = model_of(text), dense_model = model_of(text);
    const MemorySink sparse = run(sparse_model, true);
    TransientSummary summary;
    const MemorySink dense = run(dense_model, false, &summary);
    EXPECT_GT(summary.stepper.lcp.lemke_calls, 0);  // the dense steps ran, modes changed
    EXPECT_TRUE(dense_model.dense_formed_from_sparse());
    EXPECT_LT(relative_difference(sparse, dense), 1e-10) << text.substr(0, 20);
    const SparseLcs& s = *dense_model.sparse_lcs();
    const Lcs& d = dense_model.lcs();
    EXPECT_EQ(d.A, Eigen::MatrixXd(s.A));
    EXPECT_EQ(d.B, Eigen::MatrixXd(s.B));
    EXPECT_EQ(d.C, Eigen::MatrixXd(s.C));
    EXPECT_EQ(d.D, Eigen::MatrixXd(s.D));
    EXPECT_EQ(d.states(), dense_model.state_count());
    EXPECT_EQ(d.pairs(), dense_model.pair_count());
  }
}

// Small circuits keep the dense LCS from formation (no sparse form to defer to).
TEST(LazyDenseLcs, SmallCircuitsFormTheDenseLcsAtOnce) {
  const CircuitModel model = model_of(rectifiers(10));
  EXPECT_EQ(model.sparse_lcs(), nullptr);
  EXPECT_FALSE(model.dense_formed_from_sparse());
  EXPECT_EQ(model.lcs().A.rows(), 10);
  EXPECT_EQ(model.state_count(), 10);
  EXPECT_EQ(model.pair_count(), 10);
}

}  // namespace
}  // namespace lcs
