#include "netlist/model_card.h"

#include <algorithm>

namespace lcs::parse {
namespace {

// ngspice diode (level 1 and its extensions) parameters that lcspice accepts and does not use.
const char* const kIgnoredDiodeParams[] = {
    "cjo", "cj0", "cj", "vj", "pb", "m", "mj", "tt", "bv", "ibv", "nbv", "ikf", "ik", "ikr",
    "jsw", "isw", "ns", "cjp", "cjsw", "php", "mjsw", "fc", "fcs", "eg", "xti", "kf", "af",
    "tnom", "tref", "level", "area", "pj", "temp", "dtemp", "tlev", "tlevc", "tm1", "tm2",
    "trs", "trs1", "trs2", "tbv1", "tbv2", "tcv", "tpb", "tphp", "tcj", "tcjsw", "gap1", "gap2",
    "rsw", "isr", "nr", "vp", "bvj", "jbv", "xom", "xoi", "lm", "lp", "wm", "wp", "xm", "xp", "d"};

const char* const kModelTypes[] = {"d", "npn", "pnp", "ltra"};

}  // namespace

ModelCard parse_model_card(const Card& card, const ParamScope& scope, const std::string& prefix,
                           std::vector<std::string>& warnings) {
  ModelCard m;
  if (card.size() < 2) throw NetlistError(card.after_last(), "missing model name after '.model'");
  if (!card[1].is_word()) throw NetlistError(card.at(1), "expected a model name, got " + quote(card[1].text));
  m.name = card[1].lower;
  if (card.size() < 3) throw NetlistError(card.after_last(), "missing model type for " + quote(m.name));
  const Token& type = card[2];
  if (!type.is_word()) throw NetlistError(card.at(2), "expected a model type, got " + quote(type.text));
  if (std::none_of(std::begin(kModelTypes), std::end(kModelTypes), [&](const char* t) { return type.lower == t; }))
    throw NetlistError(card.at(2), "unsupported model type " + quote(type.text));
  m.type = type.lower;

  // Parameters, optionally in one pair of parentheses.
  std::size_t first = 3, last = card.size();
  if (first < last && card[first].is(Token::Kind::LParen)) {
    std::size_t close = first + 1;
    while (close < last && !card[close].is(Token::Kind::RParen)) ++close;
    if (close == last) throw NetlistError(card.at(first), "missing ')'");
    if (close + 1 < last) throw NetlistError(card.at(close + 1), "unexpected extra token " + quote(card[close + 1].text));
    ++first;
    last = close;
  }
  std::vector<Assignment> params = split_assignments(card, first, last, m.type != "d", false);
  if (m.type != "d") return m;  // BJT and line models: read by the cards that will use them

  DiodeModel& d = m.diode;
  d.name = prefix + m.name;
  d.loc = card.at(1);
  SourceLocation first_ignored;
  for (const Assignment& a : params) {
    const Token& key = card[a.name];
    double v = value_of(card, a.value_first, a.value_last, scope);
    SourceLocation at_value = card.at(a.value_first);
    auto check = [&](bool ok, const char* rule) {
      if (!ok) throw NetlistError(at_value, "diode parameter " + quote(key.lower) + " must " + rule);
    };
    if (key.lower == "von") {
      d.von = v;
    } else if (key.lower == "ron") {
      check(v >= 0, "not be negative");
      d.ron = v;
    } else if (key.lower == "is") {
      check(v > 0, "be positive");
      d.is = v;
      d.has_is = true;
    } else if (key.lower == "n") {
      check(v > 0, "be positive");
      d.n = v;
      d.has_n = true;
    } else if (key.lower == "rs") {
      check(v >= 0, "not be negative");
      d.rs = v;
      d.has_rs = true;
    } else if (std::any_of(std::begin(kIgnoredDiodeParams), std::end(kIgnoredDiodeParams),
                           [&](const char* p) { return key.lower == p; })) {
      if (d.ignored.empty()) first_ignored = card.at(key);
      if (std::find(d.ignored.begin(), d.ignored.end(), key.lower) == d.ignored.end())
        d.ignored.push_back(key.lower);
    } else {
      throw NetlistError(card.at(key), "unknown diode model parameter " + quote(key.text));
    }
  }
  if (!d.ignored.empty()) {
    std::string list;
    for (const std::string& p : d.ignored) list += (list.empty() ? "" : ", ") + p;
    warnings.push_back(warning_line(first_ignored, "diode model " + quote(d.name) + ": parameter" +
                                                       (d.ignored.size() > 1 ? "s " : " ") + list +
                                                       " ignored by lcspice"));
  }
  return m;
}

}  // namespace lcs::parse
