#include "netlist/measure_card.h"

#include <cctype>
#include <cmath>
#include <memory>
#include <set>
#include <stdexcept>
#include <string>

#include "netlist/expression.h"

namespace lcs::parse {
namespace {

// Analyses a `.meas` card may name besides `tran`: the measure is skipped with a warning.
const char* const kOtherAnalyses[] = {"ac", "dc", "op", "noise", "tf", "disto", "pz", "sens", "sp"};
const char* const kKindList = "AVG, RMS, MIN, MAX, PP, INTEG, MIN_AT, MAX_AT, FIND, WHEN, TRIG or PARAM";
const char* const kProbeForms = "v(node), v(node1,node2) or i(element)";

struct Statistic {
  const char* keyword;
  Measure::Kind kind;
};
const Statistic kStatistics[] = {
    {"avg", Measure::Kind::Avg},     {"rms", Measure::Kind::Rms},     {"min", Measure::Kind::Min},
    {"max", Measure::Kind::Max},     {"pp", Measure::Kind::Pp},       {"integ", Measure::Kind::Integ},
    {"integral", Measure::Kind::Integ}, {"min_at", Measure::Kind::MinAt}, {"max_at", Measure::Kind::MaxAt},
};

bool is_kind_keyword(const std::string& k) {
  for (const Statistic& s : kStatistics)
    if (k == s.keyword) return true;
  return k == "find" || k == "when" || k == "trig";
}

std::string upper(std::string s) {
  for (char& c : s)
    if (c >= 'a' && c <= 'z') c = static_cast<char>(c - 'a' + 'A');
  return s;
}

// A measure lcspice does not evaluate (an ngspice feature it leaves out): skipped with a warning.
struct Skip {
  SourceLocation loc;
  std::string why;
};

// `NAME=value` parameters after a probe, as one clause (the measure, WHEN, TRIG or TARG) allows.
enum Allowed : unsigned { kFrom = 1, kTo = 2, kTd = 4, kVal = 8, kEdge = 16 };

struct Params {
  std::optional<double> from, to, td, val;
  std::size_t from_token = 0, to_token = 0, td_token = 0;
  MeasureCrossing::Edge edge = MeasureCrossing::Edge::First;
  int count = 0;
  bool last = false;
};

class Reader {
 public:
  Reader(const Card& card, const ParamScope& scope, std::vector<std::string>& warnings)
      : card_(card), scope_(scope), warnings_(warnings), n_(card.size()) {}

  std::optional<Measure> read() {
    if (i_ < n_ && card_[i_].is_word()) {
      const std::string& a = card_[i_].lower;
      if (a == "tran") {
        ++i_;
      } else {
        for (const char* other : kOtherAnalyses)
          if (a == other) {
            warnings_.push_back(warning_line(card_.at(i_), quote(card_[0].lower + " " + a) +
                                                               " is ignored (lcspice runs transient analyses)"));
            return std::nullopt;
          }
      }
    }
    Measure m;
    read_name(m);
    try {
      read_kind(m);
    } catch (const Skip& skip) {
      warnings_.push_back(warning_line(skip.loc, skip.why + ": measure " + quote(m.name) + " is skipped"));
      return std::nullopt;
    }
    return m;
  }

 private:
  [[noreturn]] void fail_at(std::size_t k, const std::string& message) const {
    throw NetlistError(k < n_ ? card_.at(k) : card_.after_last(), message);
  }

  void skip_commas() {
    while (i_ < n_ && card_[i_].is(Token::Kind::Comma)) ++i_;
  }

  bool assignment_at(std::size_t k, const char* name) const {
    return k + 1 < n_ && card_[k].is_word(name) && card_[k + 1].is(Token::Kind::Equals);
  }

