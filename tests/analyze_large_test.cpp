// `analyze` of large sparse circuits (issue 12): the index from sparse Markov parameters and the
// uniqueness report by the blocks of pairs the LCP matrices couple (solver/model/pair_blocks.h),
// never the dense m x m matrices.
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "tests/cli_support.h"

namespace lcs::cli_testing {
namespace {

fs::path write(const std::string& name, const std::string& text) {
  const fs::path dir = scratch_dir("analyze_large_" + name);
  std::ofstream(dir / (name + ".cir")) << text;
  return dir / (name + ".cir");
}

std::string rectifiers(int n) {
  std::string s = "rectifiers\nV1 in 0 SIN(0 10 50)\n";
  for (int k = 1; k <= n; ++k) {
    const std::string id = std::to_string(k);
    s += "RS" + id + " in a" + id + " 1\nD" + id + " a" + id + " o" + id + " drect\n";
    s += "C" + id + " o" + id + " 0 100u\nRL" + id + " o" + id + " 0 " + std::to_string(1000 + 100 * (k % 10)) + "\n";
  }
  return s + ".model drect D(VON=0.7 RON=0.1)\n.tran 0.1m 0.1 UIC\n.end\n";
}

// As `bench --scale ladder`: one 1 kohm, 10 nF line in n sections, a clamp at every node.
std::string ladder(int n, const std::string& ron = "") {
  std::string s = "ladder\nV1 in 0 SIN(0 5 1k)\nVCL clamp 0 DC 2\n";
  for (int k = 1; k <= n; ++k) {
    const std::string prev = k == 1 ? "in" : "n" + std::to_string(k - 1), node = "n" + std::to_string(k);
    s += "R" + std::to_string(k) + " " + prev + " " + node + " " + std::to_string(1000.0 / n) + "\n";
    s += "C" + std::to_string(k) + " " + node + " 0 " + std::to_string(10000.0 / n) + "p\n";
    s += "D" + std::to_string(k) + " " + node + " clamp dcl\n";
  }
  return s + ".model dcl D(VON=0.6 RON=" + (ron.empty() ? std::to_string(1000 * n) : ron) + ")\n.tran 5u 5m UIC\n.end\n";
}

// n storage-free flip-flops (Figure 5.10) on one supply: each has three operating points.
std::string flip_flops(int n) {
  std::string s = "flip-flops\nvs vs 0 5\n";
  for (int k = 1; k <= n; ++k) {
    const std::string id = std::to_string(k), c1 = "c1_" + id, c2 = "c2_" + id, b1 = "b1_" + id, b2 = "b2_" + id;
    s += "r1_" + id + " vs " + c1 + " 1k\nr2_" + id + " vs " + c2 + " 1k\n";
    s += "r3_" + id + " " + c1 + " " + b2 + " 10k\nr4_" + id + " " + c2 + " " + b1 + " 10k\n";
    s += "r5_" + id + " " + b1 + " 0 10k\nr6_" + id + " " + b2 + " 0 10k\n";
    s += "qa" + id + " " + c1 + " " + b1 + " 0 qn\nqb" + id + " " + c2 + " " + b2 + " 0 qn\n";
  }
  return s + ".model qn npn(bf=100 von=0.7)\n.tran 1u 10u\n.end\n";
}

// As `bench --scale cw`: an n-stage Cockcroft-Walton multiplier (2n diodes, 2n capacitors).
std::string multiplier(int n) {
  std::string s = "multiplier\nV1 in 0 SIN(0 100 50)\n";
  for (int k = 1; k <= n; ++k) {
    const std::string ap = k == 1 ? "in" : "a" + std::to_string(k - 1), bp = k == 1 ? "0" : "b" + std::to_string(k - 1);
    const std::string a = "a" + std::to_string(k), b = "b" + std::to_string(k);
    s += "C" + std::to_string(2 * k - 1) + " " + ap + " " + a + " 10u\n";
    s += "D" + std::to_string(2 * k - 1) + " " + bp + " " + a + " dcw\n";
    s += "D" + std::to_string(2 * k) + " " + a + " " + b + " dcw\n";
    s += "C" + std::to_string(2 * k) + " " + bp + " " + b + " 10u\n";
  }
  return s + "RL b" + std::to_string(n) + " 0 1g\n.model dcw D(VON=0.7 RON=1)\n.tran 0.1m 20m UIC\n.end\n";
}

Result analyze(const std::string& name, const std::string& text) {
  const fs::path f = write(name, text);
  return run_lcspice("analyze '" + f.string() + "'", f.parent_path());
}

// 300 rectifiers are 300 blocks of one pair (they meet only at the ideal source): each a
// positive 1 x 1 matrix, so both matrices are P-matrices.
TEST(AnalyzeLarge, RectifierBankIsAPMatrixBlockByBlock) {
  const Result r = analyze("rectifiers", rectifiers(300));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("\n  index: 0\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\n  operating point (D - C A^-1 B), m = 300: a P-matrix: one solution for every q\n"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("\n  implicit Euler step, h = TSTEP = 0.0001 s (D + h C (I - h A)^-1 B), m = 300: a "
                       "P-matrix: one solution for every q\n"),
            std::string::npos)
      << r.out;
}

// The ladder's pairs are one block of 300 (the line couples them all): its symmetric part is
// diagonally dominant (RON = 300 kohm against the line's 1 kohm), so P without the dense matrix;
// the dense test (M + M^T positive definite) said the same.
TEST(AnalyzeLarge, LadderIsAPMatrixByDiagonalDominance) {
  const Result r = analyze("ladder", ladder(300));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("\n  index: 0\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\n  operating point (D - C A^-1 B), m = 300: a P-matrix: one solution for every q\n"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("\n  implicit Euler step, h = TSTEP = 5e-06 s (D + h C (I - h A)^-1 B), m = 300: a "
                       "P-matrix: one solution for every q\n"),
            std::string::npos)
      << r.out;
}

// With RON = 0, D is empty (every clamp's loop is a capacitor and the clamp source): the index
// is 1, from the sparse sum D + CB/s (Eigen's SparseLU never returned on that D: `analyze` hung).
// The 300 pairs are one block, not dominant (the DC matrix is the line's resistance matrix
// min(i, j) R), so the dense block test decides: P.
TEST(AnalyzeLarge, LadderWithoutClampResistanceHasIndexOne) {
  const Result r = analyze("ladder_ron0", ladder(300, "0"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("\n  index: 1\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\n  d300       current  C     1              VON=0.6 V RON=0 ohm\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\n  operating point (D - C A^-1 B), m = 300: a P-matrix: one solution for every q\n"),
            std::string::npos)
      << r.out;
}

// The dominance test of one block of b coupled pairs is b sparse solves, O(b^2) on a ladder
// (25,000 sections took 31 s): past analyze's bound the block is reported not checked, with the
// work it would have taken, in the time the rest of the report takes.
TEST(AnalyzeLarge, LadderTooLargeForTheDominanceTestSaysSo) {
  const Result r = analyze("ladder_10000", ladder(10000));
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string why = ": not checked (a block of 10000 coupled pairs: its diagonal-dominance test needs 10000 "
                          "sparse solves, ";
  const std::size_t op = r.out.find("\n  operating point (D - C A^-1 B), m = 10000" + why);
  ASSERT_NE(op, std::string::npos) << r.out.substr(r.out.find("uniqueness"));
  EXPECT_NE(r.out.find(" entry operations, over analyze's bound of 1e+09)\n", op), std::string::npos);
  EXPECT_NE(r.out.find("\n  implicit Euler step, h = TSTEP = 5e-06 s (D + h C (I - h A)^-1 B), m = 10000" + why),
            std::string::npos);
  const fs::path f = write("ladder_10000_json", ladder(10000));
  const Result json = run_lcspice("analyze --json '" + f.string() + "'", f.parent_path());
  ASSERT_EQ(json.code, 0) << json.err;
  EXPECT_NE(json.out.find("\"verdict\": \"unchecked\""), std::string::npos);
  EXPECT_EQ(json.out.find("\"verdict\": \"P\""), std::string::npos);
}

// 30 flip-flops: 120 pairs, more than the 16 of an exact check of the whole matrix, but blocks
// of 4, each checked exactly: the first names its transistors, as for one flip-flop.
TEST(AnalyzeLarge, FlipFlopsAreFoundNotPInTheirOwnBlock) {
  const Result r = analyze("flip_flops", flip_flops(30));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("\n  operating point (D - C A^-1 B), m = 120: not a P-matrix: the principal minor of "
                       "{qa1:be, qb1:be} is "),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("(transistors qa1 and qb1): several solutions are possible\n"), std::string::npos) << r.out;
}

// A multiplier's LCS is dense (its loops run down the capacitor chains). At 1100 stages, n + m =
// 4400, a dense matrix is 148 MB, over analyze's 128 MB for its O((n + m)^3) reports
// (dense_budget.h): the index and both uniqueness entries say why they were not computed (before,
// 2500 stages took more than 200 s and 3.1 GB), and a loop is shown by its ends (the text was 83 MB).
TEST(AnalyzeLarge, DenseMultiplierOverTheBudgetSaysWhatItDidNotCompute) {
  const Result r = analyze("multiplier", multiplier(1100));
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string why = "the dense LCS of 2200 states and 2200 pairs (148 MB a matrix) is over the 128 MB "
                          "budget for dense matrices";
  EXPECT_NE(r.out.find("\n  index: not computed (" + why + ")\n"), std::string::npos) << r.out.substr(0, 2000);
  EXPECT_NE(r.out.find("\n  operating point (D - C A^-1 B), m = 2200: not checked (" + why + ")\n"), std::string::npos);
  EXPECT_NE(r.out.find("\n  implicit Euler step, h = TSTEP = 0.0001 s (D + h C (I - h A)^-1 B), m = 2200: not "
                       "checked (" + why + ")\n"),
            std::string::npos);
  // d7 closes through c7, c5, c3, c1 down one chain, v1, and c2, c4, c6 up the other; d2200 through
  // all 1100 odd and 1100 even capacitors and v1: 2202 branches.
  EXPECT_NE(r.out.find("\n  d7         D  loop: +d7 -c7 -c5 -c3 -c1 +v1 +c2 +c4 +c6\n"), std::string::npos);
  EXPECT_NE(r.out.find("\n  d2200      D  loop: +d2200 -c2200 -c2198 -c2196 -c2194 -c2192 -c2190 -c2188 -c2186 "
                       "-c2184 -c2182 -c2180 ... (2202 branches in all) ... +c2177 +c2179 +c2181 +c2183 +c2185 "
                       "+c2187 +c2189 +c2191 +c2193 +c2195 +c2197 +c2199\n"),
            std::string::npos);
  EXPECT_LT(r.out.size(), std::size_t{4} << 20);
}

// The methods that work on the dense LCS refuse a circuit whose working set is over the 1 GB
// budget (usage error, exit 1, as any method that does not apply); euler steps on the sparse circuit.
TEST(AnalyzeLarge, DenseMethodsRefuseAMultiplierTooLargeForThem) {
  const fs::path f = write("multiplier_run", multiplier(2500));
  const Result event = run_lcspice("run '" + f.string() + "' --method event -o out.csv", f.parent_path());
  EXPECT_EQ(event.code, 1);
  EXPECT_EQ(event.err, "error: method event: the dense LCS of 5000 states and 5000 pairs (763 MB a matrix, 3 of "
                       "them: 2.2 GB) is over the 1.0 GB budget for dense matrices; methods euler and theta step "
                       "on the sparse circuit\n");
  const Result radau = run_lcspice("run '" + f.string() + "' --method radau5 -o out.csv", f.parent_path());
  EXPECT_EQ(radau.code, 1);
  EXPECT_NE(radau.err.find("(763 MB a matrix, 10 of them: 7.5 GB)"), std::string::npos) << radau.err;
  const Result euler = run_lcspice("run '" + f.string() + "' --method euler -o out.csv", f.parent_path());
  EXPECT_EQ(euler.code, 0) << euler.err;
}

}  // namespace
}  // namespace lcs::cli_testing
