// Arithmetic expressions of `.param` and `{...}`: + - * / ^ ** (right-associative), unary +-,
// parentheses, numbers with SPICE suffixes, parameter names, `pi`, and the functions sqrt exp
// log (natural) ln log10 abs sin cos tan asin acos atan sinh cosh tanh min max pow floor ceil,
// and ngspice's comparisons == != < <= > >=, logic && || (also & |) and !, and if(c, a, b)
// (true is 1, false 0; a condition is true when nonzero).
// Internal to the netlist reader.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <string_view>

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

// Throws ExpressionError; the result is always finite.
double evaluate_expression(std::string_view text, const Lookup& lookup);

}  // namespace lcs::parse