  void read_name(Measure& m) {
    if (i_ >= n_) fail_at(i_, "missing the measure's name after " + quote(card_[i_ - 1].text));
    const Token& t = card_[i_];
    if (!t.is_word()) fail_at(i_, "expected the measure's name, got " + quote(t.text));
    // `.meas tran AVG v(out)`: the name left out, the kind read as one.
    if (is_kind_keyword(t.lower) && i_ + 2 < n_ && card_[i_ + 1].is_word() && card_[i_ + 2].is(Token::Kind::LParen))
      fail_at(i_, "missing the measure's name before " + quote(t.text));
    m.name = t.lower;
    m.loc = card_.at(i_);
    ++i_;
  }

  void read_kind(Measure& m) {
    if (i_ >= n_)
      fail_at(i_, "missing the measure's kind after " + quote(card_[i_ - 1].text) + " (" + kKindList + ")");
    const Token& t = card_[i_];
    if (!t.is_word()) fail_at(i_, "expected the measure's kind (" + std::string(kKindList) + "), got " + quote(t.text));
    const std::string k = t.lower;
    if (k == "param") {
      m.kind = Measure::Kind::Param;
      read_expression(m.name, m.expression);
      return;
    }
    if (k == "deriv" || k == "derivative") throw Skip{card_.at(i_), "'.meas' DERIV is not supported by lcspice"};
    if (k == "err" || k == "err1" || k == "err2" || k == "err3")
      throw Skip{card_.at(i_), "'.meas' " + upper(k) + " is not supported by lcspice"};
    context_ = upper(k);
    const std::size_t keyword = i_++;
    for (const Statistic& s : kStatistics)
      if (k == s.keyword) {
        m.kind = s.kind;
        m.probe = read_probe(keyword);
        Params p = read_params(kFrom | kTo | kTd, nullptr);
        if (p.td)
          warnings_.push_back(warning_line(card_.at(p.td_token), "TD= is ignored by " + context_ +
                                                                     " (as in ngspice): FROM= starts its window"));
        m.from = p.from.value_or(0);
        m.to = p.to;
        return;
      }
    if (k == "find") {
      m.probe = read_probe(keyword);
      if (assignment_at(i_, "at")) {
        m.kind = Measure::Kind::FindAt;
        context_ = "FIND ... AT=";
        m.at = value(i_ + 2, "at");
        i_ += 3;
        read_params(0, nullptr);
        return;
      }
      if (i_ < n_ && card_[i_].is_word("when")) {
        m.kind = Measure::Kind::FindWhen;
        context_ = "WHEN";
        const std::size_t when = i_++;
        read_condition(m.when, when);
        return;
      }
      fail_at(i_, "expected AT=time or WHEN after 'FIND " + m.probe.name() + "'");
    }
    if (k == "when") {
      m.kind = Measure::Kind::When;
      read_condition(m.when, keyword);
      return;
    }
    if (k == "trig") {
      m.kind = Measure::Kind::TrigTarg;
      read_trig_targ(m.when, keyword, "targ");
      if (i_ >= n_) fail_at(i_, "missing TARG after TRIG (TRIG ... TARG probe VAL=level RISE=n)");
      context_ = "TARG";
      const std::size_t targ = i_++;
      read_trig_targ(m.targ, targ, nullptr);
      // ngspice: a FROM= on one of TRIG and TARG applies to both.
      if (m.when.from != 0 && m.targ.from == 0) m.targ.from = m.when.from;
      else if (m.targ.from != 0 && m.when.from == 0) m.when.from = m.targ.from;
      return;
    }
    if (k == "targ") fail_at(keyword, "TARG without TRIG (TRIG ... TARG ...)");
    fail_at(keyword, "unknown measure kind " + quote(t.text) + " (expected " + kKindList + ")");
  }

