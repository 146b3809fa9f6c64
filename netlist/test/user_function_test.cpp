// `.func NAME(ARGS) {BODY}` (ngspice, LTspice): user functions in expressions. A call binds the
// arguments to the parameter names; other names in the body are looked up where the call is, as
// ngspice expands a .func in place.
#include <gtest/gtest.h>

#include "netlist/netlist.h"
#include "netlist/test/parse_helpers.h"

namespace lcs {
namespace {

TEST(UserFunction, CallsBindArgumentsInEveryWrittenForm) {
  const Netlist n = test::parse(
      "t\n.param r=1k\n"
      ".func double(x) {2*x}\n"
      ".func vth(a, b) = {a + b*0.1}\n"
      ".func half(x) 'x/2'\n"
      ".func cube(x) x*x*x\n"
      "R1 a 0 {double(r)}\n"
      "R2 a b {vth(1, half(2))}\n"
      "R3 b 0 {cube(3) + double(double(1))}\n"
      "V1 a 0 1\n");
  EXPECT_DOUBLE_EQ(test::element(n, "r1").value, 2000.0);
  EXPECT_DOUBLE_EQ(test::element(n, "r2").value, 1.1);
  EXPECT_DOUBLE_EQ(test::element(n, "r3").value, 31.0);
  EXPECT_TRUE(n.warnings.empty());
}

// A function may be defined below its use and use parameters; an argument shadows a parameter of
// the same name; `.param` may call a function.
TEST(UserFunction, ParametersAndFunctionsMeetInBothDirections) {
  const Netlist n = test::parse(
      "t\nR1 a 0 {g(3)}\n.param k=10 x=100\n.param p={g(1)}\nR2 a 0 {p}\n"
      ".func g(x) {k*x}\nV1 a 0 1\n");
  EXPECT_DOUBLE_EQ(test::element(n, "r1").value, 30.0);
  EXPECT_DOUBLE_EQ(test::element(n, "r2").value, 10.0);
}

// Inside a subcircuit, a .func is the instance's own; its free names are the instance's parameters.
TEST(UserFunction, SubcircuitFunctionsAreLocalAndSeeTheInstanceParameters) {
  const Netlist n = test::parse(
      "t\n.func f(x) {x+1}\n"
      ".subckt cell a params: g=2\n.func f(x) {g*x}\nR1 a 0 {f(5)}\n.ends\n"
      "X1 n cell g=3\nX2 n cell\nR9 n 0 {f(5)}\nV1 n 0 1\n");
  EXPECT_DOUBLE_EQ(test::element(n, "x1.r1").value, 15.0);
  EXPECT_DOUBLE_EQ(test::element(n, "x2.r1").value, 10.0);
  EXPECT_DOUBLE_EQ(test::element(n, "r9").value, 6.0);
}

TEST(UserFunction, ConditionsMayCallTopLevelFunctions) {
  const Netlist n = test::parse(
      "t\n.func big(x) {x > 10}\n.param v=20\n.if (big(v))\nR1 a 0 1k\n.else\nR1 a 0 2k\n.endif\nV1 a 0 1\n");
  EXPECT_DOUBLE_EQ(test::element(n, "r1").value, 1000.0);
}

TEST(UserFunction, ErrorsPointAtTheCallOrTheDefinition) {
  EXPECT_EQ(test::diag("t\n.func f(x, y) {x*y}\nR1 a 0 {f(2)}\n"),
            "t.cir:3:9: error: 'f' takes 2 arguments (.func at t.cir:2)\nR1 a 0 {f(2)}\n        ^");
  EXPECT_EQ(test::diag("t\n.func f(x) {x/(x-1)}\nR1 a 0 {f(1)}\n"),
            "t.cir:3:9: error: in function 'f' (.func at t.cir:2): division by zero\nR1 a 0 {f(1)}\n        ^");
  EXPECT_EQ(test::diag("t\n.func f(x) {x*q}\nR1 a 0 {f(1)}\n"),
            "t.cir:3:9: error: in function 'f' (.func at t.cir:2): undefined parameter 'q'\nR1 a 0 {f(1)}\n"
            "        ^");
  EXPECT_EQ(test::diag("t\n.func f(x) {f(x)}\nR1 a 0 {f(1)}\n"),
            "t.cir:3:9: error: in function 'f' (.func at t.cir:2): functions nested too deeply calling 'f' (does it "
            "call itself?)\nR1 a 0 {f(1)}\n"
            "        ^");
  EXPECT_EQ(test::diag("t\n.func f(pi) {pi*2}\n"),
            "t.cir:2:9: error: cannot name an argument 'pi' (the constant)\n.func f(pi) {pi*2}\n        ^~");
  EXPECT_EQ(test::diag("t\n.func sin(x) {x}\n"),
            "t.cir:2:7: error: cannot redefine the built-in function 'sin'\n.func sin(x) {x}\n      ^~~");
  EXPECT_EQ(test::diag("t\n.func f(x, x) {x}\n"),
            "t.cir:2:12: error: argument 'x' named twice\n.func f(x, x) {x}\n           ^");
  EXPECT_EQ(test::diag("t\n.func f(x)\n"),
            "t.cir:2:11: error: missing the body of function 'f'\n.func f(x)\n          ^");
  EXPECT_EQ(test::diag("t\n.func f x\n"),
            "t.cir:2:9: error: expected '(' and the argument names after '.func f'\n.func f x\n        ^");
}

// f_k calls f_(k-1) twice: 2^(k+1) - 1 calls. Up to 100,000 calls an expression is evaluated
// (15 levels, 65,535 calls); past that it is an error at the call, not minutes of work (30
// levels would be two billion calls).
TEST(UserFunction, CallsPerExpressionAreBounded) {
  std::string deck = "t\n.func f0(x) {x+1}\n";
  for (int k = 1; k <= 30; ++k)
    deck += ".func f" + std::to_string(k) + "(x) {f" + std::to_string(k - 1) + "(x)+f" + std::to_string(k - 1) + "(x)}\n";
  const Netlist n = test::parse(deck + "R1 a 0 {f15(1)}\nV1 a 0 1\n");
  EXPECT_DOUBLE_EQ(test::element(n, "r1").value, 65536.0);  // 2^15 (1 + 1)
  EXPECT_EQ(test::diag(deck + "R1 a 0 {f30(1)}\n"),
            "t.cir:33:9: error: more than 100000 function calls in one expression\nR1 a 0 {f30(1)}\n        ^~~");
}

}  // namespace
}  // namespace lcs
