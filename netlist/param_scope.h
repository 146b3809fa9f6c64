// Parameters (`.param`, subcircuit `params:` and instance overrides) and the evaluation of values
// written on cards. Internal to the netlist reader.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "netlist/expression.h"
#include "netlist/lexer.h"

namespace lcs::parse {

// One scope of parameters: the top level, or one subcircuit instance (whose parent is the scope
// it was instantiated from). Definitions are evaluated lazily, on first use, in their own scope,
// so a parameter may use another one defined further down; a cycle is an error.
class ParamScope {
 public:
  explicit ParamScope(const ParamScope* parent = nullptr) : parent_(parent) {}

  // `name = <chars [begin, end) of card>`; a later definition of the same name replaces it.
  void define(const std::string& name, const Card* card, int begin, int end);
  void set(const std::string& name, double value);
  bool defines(const std::string& name) const { return defs_.count(name) > 0; }

  // Value of a name here or in an enclosing scope; nullopt when undefined. Throws NetlistError
  // for an error inside the definition, LookupFailure for a cycle.
  std::optional<double> lookup(const std::string& name) const;

  // Evaluates every local definition in definition order (so errors show up in card order).
  void evaluate_all() const;

  // Every parameter and user function seen here (an inner definition hides an outer one), for an
  // expression evaluated after the deck is read (`.meas ... PARAM=`). Call after evaluate_all()
  // on this scope and its parents.
  std::map<std::string, double> visible_values() const;
  std::map<std::string, UserFunction> visible_functions() const;

  // `.func`: a user function of this scope (a later definition of the same name replaces it),
  // and the one a name calls here or in an enclosing scope (nullptr: none).
  void define_function(const std::string& name, UserFunction function);
  const UserFunction* function(const std::string& name) const;

 private:
  struct Def {
    const Card* card = nullptr;  // nullptr: value set directly
    int begin = 0, end = 0;
    mutable std::optional<double> value;
    mutable bool busy = false;
  };
  double evaluate(const std::string& name, const Def& def) const;

  const ParamScope* parent_;
  std::map<std::string, Def> defs_;
  std::vector<std::string> order_;
  std::map<std::string, UserFunction> functions_;
};

// `.func NAME(ARG, ...) {BODY}` (also `= {BODY}`, `'BODY'` or the bare expression): defines
// NAME in `scope`. Throws NetlistError at a malformed definition or a built-in's name.
void define_function(const Card& card, ParamScope& scope);

// Evaluates an expression written at chars [begin, end) of `card` (errors point inside it).
double evaluate_at(const Card& card, int begin, int end, const ParamScope& scope);

// The number written as the token range [first, last) of a card: a plain number (`10uF`) or a
// `{expression}` / `'expression'`. With `bare_expressions` (as in .param and instance parameters)
// an unbraced expression (`2*a`, `sqrt(2)`) is accepted too. Throws NetlistError.
double value_of(const Card& card, std::size_t first, std::size_t last, const ParamScope& scope,
                bool bare_expressions = false);
inline double value_of(const Card& card, std::size_t token, const ParamScope& scope) {
  return value_of(card, token, token + 1, scope);
}

// `name = value` groups of a card's tokens [first, last). A value is one token, or with
// `expressions` (.param, subcircuit parameters) everything up to the next `name =`, a comma or
// the end (commas inside parentheses stay in it), so `a = 2 * b` works. With `allow_flags` a name
// without `=` is a flag (value_first == value_last). Throws NetlistError for anything else.
struct Assignment {
  std::size_t name = 0;  // token index
  std::size_t value_first = 0, value_last = 0;
  bool flag() const { return value_first == value_last; }
};
std::vector<Assignment> split_assignments(const Card& card, std::size_t first, std::size_t last,
                                          bool allow_flags, bool expressions);

// Is this a valid parameter / option name ([a-z_][a-z0-9_]*)?
bool is_identifier(const std::string& lower);

}  // namespace lcs::parse
