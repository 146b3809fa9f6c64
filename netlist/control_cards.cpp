#include <algorithm>
#include <cmath>
#include "netlist/control_cards.h"

#include <cctype>
#include <cstdio>
#include <algorithm>
#include <cstdlib>

#include "netlist/element_card.h"

namespace lcs::parse {
namespace {

const char* const kIgnoredCards[] = {".ac", ".dc", ".noise", ".tf", ".four", ".temp", ".width", ".sens", ".disto", ".pz"};
const char* const kOtherAnalyses[] = {"ac", "dc", "op", "noise", "tf", "disto", "pz", "sens"};

[[noreturn]] void expected_ic(const Card& card, std::size_t i) {
  if (i >= card.size()) throw NetlistError(card.after_last(), "expected 'v(node)=value' after " + quote(card[i - 1].text));
  throw NetlistError(card.at(i), "expected 'v(node)=value', got " + quote(card[i].text));
}

}  // namespace

DotCard classify_dot_card(const std::string& k) {
  if (k == ".param") return DotCard::Param;
  if (k == ".func") return DotCard::Func;
  if (k == ".model") return DotCard::Model;
  if (k == ".subckt") return DotCard::Subckt;
  if (k == ".ends") return DotCard::Ends;
  if (k == ".tran" || k == ".tran/op") return DotCard::Tran;  // PSpice's /OP: print the bias point too
  if (k == ".ic") return DotCard::Ic;
  if (k == ".nodeset") return DotCard::Nodeset;
  if (k == ".print" || k == ".plot") return DotCard::Print;
  if (k == ".save" || k == ".probe" || k == ".probe64") return DotCard::Save;  // .PROBE64: PSpice's
  if (k == ".options" || k == ".option" || k == ".opt") return DotCard::Options;
  if (k == ".op" || k == ".backanno") return DotCard::Op;
  if (k == ".global") return DotCard::Global;
  if (k == ".title") return DotCard::Title;
  if (k == ".endc") return DotCard::Endc;
  if (k == ".meas" || k == ".measure") return DotCard::Measure;
  for (const char* c : kIgnoredCards)
    if (k == c) return DotCard::Ignored;
  return DotCard::Unknown;
}

bool allowed_in_subcircuit(DotCard kind) {
  return kind == DotCard::Param || kind == DotCard::Func || kind == DotCard::Model || kind == DotCard::Subckt || kind == DotCard::Ends;
}

TranSpec parse_tran(const Card& card, const ParamScope& scope, std::vector<std::string>& warnings) {
  TranSpec spec;
  spec.loc = card.at(0);
  std::vector<std::size_t> values;
  for (std::size_t i = 1; i < card.size(); ++i) {
    const Token& t = card[i];
    if (t.is(Token::Kind::Comma)) continue;
    if (t.is_word("uic") || t.is_word("skipbp")) {  // SKIPBP: PSpice's name for UIC
      spec.uic = true;
      continue;
    }
    if (t.is_word("startup")) {
      spec.uic = true;
      warnings.push_back(warning_line(card.at(t), "'startup' (LTspice: the supplies ramped up from 0 V over the "
                                                  "first 20 us) is read as UIC: the run starts from rest with the "
                                                  "sources at their values"));
      continue;
    }
    if (t.is_word("steady") || t.is_word("nodiscard")) {
      warnings.push_back(warning_line(card.at(t), quote(t.lower) + " (LTspice) is ignored: lcspice runs to TSTOP "
                                                                   "and writes rows from TSTART"));
      continue;
    }
    if (values.size() == 4) throw NetlistError(card.at(t), "unexpected extra token " + quote(t.text));
    values.push_back(i);
  }
  // LTspice's `.tran TSTOP` (its dialog with only the stop time filled in): `.tran 0 TSTOP`. Not
  // in a .control block, where ngspice's `tran` needs both.
  const bool dot_card = !card[0].lower.empty() && card[0].lower[0] == '.';
  if (values.size() == 1 && dot_card) {
    spec.stop_only = true;
    values.insert(values.begin(), 0);  // no token: TSTEP 0, picked below
  }
  if (values.size() < 2) throw NetlistError(card.after_last(), "'.tran' needs TSTEP and TSTOP");
  double v[4] = {0, 0, 0, 0};
  for (std::size_t k = spec.stop_only ? 1 : 0; k < values.size(); ++k) v[k] = value_of(card, values[k], scope);
  spec.tstep = v[0];
  spec.tstop = v[1];
  spec.tstart = v[2];
  spec.tmax = v[3];
  if (spec.tstep < 0 || !std::isfinite(spec.tstep))
    throw NetlistError(card.at(values[0]), "'.tran' step must be positive");
  if (spec.tstart < 0) throw NetlistError(card.at(values[2]), "'.tran' start time must not be negative");
  if (!(spec.tstop > spec.tstart))
    throw NetlistError(card.at(values[1]), values.size() > 2 ? "'.tran' stop time must be greater than the start time"
                                                             : "'.tran' stop time must be positive");
  if (spec.tmax < 0) throw NetlistError(card.at(values[3]), "'.tran' maximum step must not be negative");
  // `.tran 0 TSTOP` (LTspice, PSpice): the simulator picks the step. TSTEP is lcspice's print
  // step and the fixed methods' default step: a thousandth of the span, as a plot needs.
  if (spec.tstep == 0) {
    spec.tstep = (spec.tstop - spec.tstart) / kPickedStepsPerSpan;
    if (spec.tmax > 0) spec.tstep = std::min(spec.tstep, spec.tmax);
    spec.step_picked = true;
  }
  return spec;
}

std::vector<NodeIc> parse_ic(const Card& card, const ParamScope& scope) {
  std::vector<NodeIc> out;
  const std::size_t n = card.size();
  if (n == 1) expected_ic(card, 1);
  std::size_t i = 1;
  while (i < n) {
    if (card[i].is(Token::Kind::Comma)) {
      ++i;
      continue;
    }
    if (!card[i].is_word("v")) expected_ic(card, i);
    if (i + 1 >= n || !card[i + 1].is(Token::Kind::LParen)) expected_ic(card, i + 1);
    if (i + 2 >= n || !card[i + 2].is_word()) expected_ic(card, i + 2);
    if (i + 3 >= n || !card[i + 3].is(Token::Kind::RParen)) expected_ic(card, i + 3);
    if (i + 4 >= n || !card[i + 4].is(Token::Kind::Equals)) expected_ic(card, i + 4);
    if (i + 5 >= n) expected_ic(card, i + 5);
    NodeIc ic;
    ic.node = is_ground(card[i + 2].lower) ? "0" : card[i + 2].lower;
    if (ic.node == "0") throw NetlistError(card.at(i + 2), "cannot set the initial voltage of ground");
    ic.value = value_of(card, i + 5, scope);
    ic.loc = card.span(card[i].begin, card[i + 3].end);
    out.push_back(ic);
    i += 6;
  }
  return out;
}

std::vector<Probe> parse_probe_card(const Card& card, std::vector<std::string>& warnings, bool& every) {
  std::vector<Probe> out;
  const std::size_t n = card.size();
  const bool save = classify_dot_card(card.keyword()) == DotCard::Save;
  std::vector<std::string> pspice_other;  // W(alias(*)), D(alias(*)), NOISE(alias(*))
  bool wildcard = false;                  // V(*) or I(*): every voltage and current
  std::size_t i = 1;
  if (!save && i < n && card[i].is_word() && !(i + 1 < n && card[i + 1].is(Token::Kind::LParen))) {
    if (card[i].lower == "tran") {
      ++i;
    } else {
      for (const char* a : kOtherAnalyses)
        if (card[i].lower == a) {
          warnings.push_back(warning_line(card.at(i), quote(card[0].lower + " " + a) + " is ignored (lcspice runs transient analyses)"));
          return out;
        }
    }
  }
  while (i < n) {
    const Token& t = card[i];
    if (t.is(Token::Kind::Comma)) {
      ++i;
      continue;
    }
    if (save && (t.is_word("all") || t.is_word("alli") || t.is_word("allv"))) {
      ++i;
      continue;
    }
    // Xyce's output options (`.PRINT TRAN FORMAT=CSV FILE=out.csv ...`).
    if (i + 1 < n && card[i + 1].is(Token::Kind::Equals) &&
        (t.is_word("format") || t.is_word("file") || t.is_word("width") || t.is_word("precision") ||
         t.is_word("delimiter") || t.is_word("filter") || t.is_word("timescalefactor"))) {
      const char* why = t.is_word("format") ? " (lcspice writes CSV)" : t.is_word("file") ? " (lcspice writes to -o)" : "";
      std::string option = t.lower;
      for (char& c : option) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
      warnings.push_back(warning_line(card.at(t), quote(card[0].lower) + ": " + option + "= is ignored" + why));
      i = std::min(n, i + 3);
      continue;
    }
    // One entry: the tokens written together (parentheses may hold blanks and commas).
    std::size_t end = i;
    int depth = 0, groups = 0;
    do {
      if (card[end].is(Token::Kind::LParen)) ++depth;
      if (card[end].is(Token::Kind::RParen) && depth > 0 && --depth == 0) ++groups;
      ++end;
    } while (end < n && (depth > 0 || (card[end].begin == card[end - 1].end && !card[end].is(Token::Kind::Comma)) ||
                         (card[end].is(Token::Kind::LParen) && card[end - 1].is_word())));
    // PSpice writes `.PROBE64 V(alias(*)) I(alias(*)) W(alias(*)) D(alias(*)) NOISE(alias(*))` into
    // every deck it exports: every voltage and current (lcspice's default probes), and power,
    // digital and noise waveforms, which lcspice does not compute. Xyce's `.PRINT TRAN V(*) I(*)`
    // asks for the same voltages and currents.
    if (save || card.keyword() == ".print") {
      const std::string entry = to_lower(card.text(t.begin, card[end - 1].end));
      const std::size_t open = entry.find('(');
      const std::string kind = entry.substr(0, open), inside = open == std::string::npos ? "" : entry.substr(open);
      if (inside == "(alias(*))" || inside == "(*)") {
        if (kind == "v" || kind == "i") {
          wildcard = true;
          i = end;
          continue;
        }
        if (kind == "w" || kind == "d" || kind == "noise") {
          pspice_other.push_back(card.text(t.begin, card[end - 1].end));
          i = end;
          continue;
        }
      }
    }
    const bool device_parameter = !t.text.empty() && t.text[0] == '@';
    const bool power = t.is_word("p") && groups == 1;
    const bool expression = t.is_expression() || groups > 1 || (groups == 1 && !card[end - 1].is(Token::Kind::RParen)) ||
                            (groups == 1 && t.is(Token::Kind::LParen));
    if (device_parameter || power || expression) {
      const std::string entry = card.text(t.begin, card[end - 1].end);
      const char* why = device_parameter ? "device parameters are not probes lcspice writes"
                        : power          ? "power probes are not written by lcspice"
                                         : "expressions are not written by lcspice (only v(), i() probes)";
      warnings.push_back(warning_line(card.span(t.begin, card[end - 1].end),
                                      quote(card[0].lower) + " entry " + quote(entry) + " is ignored: " + why));
      i = end;
      continue;
    }
    if (depth > 0) {
      std::size_t open = i;
      while (!card[open].is(Token::Kind::LParen)) ++open;
      throw NetlistError(card.at(open), "missing ')'");
    }
    int b = t.begin, e = card[end - 1].end;
    out.push_back(parse_probe(card.text(b, e), card.span(b, e)));
    i = end;
  }
  // Every voltage and current are lcspice's default probes; they include whatever else a .print
  // card names (Xyce's `.PRINT TRAN V(*) I(R1)`, or on another card). (.save and .probe keep
  // their named entries, as `.save all v(a)` does.)
  if (wildcard && !save) every = true;
  if (!pspice_other.empty()) {
    std::string list;
    for (const std::string& e : pspice_other) list += (list.empty() ? "" : ", ") + e;
    warnings.push_back(warning_line(card.at(0), quote(card[0].lower) + ": " + list +
                                                    " (PSpice's power, digital and noise waveforms) not written by lcspice"));
  }
  return out;
}

void parse_options(const Card& card, const ParamScope& scope, Netlist& netlist) {
  for (const Assignment& a : split_assignments(card, 1, card.size(), true, false)) {
    const Token& name = card[a.name];
    std::string value;
    if (!a.flag()) {
      const Token& first = card[a.value_first];
      if (a.value_last - a.value_first == 1 && first.is_expression()) {
        // The shortest text that reads back as the same double.
        const double v = value_of(card, a.value_first, scope);
        char buf[40];
        for (int precision = 15; precision <= 17; ++precision) {
          std::snprintf(buf, sizeof buf, "%.*g", precision, v);
          if (std::strtod(buf, nullptr) == v) break;
        }
        value = buf;
      } else {
        value = to_lower(card.text(first.begin, card[a.value_last - 1].end));
      }
    }
    netlist.options[name.lower] = value;
    netlist.option_locs[name.lower] = card.at(name);
  }
}

}  // namespace lcs::parse
