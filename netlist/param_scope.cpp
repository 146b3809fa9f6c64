#include "netlist/param_scope.h"

#include <cctype>
#include <string>

#include "netlist/expression.h"
#include "netlist/number.h"

namespace lcs::parse {
namespace {

// Lazy evaluation recurses through definitions; a long backward chain must not blow the stack.
constexpr int kMaxNesting = 500;
thread_local int nesting = 0;

struct NestingGuard {
  NestingGuard() {
    if (++nesting > kMaxNesting) {
      --nesting;
      throw LookupFailure{"parameters nested too deeply"};
    }
  }
  ~NestingGuard() { --nesting; }
};

}  // namespace

void ParamScope::define(const std::string& name, const Card* card, int begin, int end) {
  if (!defs_.count(name)) order_.push_back(name);
  Def& d = defs_[name];
  d.card = card;
  d.begin = begin;
  d.end = end;
  d.value.reset();
}

void ParamScope::set(const std::string& name, double value) {
  if (!defs_.count(name)) order_.push_back(name);
  Def& d = defs_[name];
  d.card = nullptr;
  d.value = value;
}

std::optional<double> ParamScope::lookup(const std::string& name) const {
  for (const ParamScope* s = this; s; s = s->parent_) {
    auto it = s->defs_.find(name);
    if (it != s->defs_.end()) return s->evaluate(name, it->second);
  }
  return std::nullopt;
}

double ParamScope::evaluate(const std::string& name, const Def& def) const {
  if (def.value) return *def.value;
  if (def.busy) throw LookupFailure{"parameter " + quote(name) + " is defined in terms of itself"};
  NestingGuard guard;
  def.busy = true;
  try {
    def.value = evaluate_at(*def.card, def.begin, def.end, *this);
  } catch (...) {
    def.busy = false;
    throw;
  }
  def.busy = false;
  return *def.value;
}

void ParamScope::evaluate_all() const {
  for (const std::string& name : order_) {
    try {
      evaluate(name, defs_.at(name));
    } catch (const LookupFailure& f) {
      const Def& d = defs_.at(name);
      throw NetlistError(d.card->span(d.begin, d.end), f.message);
    }
  }
}

std::map<std::string, double> ParamScope::visible_values() const {
  std::map<std::string, double> out;
  for (const ParamScope* s = this; s; s = s->parent_)
    for (const auto& [name, def] : s->defs_) out.emplace(name, s->evaluate(name, def));
  return out;
}

std::map<std::string, UserFunction> ParamScope::visible_functions() const {
  std::map<std::string, UserFunction> out;
  for (const ParamScope* s = this; s; s = s->parent_) out.insert(s->functions_.begin(), s->functions_.end());
  return out;
}

void ParamScope::define_function(const std::string& name, UserFunction function) {
  functions_[name] = std::move(function);
}

const UserFunction* ParamScope::function(const std::string& name) const {
  for (const ParamScope* s = this; s; s = s->parent_) {
    auto it = s->functions_.find(name);
    if (it != s->functions_.end()) return &it->second;
  }
  return nullptr;
}

void define_function(const Card& card, ParamScope& scope) {
  if (card.size() < 2 || !card[1].is_word())
    throw NetlistError(card.size() < 2 ? card.after_last() : card.at(1), "expected a function name after '.func'");
  const Token& name = card[1];
  if (!is_identifier(name.lower)) throw NetlistError(card.at(name), "invalid function name " + quote(name.text));
  if (is_builtin_function(name.lower))
    throw NetlistError(card.at(name), "cannot redefine the built-in function " + quote(name.text));
  if (card.size() < 3 || !card[2].is(Token::Kind::LParen))
    throw NetlistError(card.size() < 3 ? card.after_last() : card.at(2),
                       "expected '(' and the argument names after '.func " + name.text + "'");
  UserFunction f;
  std::size_t i = 3;
  while (i < card.size() && !card[i].is(Token::Kind::RParen)) {
    const Token& arg = card[i];
    if (!arg.is_word() || !is_identifier(arg.lower))
      throw NetlistError(card.at(arg), "expected an argument name, got " + quote(arg.text));
    if (arg.lower == "pi") throw NetlistError(card.at(arg), "cannot name an argument 'pi' (the constant)");
    for (const std::string& p : f.params)
      if (p == arg.lower) throw NetlistError(card.at(arg), "argument " + quote(arg.text) + " named twice");
    f.params.push_back(arg.lower);
    ++i;
    if (i < card.size() && card[i].is(Token::Kind::Comma)) ++i;
  }
  if (i >= card.size()) throw NetlistError(card.after_last(), "missing ')' after the arguments of " + quote(name.text));
  ++i;  // past ')'
  if (i < card.size() && card[i].is(Token::Kind::Equals)) ++i;
  if (i >= card.size()) throw NetlistError(card.after_last(), "missing the body of function " + quote(name.text));
  const Token& first = card[i];
  if (i + 1 == card.size() && first.is_expression())
    f.body = first.text;
  else
    f.body = card.text(first.begin, card.tokens.back().end);
  const SourceLocation loc = card.at(0);
  f.defined_at = loc.file + ":" + std::to_string(loc.line);
  scope.define_function(name.lower, std::move(f));
}

double evaluate_at(const Card& card, int begin, int end, const ParamScope& scope) {
  try {
    return evaluate_expression(std::string_view(card.chars).substr(begin, end - begin),
                               [&](const std::string& name) { return scope.lookup(name); },
                               [&](const std::string& name) { return scope.function(name); });
  } catch (const ExpressionError& e) {
    throw NetlistError(card.span(begin + e.offset, begin + e.offset + e.length), e.message);
  }
}

namespace {

// `4k7`, `2u2`, `1R5`: the suffix in place of the decimal point (European schematics; LTspice
// reads 4k7 as 4.7k, ngspice as 4k). Neither is guessed here: the message says how to write it.
std::string decimal_in_suffix_hint(const std::string& text) {
  std::size_t i = 0;
  while (i < text.size() && std::isdigit(static_cast<unsigned char>(text[i]))) ++i;
  if (i == 0 || i + 1 >= text.size()) return "";
  const char suffix = static_cast<char>(std::tolower(static_cast<unsigned char>(text[i])));
  if (std::string("kmunpfgtr").find(suffix) == std::string::npos) return "";
  std::size_t j = i + 1;
  while (j < text.size() && std::isdigit(static_cast<unsigned char>(text[j]))) ++j;
  if (j == i + 1 || j != text.size()) return "";
  // (M is mega there, as in 1M5: SPICE's Meg; m stays milli.)
  const std::string written = suffix == 'r' ? "" : text[i] == 'M' ? "Meg" : std::string(1, text[i]);
  return " (a suffix in place of the decimal point is not read: write " + text.substr(0, i) + "." +
         text.substr(i + 1) + written + ")";
}

}  // namespace

double value_of(const Card& card, std::size_t first, std::size_t last, const ParamScope& scope,
                bool bare_expressions) {
  const Token& t = card[first];
  if (last - first == 1) {
    if (t.is_expression()) return evaluate_at(card, t.begin + 1, t.end - 1, scope);
    if (t.is_word() && !bare_expressions) {
      if (auto v = parse_number(t.text)) return *v;
      throw NetlistError(card.at(t), "invalid number " + quote(t.text) + decimal_in_suffix_hint(t.text));
    }
  }
  if (!bare_expressions) {
    if (last - first > 1) throw NetlistError(card.at(first + 1), "unexpected extra token " + quote(card[first + 1].text));
    throw NetlistError(card.at(t), "expected a number, got " + quote(t.text));
  }
  return evaluate_at(card, card[first].begin, card[last - 1].end, scope);
}

std::vector<Assignment> split_assignments(const Card& card, std::size_t first, std::size_t last,
                                          bool allow_flags, bool expressions) {
  std::vector<Assignment> out;
  std::size_t i = first;
  // `name =` with a name that cannot be a number (so `1 = 2` inside an expression is no assignment).
  auto starts_assignment = [&](std::size_t k) {
    if (k + 1 >= last || !card[k].is_word() || !card[k + 1].is(Token::Kind::Equals)) return false;
    char c = card[k].lower[0];
    return (c >= 'a' && c <= 'z') || c == '_';
  };
  while (i < last) {
    const Token& t = card[i];
    if (t.is(Token::Kind::Comma)) {
      ++i;
      continue;
    }
    if (!t.is_word()) throw NetlistError(card.at(t), "expected 'name=value', got " + quote(t.text));
    Assignment a;
    a.name = i;
    if (!(i + 1 < last && card[i + 1].is(Token::Kind::Equals))) {
      if (!allow_flags) {
        const SourceLocation loc = i + 1 < last ? card.at(i + 1) : card.after_last();
        throw NetlistError(loc, "missing '=' after " + quote(t.text));
      }
      a.value_first = a.value_last = i + 1;
      out.push_back(a);
      ++i;
      continue;
    }
    i += 2;
    a.value_first = i;
    int depth = 0;
    if (!expressions && i < last && !card[i].is(Token::Kind::Comma) && !starts_assignment(i)) {
      a.value_last = ++i;
      out.push_back(a);
      continue;
    }
    while (i < last) {
      const Token& v = card[i];
      if (depth == 0 && (v.is(Token::Kind::Comma) || starts_assignment(i))) break;
      if (v.is(Token::Kind::LParen)) ++depth;
      if (v.is(Token::Kind::RParen) && depth > 0) --depth;
      ++i;
    }
    a.value_last = i;
    if (a.value_first == a.value_last) {
      const SourceLocation loc = a.value_last < last ? card.at(a.value_last) : card.after_last();
      throw NetlistError(loc, "missing value for " + quote(t.text));
    }
    out.push_back(a);
  }
  return out;
}

bool is_identifier(const std::string& s) {
  if (s.empty() || !((s[0] >= 'a' && s[0] <= 'z') || s[0] == '_')) return false;
  for (char c : s)
    if (!((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_')) return false;
  return true;
}

}  // namespace lcs::parse
