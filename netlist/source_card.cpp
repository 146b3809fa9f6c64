#include "netlist/source_card.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <sstream>
#include <string_view>

#include "netlist/deck_reader.h"
#include "netlist/number.h"

namespace lcs::parse {
namespace {

namespace fs = std::filesystem;

struct FunctionSpec {
  const char* name;
  Waveform::Kind kind;
  std::size_t min_params, max_params;  // max 0: unbounded
};

const FunctionSpec kFunctions[] = {
    {"sin", Waveform::Kind::Sin, 2, 7},   // the 7th, NCYCLES, is LTspice's
    {"sine", Waveform::Kind::Sin, 2, 7},  // ngspice's other name for SIN
    {"pulse", Waveform::Kind::Pulse, 2, 8},  // the 8th: NP, the number of pulses (ngspice 39, LTspice)
    {"pwl", Waveform::Kind::Pwl, 2, 0},
    {"exp", Waveform::Kind::Exp, 2, 6},
    {"sffm", Waveform::Kind::Sffm, 2, 8},
    {"am", Waveform::Kind::Am, 2, 8},
};

const char* const kUnsupported[] = {"trnoise", "trrandom", "pat", "ext"};

bool looks_numeric(const Token& t) {
  return t.is_expression() || (t.is_word() && parse_number(t.text).has_value());
}

std::string plural(std::size_t n, const char* what) {
  return std::to_string(n) + " " + what + (n == 1 ? "" : "s");
}

struct LtspiceRepeat {
  std::size_t at = 0;        // the REPEAT token
  std::size_t count_at = 0;  // FOR N's N (0: FOREVER)
  double count = 0;
};

// LTspice's PWL REPEAT: the points' times are relative to each repetition's start, a repetition
// lasts until the last point's time P, and the next starts there (from the last value to the first
// point, as a PWL interpolates). FOR N is written out as N copies (then the last value holds);
// FOREVER is ngspice's r= from the first point, with the ramp from the last value back to the
// first point appended when the first point is after 0 (a period of P).
void apply_ltspice_repeat(const Card& card, const LtspiceRepeat& repeat, const std::vector<std::size_t>& args,
                          std::vector<double>& params, std::optional<double>& repeat_from, std::size_t& repeat_from_at) {
  constexpr double kMaxRepeatedValues = 1e6;
  const std::size_t values = params.size();
  const double first = params[0], period = params[values - 2];
  if (first < 0) throw NetlistError(card.at(args[0]), "pwl REPEAT times must not be negative (they count from each repetition's start)");
  if (!(period > 0)) throw NetlistError(card.at(args[values - 2]), "pwl REPEAT needs a last time point after 0 (the repetition's length)");
  if (!repeat.count_at) {
    if (first > 0) {
      params.push_back(period + first);
      params.push_back(params[1]);
    }
    repeat_from = first;
    repeat_from_at = repeat.at;
    return;
  }
  const double n = repeat.count;
  if (!(n >= 1) || n != std::floor(n)) throw NetlistError(card.at(repeat.count_at), "REPEAT FOR count must be a whole number of at least 1");
  if (n * static_cast<double>(values) > kMaxRepeatedValues)
    throw NetlistError(card.at(repeat.count_at), "REPEAT FOR " + card[repeat.count_at].text + " writes out more than 1e6 values; use REPEAT FOREVER and a TSTOP that ends it");
  const std::vector<double> block = params;
  for (long k = 1; k < static_cast<long>(n); ++k)
    for (std::size_t v = 0; v < values; v += 2) {
      const double t = block[v] + static_cast<double>(k) * period;
      if (t == params[params.size() - 2] && block[v + 1] == params.back()) continue;  // the same point
      params.push_back(t);
      params.push_back(block[v + 1]);
    }
}

// LTspice's and PSpice's `PWL file=NAME` (PSpice also `PWL FILE NAME`): the time-value pairs
// read from a text file, relative to the deck's directory; numbers with SPICE suffixes, separated
// by blanks, commas or semicolons; lines starting with '*', '#' or ';' are comments. Errors name
// the file and its line.
std::vector<double> read_pwl_file(const Card& card, std::size_t name_at) {
  const Token& name = card[name_at];
  fs::path path(name.text);
  const std::string& deck = card.at(name_at).file;
  if (path.is_relative() && !deck.empty()) path = fs::path(deck).parent_path() / path;
  std::string text;
  if (!read_file(path.string(), text, true))
    throw NetlistError(card.at(name_at), "cannot open PWL file '" + path.string() + "'");
  std::vector<double> values;
  std::vector<int> value_lines;  // each value's line in the file
  std::istringstream lines(text);
  std::string line;
  for (int number = 1; std::getline(lines, line); ++number) {
    std::size_t k = line.find_first_not_of(" \t\r");
    if (k == std::string::npos || line[k] == '*' || line[k] == '#' || line[k] == ';') continue;
    while (k < line.size()) {
      k = line.find_first_not_of(" \t\r,;", k);
      if (k == std::string::npos) break;
      const std::size_t end = std::min(line.find_first_of(" \t\r,;", k), line.size());
      const std::optional<double> v = parse_number(std::string_view(line).substr(k, end - k));
      if (!v)
        throw NetlistError(card.at(name_at), "PWL file '" + path.string() + "' line " + std::to_string(number) +
                                                 ": invalid number '" + line.substr(k, end - k) + "'");
      values.push_back(*v);
      value_lines.push_back(number);
      k = end;
    }
  }
  if (values.size() < 2 || values.size() % 2 != 0)
    throw NetlistError(card.at(name_at), "PWL file '" + path.string() + "' needs time-value pairs (" +
                                             std::to_string(values.size()) + " numbers)");
  for (std::size_t k = 2; k < values.size(); k += 2)
    if (values[k] < values[k - 2])
      throw NetlistError(card.at(name_at), "PWL file '" + path.string() + "' line " +
                                               std::to_string(value_lines[k]) + ": times must not decrease");
  return values;
}

}  // namespace

Waveform parse_source_waveform(const Card& card, std::size_t first, const ParamScope& scope,
                               const std::string& name, std::vector<std::string>& warnings,
                               double* multiplier, InstanceParasitics* parasitics) {
  Waveform w;
  bool have_dc = false, have_function = false;
  double pwl_td = 0;
  std::optional<double> pwl_repeat;
  std::size_t pwl_repeat_at = 0;
  const std::size_t n = card.size();
  std::size_t i = first;
  while (i < n) {
    const Token& t = card[i];
    if (t.is(Token::Kind::Comma)) {
      ++i;
      continue;
    }
    if (t.is_word("dc")) {
      if (have_dc) throw NetlistError(card.at(t), "second DC value for " + quote(name));
      // `DC 5` or `DC=5` (ngspice reads both).
      const std::size_t at = i + 1 < n && card[i + 1].is(Token::Kind::Equals) ? i + 2 : i + 1;
      if (at >= n) throw NetlistError(card.after_last(), "missing value after " + quote(t.text));
      w.dc = value_of(card, at, scope);
      have_dc = true;
      i = at + 1;
      continue;
    }
    if (t.is_word("m") && i + 1 < n && card[i + 1].is(Token::Kind::Equals)) {
      if (!multiplier)
        throw NetlistError(card.at(t), "unknown parameter 'm' for " + quote(name) +
                                           " (a voltage source has no multiplier)");
      if (i + 2 >= n) throw NetlistError(card.after_last(), "missing value for 'm'");
      *multiplier = value_of(card, i + 2, scope);
      if (!(*multiplier > 0))
        throw NetlistError(card.at(i + 2), "multiplier m of " + quote(name) + " must be positive");
      i += 3;
      continue;
    }
    // ngspice's PWL options after the list, in either order: TD=delay shifts every time point;
    // R=time repeats the stretch from that time point to the last (applied after the loop).
    if (have_function && w.kind == Waveform::Kind::Pwl && (t.is_word("td") || t.is_word("r")) && i + 1 < n &&
        card[i + 1].is(Token::Kind::Equals)) {
      if (i + 2 >= n) throw NetlistError(card.after_last(), "missing value for " + quote(t.lower));
      const double v = value_of(card, i + 2, scope);
      if (t.is_word("td")) {
        pwl_td = v;
      } else {
        pwl_repeat = v;
        pwl_repeat_at = i + 2;
      }
      i += 3;
      continue;
    }
    if (have_function && w.kind == Waveform::Kind::Pwl && t.is_word("repeat"))
      throw NetlistError(card.at(t), "LTspice's REPEAT is read as the whole PWL only ('PWL REPEAT FOR N (...) "
                                     "ENDREPEAT' or 'PWL REPEAT FOREVER (...) ENDREPEAT'), not after other points");
    if (t.is_word("ac")) {
      warnings.push_back(warning_line(card.at(t), "AC specification of " + quote(name) + " is ignored"));
      ++i;
      if (i < n && card[i].is(Token::Kind::Equals)) ++i;  // `AC=1`, as `DC=5`
      for (int k = 0; k < 2 && i < n && (looks_numeric(card[i]) || card[i].is(Token::Kind::Comma)); ++i)
        if (!card[i].is(Token::Kind::Comma)) ++k;
      continue;
    }
    const FunctionSpec* fn = nullptr;
    if (t.is_word())
      for (const FunctionSpec& f : kFunctions)
        if (t.lower == f.name) fn = &f;
    if (fn) {
      if (have_function) throw NetlistError(card.at(t), "more than one transient function for " + quote(name));
      have_function = true;
      // Arguments: a parenthesised list, or the numbers that follow. A "+" written against a
      // {expression} is LTspice's PWL increment of an expression (`+{t_rise}`): one argument,
      // the expression, marked in `plus_before`.
      std::vector<std::size_t> args;
      std::vector<bool> plus_before;
      auto plus_of_expression = [&](std::size_t k) {
        return card[k].is_word("+") && k + 1 < n && card[k + 1].is_expression() && card[k].end == card[k + 1].begin;
      };
      auto take = [&](std::size_t& k) {
        const bool plus = plus_of_expression(k);
        if (plus) ++k;
        args.push_back(k);
        plus_before.push_back(plus);
      };
      std::size_t j = i + 1;
      // LTspice's `PWL REPEAT FOR N (points) ENDREPEAT` / `PWL REPEAT FOREVER (points) ENDREPEAT`
      // (parentheses optional), as the whole PWL: read below (ltspice_repeat).
      std::optional<LtspiceRepeat> repeat;
      // `PWL file=NAME` (LTspice, PSpice) or `PWL FILE NAME` (PSpice), NAME quoted or not.
      const bool from_file = fn->kind == Waveform::Kind::Pwl && j + 1 < n && card[j].is_word("file") &&
                             (card[j + 1].is(Token::Kind::Equals) || card[j + 1].is(Token::Kind::Quoted) ||
                              (card[j + 1].is_word() && !looks_numeric(card[j + 1])));
      if (from_file) {
        if (card[j + 1].is(Token::Kind::Equals) && j + 2 >= n)
          throw NetlistError(card.after_last(), "missing file name after 'file='");
        const std::size_t name_at = card[j + 1].is(Token::Kind::Equals) ? j + 2 : j + 1;
        w.kind = fn->kind;
        w.params = read_pwl_file(card, name_at);
        i = name_at + 1;
        continue;
      }
      if (fn->kind == Waveform::Kind::Pwl && j < n && card[j].is_word("repeat")) {
        repeat = LtspiceRepeat{};
        repeat->at = j;
        if (j + 1 < n && card[j + 1].is_word("forever")) {
          j += 2;
        } else if (j + 2 < n && card[j + 1].is_word("for") && looks_numeric(card[j + 2])) {
          repeat->count_at = j + 2;
          j += 3;
        } else {
          throw NetlistError(card.at(j), "expected 'REPEAT FOREVER' or 'REPEAT FOR N' (LTspice)");
        }
        const bool paren = j < n && card[j].is(Token::Kind::LParen);
        const std::size_t open = paren ? j++ : j;
        while (j < n && !(paren ? card[j].is(Token::Kind::RParen) : card[j].is_word("endrepeat"))) {
          if (!card[j].is(Token::Kind::Comma)) take(j);
          ++j;
        }
        if (paren && j >= n) throw NetlistError(card.at(open), "missing ')'");
        if (paren) ++j;
        if (j >= n || !card[j].is_word("endrepeat"))
          throw NetlistError(j < n ? card.at(j) : card.after_last(), "expected 'ENDREPEAT' (LTspice's PWL REPEAT)");
        ++j;
      } else if (j < n && card[j].is(Token::Kind::LParen)) {
        std::size_t open = j++;
        while (j < n && !card[j].is(Token::Kind::RParen)) {
          if (!card[j].is(Token::Kind::Comma)) take(j);
          ++j;
        }
        if (j >= n) throw NetlistError(card.at(open), "missing ')'");
        ++j;
      } else {
        while (j < n && (looks_numeric(card[j]) || card[j].is(Token::Kind::Comma) || plus_of_expression(j))) {
          if (!card[j].is(Token::Kind::Comma)) take(j);
          ++j;
        }
      }
      if (args.size() < fn->min_params)
        throw NetlistError(card.at(t), quote(t.lower) + " needs at least " + plural(fn->min_params, "parameter"));
      if (fn->max_params && args.size() > fn->max_params)
        throw NetlistError(card.at(args[fn->max_params]),
                           quote(t.lower) + " takes at most " + plural(fn->max_params, "parameter"));
      w.kind = fn->kind;
      for (std::size_t a : args) w.params.push_back(value_of(card, a, scope));
      if (fn->kind == Waveform::Kind::Pwl) {
        if (args.size() % 2 != 0)
          throw NetlistError(card.at(args.back()), "'pwl' needs time-value pairs (odd number of values)");
        // LTspice's increment: a time written "+T" is T after the previous time point (the Qorvo
        // forum's "increment operator"; cumulative). ngspice would read T as an absolute time,
        // which here almost always decreases (an error there), so the LTspice reading is taken.
        bool incremented = false;
        for (std::size_t k = 2; k < w.params.size(); k += 2) {
          const Token& time = card[args[k]];
          if (plus_before[k] || (time.is_word() && !time.text.empty() && time.text[0] == '+')) {
            w.params[k] += w.params[k - 2];
            incremented = true;
          }
        }
        if (incremented)
          warnings.push_back(warning_line(card.at(t), "pwl times of " + quote(name) + " written '+T' are read as "
                                                      "T after the previous time point (LTspice; ngspice reads "
                                                      "them as absolute times)"));
        for (std::size_t k = 2; k < w.params.size(); k += 2)
          if (w.params[k] < w.params[k - 2])
            throw NetlistError(card.at(args[k]), "pwl times must not decrease");
        if (repeat) {
          if (repeat->count_at) repeat->count = value_of(card, repeat->count_at, scope);
          apply_ltspice_repeat(card, *repeat, args, w.params, pwl_repeat, pwl_repeat_at);
        }
      }
      if (fn->kind == Waveform::Kind::Sin) {
        // value = VO + VA exp(-THETA (t - TD)) sin(2 pi FREQ (t - TD) + 2 pi PHASE / 360)
        const double two_pi = 6.283185307179586;
        if (w.params.size() > 2 && !std::isfinite(two_pi * w.params[2]))
          throw NetlistError(card.at(args[2]), "sin frequency is too large: 2*pi*FREQ is not a finite number");
        if (w.params.size() > 5 && !std::isfinite(two_pi * w.params[5] / 360))
          throw NetlistError(card.at(args[5]), "sin phase is too large: 2*pi*PHASE/360 is not a finite number");
        if (w.params.size() > 6 && !(w.params[6] >= 0))
          throw NetlistError(card.at(args[6]), "sin cycle count NCYCLES must not be negative");
        if (w.params.size() > 6 && w.params[6] > 0 && w.params[2] < 0)
          throw NetlistError(card.at(args[2]), "sin NCYCLES needs a positive frequency (the cycles of FREQ " +
                                                   card[args[2]].text + " do not end)");
      }
      if (fn->kind == Waveform::Kind::Pulse) {
        const char* what[] = {nullptr, nullptr, nullptr, "rise time", "fall time", "width", "period", "count NP"};
        for (std::size_t k = 3; k < w.params.size(); ++k)
          if (w.params[k] < 0)
            throw NetlistError(card.at(args[k]), std::string("pulse ") + what[k] + " must not be negative");
      }
      if (fn->kind == Waveform::Kind::Exp)
        for (std::size_t k : {3, 5})
          if (k < w.params.size() && w.params[k] < 0)
            throw NetlistError(card.at(args[k]), "exp time constant must not be negative");
      if (fn->kind == Waveform::Kind::Sffm && w.params.size() >= 5 && w.params[4] != 0) {
        // ngspice limits the modulation index so the instantaneous frequency stays >= 0.
        const double mdi = w.params[3], limit = w.params[2] / w.params[4];
        if (mdi > limit || mdi < 0)
          warnings.push_back(warning_line(card.at(args[3]), "sffm modulation index " + card[args[3]].text + " of " +
                                                                quote(name) + " is limited to " +
                                                                (mdi < 0 ? std::string("0") : "FC/FS") +
                                                                " (as ngspice does)"));
      }
      if (fn->kind == Waveform::Kind::Am && w.params.size() <= 5) {
        // ngspice 40 changed AM's parameters; decks written for earlier versions (and their
        // manuals) give AM(VA VO MF FC TD). Five values or fewer fit both forms: say which is read.
        auto hz = [&](std::size_t k) {
          char buf[32];
          std::snprintf(buf, sizeof buf, "%g Hz", k < w.params.size() ? w.params[k] : 0.0);
          return std::string(buf);
        };
        warnings.push_back(warning_line(
            card.at(t), "AM of " + quote(name) + " is read in ngspice 40's order, AM(VO VMO VMA FM FC TD PHASEM "
                        "PHASEC): carrier FC = " + hz(4) + ", modulation FM = " + hz(3) +
                        "; ngspice 39 and earlier read AM(VA VO MF FC TD), a carrier of " + hz(3) +
                        " here (six values or more are read in the 40+ order without this warning)"));
      }
      i = j;
      continue;
    }
    if (t.is_word())
      for (const char* u : kUnsupported)
        if (t.lower == u) throw NetlistError(card.at(t), "unsupported source function " + quote(t.text));
    if (!have_dc && !have_function && (t.is_word() || t.is_expression())) {
      w.dc = value_of(card, i, scope);  // a bare value; throws `invalid number` for junk
      have_dc = true;
      ++i;
      continue;
    }
    if (parasitics) {
      const std::size_t next = read_parasitic(card, i, ElementKind::VoltageSource, scope, name, *parasitics);
      if (next != i) {
        i = next;
        continue;
      }
    }
    if (t.is_word() && i + 1 < card.size() && card[i + 1].is(Token::Kind::Equals))
      throw NetlistError(card.at(t), "unknown parameter " + quote(t.text) + " for " + quote(name) +
                                         ltspice_parasitic_hint(t.lower));
    throw NetlistError(card.at(t), "unexpected extra token " + quote(t.text));
  }
  if (!have_dc && !have_function)
    warnings.push_back(warning_line(card.at(0), quote(name) + " has no value, DC 0 assumed"));
  // ngspice (vsrcpar.c) reads r < -0.5 as no repeat (decks pass r=-1 through a parameter).
  if (pwl_repeat && *pwl_repeat >= -0.5) {
    const double r = *pwl_repeat;
    std::optional<double> point;  // the time point r names (the last one would repeat a period of 0)
    for (std::size_t k = 0; !point && k + 2 < w.params.size(); k += 2)
      if (std::fabs(w.params[k] - r) <= 1e-12 * std::max(std::fabs(r), std::fabs(w.params[k]))) point = w.params[k];
    if (!point)
      throw NetlistError(card.at(pwl_repeat_at), "pwl repeat time r=" + card[pwl_repeat_at].text + " of " +
                                                     quote(name) + " must be one of its time points before the last");
    w.repeat_from = *point + pwl_td;
  }
  for (std::size_t k = 0; pwl_td != 0 && k < w.params.size(); k += 2) w.params[k] += pwl_td;
  return w;
}

std::string ltspice_parasitic_hint(const std::string& k) {
  if (k == "rser" || k == "lser")
    return " (LTspice's series parasitic: lcspice reads Rser on L, C and V and Lser on C; write this one as "
           "its own element in series)";
  if (k == "rpar" || k == "cpar")
    return " (LTspice's parallel parasitic: lcspice reads Rpar on L and C and Cpar on L, C and V; write this "
           "one as its own element in parallel)";
  return "";
}

}  // namespace lcs::parse
