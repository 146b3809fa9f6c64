// The {expression} evaluator on its own: operators, precedence, functions, errors with offsets.
#include "netlist/expression.h"

#include <cmath>
#include <map>

#include <gtest/gtest.h>

namespace lcs::parse {
namespace {

const std::map<std::string, double> kParams = {{"a", 3}, {"b", 1}, {"r_load", 2e3}, {"zero", 0}};

double eval(const std::string& text) {
  return evaluate_expression(text, [](const std::string& name) -> std::optional<double> {
    auto it = kParams.find(name);
    if (it == kParams.end()) return std::nullopt;
    return it->second;
  });
}

ExpressionError error_of(const std::string& text) {
  try {
    eval(text);
  } catch (const ExpressionError& e) {
    return e;
  }
  ADD_FAILURE() << "no error for " << text;
  return {};
}

void expect_error(const std::string& text, int offset, int length, const std::string& message) {
  ExpressionError e = error_of(text);
  EXPECT_EQ(e.message, message) << text;
  EXPECT_EQ(e.offset, offset) << text;
  EXPECT_EQ(e.length, length) << text;
}

TEST(ParseExpression, ArithmeticAndPrecedence) {
  EXPECT_EQ(eval("1+2*3"), 7);
  EXPECT_EQ(eval("(1+2)*3"), 9);
  EXPECT_EQ(eval("10/4"), 2.5);
  EXPECT_EQ(eval("10-4-3"), 3);   // left-associative
  EXPECT_EQ(eval("16/4/2"), 2);
  // ngspice 39.3's numparam (libngspice): powers group left to right, of the base's magnitude.
  EXPECT_EQ(eval("2^3^2"), 64);
  EXPECT_EQ(eval("2**3**2"), 64);
  EXPECT_EQ(eval("2^-1^2"), 0.25);
  EXPECT_EQ(eval("(-2)^3"), 8);
  EXPECT_DOUBLE_EQ(eval("(-8)^(1/3)"), 2);
  EXPECT_EQ(eval("7%3"), 1);  // and ngspice's remainder, <>, sqr, arctan, the inverse hyperbolics
  EXPECT_EQ(eval("-7%3"), -1);
  EXPECT_EQ(eval("7.5%2"), 1.5);
  EXPECT_EQ(eval("2+7%3"), 3);
  EXPECT_EQ(eval("2*7%4"), 2);
  EXPECT_EQ(eval("2<>3"), 1);
  EXPECT_EQ(eval("3<>3"), 0);
  EXPECT_EQ(eval("sqr(-2)"), 4);
  EXPECT_DOUBLE_EQ(eval("arctan(1)"), 0.7853981633974483);
  EXPECT_NEAR(eval("asinh(1)"), 8.8137358702e-01, 1e-11);
  EXPECT_NEAR(eval("acosh(2)"), 1.3169578969e+00, 1e-10);
  EXPECT_NEAR(eval("atanh(0.5)"), 5.4930614433e-01, 1e-11);
  EXPECT_EQ(eval("2**3"), 8);
  EXPECT_EQ(eval("2*3**2"), 18);
  EXPECT_EQ(eval("-2^2"), -4);    // power binds tighter than unary minus
  EXPECT_EQ(eval("2^-1"), 0.5);
  EXPECT_EQ(eval("--3"), 3);
  EXPECT_EQ(eval("+4"), 4);
  EXPECT_EQ(eval("  1 +\t1 "), 2);
}

TEST(ParseExpression, ComparisonsLogicAndIf) {
  EXPECT_EQ(eval("a == 3"), 1);
  EXPECT_EQ(eval("a != 3"), 0);
  EXPECT_EQ(eval("b < a"), 1);
  EXPECT_EQ(eval("a <= 2"), 0);
  EXPECT_EQ(eval("a >= 3"), 1);
  EXPECT_EQ(eval("1 + 1 > 1"), 1);       // arithmetic binds tighter than comparison
  EXPECT_EQ(eval("b > 0 && zero"), 0);
  EXPECT_EQ(eval("b > 0 & a > 2"), 1);   // ngspice's single & and |
  EXPECT_EQ(eval("zero || 2 < 1"), 0);
  EXPECT_EQ(eval("zero | a"), 1);
  EXPECT_EQ(eval("1 || 0 && 0"), 1);     // && binds tighter than ||
  EXPECT_EQ(eval("!zero + 1"), 2);
  EXPECT_EQ(eval("!(a == 3)"), 0);
  EXPECT_EQ(eval("if(a > 2, 10, 20)"), 10);
  EXPECT_EQ(eval("IF ( (zero < 1e-9) , 1e-9, zero )"), 1e-9);
  expect_error("if(1, 2)", 0, 2, "'if' takes 3 arguments");
  expect_error("a <", 3, 1, "unexpected end of expression");
}

// ngspice's conditional operator and the functions its decks use beside if(): values checked
// against libngspice 39 (`.param` then `print`).
TEST(ParseExpression, ConditionalOperatorAndNgspiceFunctions) {
  EXPECT_EQ(eval("a > b ? 1k : 2k"), 1000);
  EXPECT_EQ(eval("a < b ? 1k : 2k"), 2000);
  EXPECT_EQ(eval("zero ? 1 : b ? 2 : 3"), 2);  // right-associative
  EXPECT_EQ(eval("(zero ? 1 : 5) * 2"), 10);
  EXPECT_EQ(eval("1 + 1 == 2 ? a : b"), 3);   // lowest precedence
  EXPECT_EQ(eval("ternary_fcn(a > 2, 10, 20)"), 10);
  EXPECT_EQ(eval("pwr(-8, 2)"), 64);
  EXPECT_NEAR(eval("pwr(-8, 1/3)"), 2, 1e-15);
  EXPECT_EQ(eval("int(-2.7)"), -2);
  EXPECT_EQ(eval("int(2.7)"), 2);
  EXPECT_EQ(eval("nint(2.5)"), 2);
  EXPECT_EQ(eval("nint(3.5)"), 4);
  EXPECT_EQ(eval("nint(-2.6)"), -3);
  EXPECT_EQ(eval("sgn(-0.1)"), -1);
  EXPECT_EQ(eval("sgn(zero)"), 0);
  // The branch not taken is read, and its division by zero is no error (libngspice 39 takes
  // both); the one taken still is.
  EXPECT_EQ(eval("a > 1 ? 1k : 1/(a - 3)*2"), 1000);
  EXPECT_EQ(eval("a < 1 ? 1/(a - 3) : 2k"), 2000);
  EXPECT_EQ(eval("ternary_fcn(a > 1, 1k, 1/zero)"), 1000);
  EXPECT_EQ(eval("if(zero, 1/zero, 5)"), 5);
  expect_error("a > 1 ? 1/zero : 1", 9, 1, "division by zero");
  expect_error("if(1, 1/zero, 5)", 7, 1, "division by zero");
  expect_error("a ? 1", 5, 1, "unexpected end of expression");
  expect_error("a ? 1 , 2", 6, 1, "unexpected ',' in expression");
}

TEST(ParseExpression, NumbersWithSuffixes) {
  EXPECT_EQ(eval("1k*2"), 2000);
  EXPECT_DOUBLE_EQ(eval("2.2u*1meg"), 2.2);
  EXPECT_EQ(eval("10uF"), 1e-5);
  EXPECT_EQ(eval("1e3+1"), 1001);
  EXPECT_EQ(eval(".5*4"), 2);
}

TEST(ParseExpression, ParametersAndPi) {
  EXPECT_EQ(eval("a*2+b"), 7);
  EXPECT_EQ(eval("A*2+B"), 7);  // names are case-insensitive
  EXPECT_EQ(eval("r_load/2"), 1000);
  EXPECT_EQ(eval("pi"), 3.14159265358979323846);
  EXPECT_EQ(eval("PI*2"), 2 * 3.14159265358979323846);
}

TEST(ParseExpression, Functions) {
  EXPECT_EQ(eval("sqrt(16)"), 4);
  EXPECT_EQ(eval("exp(0)"), 1);
  EXPECT_DOUBLE_EQ(eval("log(exp(2))"), 2);  // log is the natural logarithm
  EXPECT_EQ(eval("ln(1)"), 0);
  EXPECT_DOUBLE_EQ(eval("log10(1000)"), 3);
  EXPECT_EQ(eval("abs(-3)"), 3);
  EXPECT_DOUBLE_EQ(eval("sin(pi/2)"), 1);
  EXPECT_EQ(eval("cos(0)"), 1);
  EXPECT_EQ(eval("tan(0)"), 0);
  EXPECT_DOUBLE_EQ(eval("atan(1)*4"), 3.14159265358979323846);
  EXPECT_EQ(eval("min(3,1,2)"), 1);
  EXPECT_EQ(eval("max(3, 7)"), 7);
  EXPECT_EQ(eval("pow(2,10)"), 1024);
  EXPECT_EQ(eval("floor(2.7)"), 2);
  EXPECT_EQ(eval("ceil(2.1)"), 3);
  EXPECT_EQ(eval("SQRT(a*a+4*4)"), 5);
  EXPECT_EQ(eval("max(min(a,b),2)"), 2);
}

TEST(ParseExpression, Errors) {
  expect_error("foo+1", 0, 3, "undefined parameter 'foo'");
  expect_error("2*Foo", 2, 3, "undefined parameter 'Foo'");
  expect_error("1/0", 1, 1, "division by zero");
  expect_error("1/(a-3)", 1, 1, "division by zero");
  expect_error("a/zero", 1, 1, "division by zero");
  expect_error("(1+2", 0, 1, "missing ')'");
  expect_error("sqrt(2", 4, 1, "missing ')'");
  expect_error("1+", 2, 1, "unexpected end of expression");
  expect_error("", 0, 1, "empty expression");
  expect_error("   ", 0, 1, "empty expression");
  expect_error("1 2", 2, 1, "unexpected '2' in expression");
  expect_error("1+*2", 2, 1, "unexpected '*' in expression");
  expect_error("2)", 1, 1, "unexpected ')' in expression");
  expect_error("a#", 1, 1, "unexpected '#' in expression");
  expect_error("bar(1)", 0, 3, "unknown function 'bar'");
  expect_error("sqrt(1,2)", 0, 4, "'sqrt' takes 1 argument");
  expect_error("pow(1)", 0, 3, "'pow' takes 2 arguments");
  expect_error("min()", 0, 3, "'min' takes at least 1 argument");
  expect_error("sqrt(-1)", 0, 4, "invalid argument to 'sqrt'");
  expect_error("1+log(0)", 2, 3, "invalid argument to 'log'");
  expect_error("10^400", 2, 1, "result of '^' is not a finite number");
  expect_error("1e200*1e200", 5, 1, "result of '*' is not a finite number");
  expect_error("1+1e999", 2, 5, "invalid number '1e999'");
}

TEST(ParseExpression, DeepNestingIsAnErrorNotACrash) {
  std::string deep(100000, '(');
  deep += "1";
  deep += std::string(100000, ')');
  EXPECT_EQ(error_of(deep).message, "expression nested too deeply");
  std::string minus(100000, '-');
  EXPECT_EQ(error_of(minus + "1").message, "expression nested too deeply");
  EXPECT_EQ(eval(std::string(50, '(') + "2" + std::string(50, ')')), 2);
}

TEST(ParseExpression, LookupFailureIsReportedAtTheName) {
  ExpressionError e;
  try {
    evaluate_expression("1 + loop", [](const std::string&) -> std::optional<double> {
      throw LookupFailure{"parameter 'loop' is defined in terms of itself"};
    });
  } catch (const ExpressionError& err) {
    e = err;
  }
  EXPECT_EQ(e.offset, 4);
  EXPECT_EQ(e.length, 4);
  EXPECT_EQ(e.message, "parameter 'loop' is defined in terms of itself");
}

}  // namespace
}  // namespace lcs::parse
