// Arithmetic expressions of `.param` and `{...}`: + - * / % (remainder) ^ ** (as ngspice 39.3's
// numparam: left to right, of the base's magnitude: 2^3^2 = 64, (-2)^3 = 8), unary +-,
// parentheses, numbers with SPICE suffixes, parameter names, `pi`, and the functions sqrt sqr exp
// log (natural) ln log10 abs sin cos tan asin acos atan (arctan) sinh cosh tanh asinh acosh atanh
// min max pow pwr floor ceil int nint sgn,
// and ngspice's comparisons == != <> < <= > >=, logic && || (also & |) and !, and if(c, a, b)
// (true is 1, false 0; a condition is true when nonzero). `.func name(a, b) {body}` defines a
// user function: a call binds the arguments to the parameter names and evaluates the body, whose
// other names are looked up where the call is (as ngspice expands a .func in place).
// Internal to the netlist reader.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace lcs::parse {

// An error at [offset, offset + length) of the expression text.
struct ExpressionError {
  int offset = 0;
  int length = 1;
  std::string message;
};

// Thrown by a Lookup that refuses a name it knows (a parameter defined in terms of itself, ...);
// the evaluator reports `message` at the name.
struct LookupFailure {
  std::string message;
};

// Value of a lower-case parameter name; nullopt when it is not defined.
using Lookup = std::function<std::optional<double>(const std::string& name)>;

// A `.func` definition.
struct UserFunction {
  std::vector<std::string> params;  // lower-case, distinct
  std::string body;                 // the expression text
  std::string defined_at;           // "file:line", for errors inside the body
};
// The user function of a lower-case name; nullptr when there is none.
using FunctionLookup = std::function<const UserFunction*(const std::string& name)>;

// Whether `lower` names a built-in function (sqrt, sin, if, ...), which .func may not redefine.
bool is_builtin_function(const std::string& lower);

// Throws ExpressionError; the result is always finite.
double evaluate_expression(std::string_view text, const Lookup& lookup, const FunctionLookup& functions = nullptr);

// Reads all of `text` as evaluate_expression does and throws its ExpressionError for the form
// only (syntax, an unknown function or name, an argument count, nesting), never for the values
// (a division by zero, sqrt of a negative): for an expression whose names get their values later.
void check_expression(std::string_view text, const Lookup& lookup, const FunctionLookup& functions = nullptr);

}  // namespace lcs::parse