  // PARAM='expression' at i_ (also {expression}, or the bare expression to the card's end), or
  // LTspice's `PARAM expression` without '='. Its form is checked here (an error is a warning
  // and the measure fails, as in ngspice), the names it reads that are no parameters of the
  // deck are recorded (they should be measures), and `evaluate` keeps the deck's parameters and
  // functions it may read.
  void read_expression(const std::string& measure, MeasureExpression& x) {
    const std::size_t keyword = i_++;
    const bool equals = i_ < n_ && card_[i_].is(Token::Kind::Equals);
    if (equals) ++i_;
    if (i_ >= n_)
      throw Skip{card_.after_last(),
                 "missing the expression after " + quote(card_.text(card_[keyword].begin, card_[i_ - 1].end))};
    const Token& t = card_[i_];
    // ngspice 39.3 reads PARAM= up to the first blank: `PARAM=vmax * 5` is vmax (and the rest is
    // ignored, as after 'expr' or {expr}); LTspice's PARAM without '=' takes the rest of the line.
    std::size_t last = i_;
    if (!t.is_expression() && !equals) last = n_ - 1;
    if (!t.is_expression() && equals)
      while (last + 1 < n_ && card_[last + 1].begin == card_[last].end) ++last;
    int begin = t.begin, end = card_[last].end;
    if (t.is_expression()) ++begin, --end;
    if (last + 1 < n_)
      warnings_.push_back(warning_line(card_.span(card_[last + 1].begin, card_[n_ - 1].end),
                                       "ignored after PARAM's expression, as ngspice ignores it (write PARAM='...' "
                                       "for one with blanks)"));
    i_ = n_;
    x.text = card_.text(begin, end);
    x.loc = card_.span(begin, end);
    auto values = std::make_shared<const std::map<std::string, double>>(scope_.visible_values());
    auto functions = std::make_shared<const std::map<std::string, UserFunction>>(scope_.visible_functions());
    const FunctionLookup function = [functions](const std::string& name) -> const UserFunction* {
      auto it = functions->find(name);
      return it == functions->end() ? nullptr : &it->second;
    };
    std::set<std::string> seen;
    const std::string lower = to_lower(x.text);
    std::size_t cursor = 0;  // names are met in reading order: each new one is first written past the last
    try {
      check_expression(x.text,
                       [&](const std::string& name) -> std::optional<double> {
                         if (auto it = values->find(name); it != values->end()) return it->second;
                         if (seen.insert(name).second) x.names.push_back({name, first_use(lower, name, cursor)});
                         return 1.0;
                       },
                       function);
    } catch (const ExpressionError& e) {
      warnings_.push_back(warning_line(card_.span(begin + e.offset, begin + e.offset + e.length),
                                       e.message + ": measure " + quote(measure) + " will fail (as in ngspice)"));
    }
    x.evaluate = [text = x.text, values, function](const MeasureExpression::MeasureLookup& measures) {
      const Lookup lookup = [&](const std::string& name) -> std::optional<double> {
        std::string why;
        try {
          if (std::optional<double> v = measures(name)) return v;
        } catch (const std::runtime_error& e) {
          why = e.what();
        }
        if (auto it = values->find(name); it != values->end()) return it->second;
        throw LookupFailure{why.empty() ? quote(name) + " is neither a measure lcspice computes nor a parameter" : why};
      };
      try {
        return evaluate_expression(text, lookup, function);
      } catch (const ExpressionError& e) {
        // A syntax error is said before a division by zero ahead of it.
        try {
          check_expression(text, lookup, function);
        } catch (const ExpressionError& form) {
          throw std::runtime_error("PARAM " + quote(text) + ": " + form.message);
        }
        throw std::runtime_error("PARAM " + quote(text) + ": " + e.message);
      }
    };
  }

  // Where `name` is first written as a whole word in `lower` (the text in lower case), looking
  // from `cursor` on (moved past it); npos when it is not there (a .func body reads it).
  static std::size_t first_use(const std::string& lower, const std::string& name, std::size_t& cursor) {
    auto word_char = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; };
    for (std::size_t at = lower.find(name, cursor); at != std::string::npos; at = lower.find(name, at + 1)) {
      const std::size_t after = at + name.size();
      if ((at == 0 || !word_char(lower[at - 1])) && (after == lower.size() || !word_char(lower[after]))) {
        cursor = after;
        return at;
      }
    }
    return std::string::npos;
  }

