#include "netlist/expression.h"

#include <cmath>
#include <vector>

#include "netlist/lexer.h"
#include "netlist/number.h"

namespace lcs::parse {
namespace {

constexpr int kMaxDepth = 200;
// User function calls inside user function bodies (a .func that calls itself never ends), and
// in all for one expression: a body that calls the previous function twice doubles the work at
// every level (22 levels, 4 million calls, took 3 s).
constexpr int kMaxCallDepth = 64;
constexpr long kMaxCalls = 100'000;
thread_local int call_depth = 0;
thread_local long calls = 0;

struct Function {
  const char* name;
  std::size_t min_args, max_args;  // max 0: any number
  double (*apply)(const std::vector<double>&);
};

const Function kFunctions[] = {
    {"sqrt", 1, 1, [](const std::vector<double>& a) { return std::sqrt(a[0]); }},
    {"exp", 1, 1, [](const std::vector<double>& a) { return std::exp(a[0]); }},
    {"log", 1, 1, [](const std::vector<double>& a) { return std::log(a[0]); }},
    {"ln", 1, 1, [](const std::vector<double>& a) { return std::log(a[0]); }},
    {"log10", 1, 1, [](const std::vector<double>& a) { return std::log10(a[0]); }},
    {"abs", 1, 1, [](const std::vector<double>& a) { return std::fabs(a[0]); }},
    {"sin", 1, 1, [](const std::vector<double>& a) { return std::sin(a[0]); }},
    {"cos", 1, 1, [](const std::vector<double>& a) { return std::cos(a[0]); }},
    {"tan", 1, 1, [](const std::vector<double>& a) { return std::tan(a[0]); }},
    {"asin", 1, 1, [](const std::vector<double>& a) { return std::asin(a[0]); }},
    {"acos", 1, 1, [](const std::vector<double>& a) { return std::acos(a[0]); }},
    {"atan", 1, 1, [](const std::vector<double>& a) { return std::atan(a[0]); }},
    {"arctan", 1, 1, [](const std::vector<double>& a) { return std::atan(a[0]); }},
    {"asinh", 1, 1, [](const std::vector<double>& a) { return std::asinh(a[0]); }},
    {"acosh", 1, 1, [](const std::vector<double>& a) { return std::acosh(a[0]); }},
    {"atanh", 1, 1, [](const std::vector<double>& a) { return std::atanh(a[0]); }},
    {"sqr", 1, 1, [](const std::vector<double>& a) { return a[0] * a[0]; }},
    {"sinh", 1, 1, [](const std::vector<double>& a) { return std::sinh(a[0]); }},
    {"cosh", 1, 1, [](const std::vector<double>& a) { return std::cosh(a[0]); }},
    {"tanh", 1, 1, [](const std::vector<double>& a) { return std::tanh(a[0]); }},
    {"floor", 1, 1, [](const std::vector<double>& a) { return std::floor(a[0]); }},
    {"ceil", 1, 1, [](const std::vector<double>& a) { return std::ceil(a[0]); }},
    {"pow", 2, 2, [](const std::vector<double>& a) { return std::pow(a[0], a[1]); }},
    {"if", 3, 3, [](const std::vector<double>& a) { return a[0] != 0 ? a[1] : a[2]; }},
    {"ternary_fcn", 3, 3, [](const std::vector<double>& a) { return a[0] != 0 ? a[1] : a[2]; }},
    // ngspice's pwr(x, y) = |x|^y (libngspice 39: pwr(-8, 2) = 64, pwr(-8, 1/3) = 2), int (toward
    // zero), nint (to the nearest, ties to even: nint(2.5) = 2, nint(3.5) = 4), sgn.
    {"pwr", 2, 2, [](const std::vector<double>& a) { return std::pow(std::fabs(a[0]), a[1]); }},
    {"int", 1, 1, [](const std::vector<double>& a) { return std::trunc(a[0]); }},
    {"nint", 1, 1, [](const std::vector<double>& a) { return std::nearbyint(a[0]); }},
    {"sgn", 1, 1, [](const std::vector<double>& a) { return static_cast<double>((a[0] > 0) - (a[0] < 0)); }},
    {"min", 1, 0,
     [](const std::vector<double>& a) {
       double m = a[0];
       for (double x : a) m = std::min(m, x);
       return m;
     }},
    {"max", 1, 0,
     [](const std::vector<double>& a) {
       double m = a[0];
       for (double x : a) m = std::max(m, x);
       return m;
     }},
};

const Function* find_builtin(const std::string& lower) {
  for (const Function& fn : kFunctions)
    if (lower == fn.name) return &fn;
  return nullptr;
}

// One level of user-function calls, undone however the call ends.
struct CallLevel {
  CallLevel() { ++call_depth; }
  ~CallLevel() { --call_depth; }
  CallLevel(const CallLevel&) = delete;
  CallLevel& operator=(const CallLevel&) = delete;
};

bool is_name_start(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_'; }
bool is_name_char(char c) { return is_name_start(c) || (c >= '0' && c <= '9'); }

class Evaluator {
 public:
  // `depth`: the nesting of the expression that calls this one (a user function's body counts
  // its caller's parentheses and calls: the stack is bounded by kMaxDepth in all).
  // `form_only`: value errors are not raised (check_expression).
  Evaluator(std::string_view text, const Lookup& lookup, const FunctionLookup& functions, int depth = 0,
            bool form_only = false)
      : s_(text), lookup_(lookup), functions_(functions), depth_(depth), form_only_(form_only) {}

  double run() {
    skip();
    if (i_ == s_.size()) fail(0, 1, "empty expression");
    double v = expr();
    skip();
    if (i_ != s_.size()) unexpected();
    return v;
  }

 private:
  [[noreturn]] void fail(std::size_t offset, std::size_t length, std::string message) {
    throw ExpressionError{static_cast<int>(offset), static_cast<int>(std::max<std::size_t>(1, length)),
                          std::move(message)};
  }
  [[noreturn]] void unexpected() {
    if (i_ >= s_.size()) fail(s_.size(), 1, "unexpected end of expression");
    fail(i_, 1, "unexpected " + quote(std::string(1, s_[i_])) + " in expression");
  }
  void skip() {
    while (i_ < s_.size() && (s_[i_] == ' ' || s_[i_] == '\t' || s_[i_] == '\r')) ++i_;
  }
  bool at(char c) {
    skip();
    return i_ < s_.size() && s_[i_] == c;
  }
  bool at_power() {
    skip();
    return i_ < s_.size() && (s_[i_] == '^' || (s_[i_] == '*' && i_ + 1 < s_.size() && s_[i_ + 1] == '*'));
  }
  double check(double v, std::size_t offset, std::size_t length, const std::string& what) {
    if (!std::isfinite(v)) {
      if (form_only_) return 0;
      fail(offset, length, "result of " + quote(what) + " is not a finite number");
    }
    return v;
  }

  struct Depth {
    Evaluator& e;
    std::size_t offset;
    explicit Depth(Evaluator& ev, std::size_t off) : e(ev), offset(off) {
      if (++e.depth_ > kMaxDepth) e.fail(offset, 1, "expression nested too deeply");
    }
    ~Depth() { --e.depth_; }
  };

  // ngspice's conditional `c ? a : b` (lowest precedence, right-associative), then its logical
  // and comparison operators, 1 for true, 0 for false: `.if (mode == 2)`,
  // `{ IF((a < 1) & (b > 0), x, y) }`. The branch not taken is read but its division by zero is
  // not an error (`a > 1 ? 1k : 1/(a - 2)` at a = 2, as libngspice 39 takes it; its sqrt(-1) is
  // an error there too, and here).
  double expr() {
    const double c = disjunction();
    if (!at('?')) return c;
    Depth d(*this, i_);
    ++i_;
    const double a = branch(c != 0);
    if (!at(':')) unexpected();
    ++i_;
    const double b = branch(c == 0);
    return c != 0 ? a : b;
  }

  double branch(bool taken) {
    if (!taken) ++untaken_;
    struct Restore {
      int& n;
      bool on;
      ~Restore() {
        if (on) --n;
      }
    } restore{untaken_, !taken};
    return expr();
  }

  double disjunction() {
    double v = conjunction();
    while (at_operator("||") || at_single('|')) {
      i_ += at_operator("||") ? 2 : 1;
      const double r = conjunction();
      v = (v != 0 || r != 0) ? 1.0 : 0.0;
    }
    return v;
  }

  double conjunction() {
    double v = comparison();
    while (at_operator("&&") || at_single('&')) {
      i_ += at_operator("&&") ? 2 : 1;
      const double r = comparison();
      v = (v != 0 && r != 0) ? 1.0 : 0.0;
    }
    return v;
  }

  double comparison() {
    double v = sum();
    while (true) {
      const char* const ops[] = {"==", "!=", "<>", "<=", ">=", "<", ">"};
      const char* op = nullptr;
      for (const char* o : ops)
        if (at_operator(o)) {
          op = o;
          break;
        }
      if (!op) return v;
      i_ += std::string_view(op).size();
      const double r = sum();
      const std::string_view o(op);
      const bool b = o == "==" ? v == r : o == "!=" || o == "<>" ? v != r : o == "<=" ? v <= r : o == ">=" ? v >= r
                   : o == "<"  ? v < r  : v > r;
      v = b ? 1.0 : 0.0;
    }
  }

  bool at_operator(std::string_view op) {
    skip();
    return s_.substr(i_, op.size()) == op;
  }
  // `c` alone, not the first character of `cc` (so `|` is not read out of `||`).
  bool at_single(char c) { return at(c) && !(i_ + 1 < s_.size() && s_[i_ + 1] == c); }

  double sum() {
    double v = term();
    while (at('+') || at('-')) {
      std::size_t op = i_;
      char c = s_[i_++];
      double r = term();
      v = check(c == '+' ? v + r : v - r, op, 1, std::string(1, c));
    }
    return v;
  }

  double term() {
    double v = unary();
    while ((at('*') && !at_power()) || at('/') || at('%')) {
      std::size_t op = i_;
      char c = s_[i_++];
      double r = unary();
      if (c == '%') {  // ngspice: the remainder with the dividend's sign (-7 % 3 = -1, 7.5 % 2 = 1.5)
        v = check(std::fmod(v, r), op, 1, "%");
      } else if (c == '/') {
        if (r == 0.0 && untaken_ == 0 && !form_only_) fail(op, 1, "division by zero");
        v = r == 0.0 ? 0.0 : check(v / r, op, 1, "/");  // 0: in a branch not taken (see expr())
      } else {
        v = check(v * r, op, 1, "*");
      }
    }
    return v;
  }

  double unary() {
    if (at('!') && !at_operator("!=")) {
      Depth d(*this, i_);
      ++i_;
      return unary() == 0 ? 1.0 : 0.0;
    }
    if (at('+') || at('-')) {
      Depth d(*this, i_);
      char c = s_[i_++];
      double v = unary();
      return c == '-' ? -v : v;
    }
    return power();
  }

  // ngspice's numparam (libngspice 39.3): `^` and `**` group left to right (2^3^2 = 64,
  // 2^-1^2 = 0.25) and take the base's magnitude ((-2)^3 = 8, (-8)^(1/3) = 2); below unary minus
  // (-2^2 = -4), and an exponent may carry its own sign (2^-1).
  double power() {
    double v = primary();
    while (at_power()) {
      std::size_t op = i_;
      std::size_t len = s_[i_] == '^' ? 1 : 2;
      i_ += len;
      Depth d(*this, op);
      const double exponent = signed_primary();
      v = check(std::pow(std::fabs(v), exponent), op, len, std::string(s_.substr(op, len)));
    }
    return v;
  }

  double signed_primary() {
    if (at('+') || at('-')) {
      Depth d(*this, i_);
      const char c = s_[i_++];
      const double v = signed_primary();
      return c == '-' ? -v : v;
    }
    return primary();
  }

  double primary() {
    skip();
    if (i_ >= s_.size()) unexpected();
    char c = s_[i_];
    if (c == '(') {
      Depth d(*this, i_);
      std::size_t open = i_++;
      double v = expr();
      if (!at(')')) {
        if (i_ >= s_.size()) fail(open, 1, "missing ')'");
        unexpected();
      }
      ++i_;
      return v;
    }
    if ((c >= '0' && c <= '9') || (c == '.' && i_ + 1 < s_.size() && s_[i_ + 1] >= '0' && s_[i_ + 1] <= '9')) {
      std::size_t start = i_;
      double v = 0;
      scan_number(s_, i_, v);
      if (!std::isfinite(v)) fail(start, i_ - start, "invalid number " + quote(std::string(s_.substr(start, i_ - start))));
      return v;
    }
    if (is_name_start(c)) {
      std::size_t start = i_;
      while (i_ < s_.size() && is_name_char(s_[i_])) ++i_;
      std::string written(s_.substr(start, i_ - start));
      std::string name = to_lower(written);
      if (at('(')) return call(name, written, start);
      if (name == "pi") return 3.14159265358979323846;
      std::optional<double> v;
      try {
        v = lookup_(name);
      } catch (const LookupFailure& f) {
        fail(start, written.size(), f.message);
      }
      if (!v) fail(start, written.size(), "undefined parameter " + quote(written));
      return *v;
    }
    unexpected();
  }

  // The arguments of a call, from its '(' to past its ')'. `conditional`: if(c, a, b) or
  // ternary_fcn(c, a, b), whose branch not taken is read as in expr().
  std::vector<double> arguments(bool conditional = false) {
    Depth d(*this, i_);
    std::size_t open = i_++;  // at '('
    std::vector<double> args;
    if (!at(')')) {
      while (true) {
        const std::size_t k = args.size();
        args.push_back(conditional && k > 0 ? branch(k == 1 ? args[0] != 0 : k == 2 ? args[0] == 0 : true) : expr());
        if (at(',')) {
          ++i_;
          continue;
        }
        if (at(')')) break;
        if (i_ >= s_.size()) fail(open, 1, "missing ')'");
        unexpected();
      }
    }
    ++i_;
    return args;
  }

  double call(const std::string& name, const std::string& written, std::size_t start) {
    const Function* f = find_builtin(name);
    const UserFunction* user = f || !functions_ ? nullptr : functions_(name);
    if (user) return call_user(*user, written, start);
    if (!f) fail(start, written.size(), "unknown function " + quote(written));
    const std::vector<double> args = arguments(name == "if" || name == "ternary_fcn");
    bool bad = args.size() < f->min_args || (f->max_args && args.size() > f->max_args);
    if (bad) {
      std::string n = std::to_string(f->min_args) + (f->min_args == 1 ? " argument" : " arguments");
      fail(start, written.size(),
           quote(written) + " takes " + (f->max_args ? "" : "at least ") + n);
    }
    double v = f->apply(args);
    if (!std::isfinite(v)) {
      if (form_only_) return 0;
      fail(start, written.size(), "invalid argument to " + quote(written));
    }
    return v;
  }

  // The body with the parameters bound to the arguments; other names are the caller's.
  double call_user(const UserFunction& user, const std::string& written, std::size_t start) {
    const std::vector<double> args = arguments();
    if (args.size() != user.params.size())
      fail(start, written.size(),
           quote(written) + " takes " + std::to_string(user.params.size()) +
               (user.params.size() == 1 ? " argument" : " arguments") + " (.func at " + user.defined_at + ")");
    if (call_depth >= kMaxCallDepth)
      fail(start, written.size(), "functions nested too deeply calling " + quote(written) + " (does it call itself?)");
    if (++calls > kMaxCalls)
      fail(start, written.size(), "more than " + std::to_string(kMaxCalls) + " function calls in one expression");
    const Lookup bound = [&](const std::string& n) -> std::optional<double> {
      for (std::size_t k = 0; k < user.params.size(); ++k)
        if (user.params[k] == n) return args[k];
      return lookup_(n);
    };
    CallLevel level;
    try {
      return Evaluator(user.body, bound, functions_, depth_ + 1, form_only_).run();
    } catch (const ExpressionError& e) {
      // Said once, at the outermost call: an error inside nested bodies, or the call budget.
      if (e.message.rfind("in function ", 0) == 0 || e.message.rfind("more than ", 0) == 0)
        fail(start, written.size(), e.message);
      fail(start, written.size(), "in function " + quote(written) + " (.func at " + user.defined_at + "): " + e.message);
    }
  }

  std::string_view s_;
  const Lookup& lookup_;
  const FunctionLookup& functions_;
  int depth_ = 0;
  bool form_only_ = false;
  int untaken_ = 0;  // inside a conditional's branch not taken
  std::size_t i_ = 0;
};

}  // namespace

bool is_builtin_function(const std::string& lower) { return find_builtin(lower) != nullptr; }

double evaluate_expression(std::string_view text, const Lookup& lookup, const FunctionLookup& functions) {
  if (call_depth == 0) calls = 0;  // an expression of the deck, not one inside a function body
  return Evaluator(text, lookup, functions).run();
}

void check_expression(std::string_view text, const Lookup& lookup, const FunctionLookup& functions) {
  if (call_depth == 0) calls = 0;
  Evaluator(text, lookup, functions, 0, true).run();
}

}  // namespace lcs::parse
