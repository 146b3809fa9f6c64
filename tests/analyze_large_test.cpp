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

}  // namespace
}  // namespace lcs::cli_testing