  // v(node), v(node1,node2), i(element), ... at i_, after the token `after`.
  Probe read_probe(std::size_t after) {
    if (i_ >= n_) fail_at(i_, "missing probe after " + quote(card_[after].text) + " (" + kProbeForms + ")");
    const Token& t = card_[i_];
    if (t.is_expression())
      throw Skip{card_.at(i_), "expressions of probes are not measured by lcspice (only " + std::string(kProbeForms) + ")"};
    if (!t.is_word() || i_ + 1 >= n_ || !card_[i_ + 1].is(Token::Kind::LParen))
      fail_at(i_, "expected a probe (" + std::string(kProbeForms) + "), got " + quote(t.text));
    if (t.lower == "par")
      throw Skip{card_.at(i_), "expressions of probes are not measured by lcspice (only " + std::string(kProbeForms) + ")"};
    std::size_t close = i_ + 1;
    for (int depth = 0; close < n_; ++close) {
      if (card_[close].is(Token::Kind::LParen)) ++depth;
      if (card_[close].is(Token::Kind::RParen) && --depth == 0) break;
    }
    if (close >= n_) fail_at(i_ + 1, "missing ')'");
    const int b = t.begin, e = card_[close].end;
    Probe p = parse_probe(card_.text(b, e), card_.span(b, e));
    i_ = close + 1;
    // `v(a)*2`, `v(a)-v(b)`: an expression written against the probe; `v(a) * 2`, `v(a) -v(b)`:
    // one with spaces, an operator after the probe.
    if (i_ < n_ && card_[i_].is_word() &&
        (card_[i_].begin == e || std::string("+-*/^").find(card_[i_].text[0]) != std::string::npos))
      throw Skip{card_.span(b, card_[i_].end),
                 "expressions of probes are not measured by lcspice (only " + std::string(kProbeForms) + ")"};
    return p;
  }

  double value(std::size_t k, const char* name) {
    if (k >= n_ || card_[k].is(Token::Kind::Comma)) fail_at(k, "missing value for " + quote(name));
    return value_of(card_, k, scope_);
  }

  // The parameters up to the end of the card or the word `stop`.
  Params read_params(unsigned allowed, const char* stop) {
    Params p;
    for (;;) {
      skip_commas();
      if (i_ >= n_ || (stop && card_[i_].is_word(stop))) return p;
      const Token& t = card_[i_];
      if (!t.is_word()) fail_at(i_, "expected 'name=value', got " + quote(t.text));
      const std::string& name = t.lower;
      unsigned bit = 0;
      if (name == "from") bit = kFrom;
      else if (name == "to") bit = kTo;
      else if (name == "td") bit = kTd;
      else if (name == "val") bit = kVal;
      else if (name == "rise" || name == "fall" || name == "cross") bit = kEdge;
      const bool assigned = i_ + 1 < n_ && card_[i_ + 1].is(Token::Kind::Equals);
      // A bare LAST is CROSS=LAST (ngspice 39.3: `WHEN v(a)=0.5 LAST`, TRIG/TARG alike).
      if (!assigned && name == "last" && (allowed & kEdge)) {
        if (p.edge != MeasureCrossing::Edge::First) fail_at(i_, "only one of RISE=, FALL=, CROSS= and LAST may be given");
        p.edge = MeasureCrossing::Edge::Cross;
        p.last = true;
        ++i_;
        continue;
      }
      if (!assigned) {
        if (bit || name == "at") fail_at(i_ + 1, "missing '=' after " + quote(t.text));
        fail_at(i_, "unexpected extra token " + quote(t.text));
      }
      if (!bit && name != "at") fail_at(i_, "unknown .meas parameter " + quote(t.text));
      if (!(allowed & bit)) fail_at(i_, upper(name) + "= does not apply to " + context_);
      const std::size_t v = i_ + 2;
      if (bit == kEdge) {
        if (p.edge != MeasureCrossing::Edge::First) fail_at(i_, "only one of RISE=, FALL=, CROSS= and LAST may be given");
        p.edge = name == "rise" ? MeasureCrossing::Edge::Rise
                 : name == "fall" ? MeasureCrossing::Edge::Fall
                                  : MeasureCrossing::Edge::Cross;
        if (v < n_ && card_[v].is_word("last")) {
          p.last = true;
        } else {
          const double x = value(v, name.c_str());
          if (!(x >= 1 && x == std::floor(x) && x < 1e9))
            fail_at(v, upper(name) + "= must be a whole number from 1, or LAST");
          p.count = static_cast<int>(x);
        }
      } else {
        std::optional<double>& slot = bit == kFrom ? p.from : bit == kTo ? p.to : bit == kTd ? p.td : p.val;
        if (slot) fail_at(i_, upper(name) + "= is given twice");
        slot = value(v, name.c_str());
        if (bit == kFrom) p.from_token = v;
        if (bit == kTo) p.to_token = v;
        if (bit == kTd) p.td_token = i_;
      }
      i_ = v + 1;
      if (p.to && *p.to <= p.from.value_or(0))
        fail_at(p.to_token, p.from ? "TO= must be greater than FROM=" : "TO= must be positive");
    }
  }

  static void apply(const Params& p, MeasureCrossing& c) {
    c.edge = p.edge;
    c.count = p.count;
    c.last = p.last;
    c.td = p.td.value_or(0);
    c.from = p.from.value_or(0);
    c.to = p.to;
  }

  // WHEN probe=level or probe=probe2, then its crossing parameters.
  void read_condition(MeasureCrossing& c, std::size_t when) {
    c.probe = read_probe(when);
    if (i_ >= n_ || !card_[i_].is(Token::Kind::Equals))
      fail_at(i_, "expected '=' after '" + c.probe.name() + "' (WHEN probe=level or probe=probe2)");
    const std::size_t equals = i_++;
    if (i_ >= n_) fail_at(i_, "missing level after '" + c.probe.name() + "='");
    if (card_[i_].is_word() && i_ + 1 < n_ && card_[i_ + 1].is(Token::Kind::LParen)) {
      c.other = read_probe(equals);
    } else {
      c.level = value(i_, "when");
      ++i_;
    }
    apply(read_params(kFrom | kTo | kTd | kEdge, nullptr), c);
  }

  // TRIG/TARG probe VAL=level RISE|FALL|CROSS=n|LAST [TD= FROM= TO=], or TRIG/TARG AT=time.
  void read_trig_targ(MeasureCrossing& c, std::size_t keyword, const char* stop) {
    const std::string which = upper(card_[keyword].lower);
    if (assignment_at(i_, "at")) {
      c.at = value(i_ + 2, "at");
      i_ += 3;
      context_ = which + " AT=";
      read_params(0, stop);
      return;
    }
    c.probe = read_probe(keyword);
    const Params p = read_params(kVal | kFrom | kTo | kTd | kEdge, stop);
    if (!p.val) throw NetlistError(c.probe.loc, which + " " + c.probe.name() + " needs VAL=level");
    if (p.edge == MeasureCrossing::Edge::First)
      throw NetlistError(c.probe.loc, which + " " + c.probe.name() + " needs RISE=, FALL= or CROSS= (n or LAST)");
    c.level = *p.val;
    apply(p, c);
  }

  const Card& card_;
  const ParamScope& scope_;
  std::vector<std::string>& warnings_;
  const std::size_t n_;
  std::size_t i_ = 1;
  std::string context_;  // the clause being read, for messages ("AVG", "WHEN", "TARG")
};

}  // namespace

std::optional<Measure> parse_measure(const Card& card, const ParamScope& scope, std::vector<std::string>& warnings) {
  return Reader(card, scope, warnings).read();
}

}  // namespace lcs::parse
