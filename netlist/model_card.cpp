#include "netlist/model_card.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "netlist/out_of_scope.h"

namespace lcs::parse {
namespace {

// ngspice diode (level 1 and its extensions) parameters that lcspice accepts and does not use.
const char* const kIgnoredDiodeParams[] = {
    "vj", "pb", "m", "mj", "tt", "ikf", "ik", "ikr",
    "jsw", "isw", "ns", "cjp", "cjsw", "php", "mjsw", "fc", "fcs", "eg", "xti", "kf", "af",
    "tnom", "tref", "level", "area", "pj", "temp", "dtemp", "tlev", "tlevc", "tm1", "tm2",
    "trs", "trs1", "trs2", "tbv1", "tbv2", "tcv", "tpb", "tphp", "tcj", "tcjsw", "gap1", "gap2",
    "rsw", "isr", "nr", "vp", "bvj", "jbv", "xom", "xoi", "lm", "lp", "wm", "wp", "xm", "xp", "d",
    "ibvl", "nbvl", "tikf"};  // PSpice's: the low-level breakdown knee, IKF's temperature coefficient

// Gummel–Poon (ngspice level 1 BJT) parameters that lcspice accepts and does not use, and the
// vendor extras found on manufacturers' cards (VCEO, ICRATING, MFG, ...), whose values may be words.
// LTspice's ideal-diode parameters (LTspice only; ngspice reads them under `ngbehavior=lta`) that
// lcspice does not model: current limits and the softening of the knees.
const char* const kIgnoredLtspiceDiodeParams[] = {"ilimit", "revilimit", "epsilon", "revepsilon"};

// The datasheet fields of vendor diode cards (LTspice's libraries carry them on every diode:
// `Iave=200m Vpk=75 mfg=OnSemi type=silicon`): documentation, no model equation reads them, and
// their values may be words.
const char* const kVendorDiodeFields[] = {"iave", "ipk", "vpk", "mfg", "type", "pd", "ppk"};

const char* const kIgnoredBjtParams[] = {
    "vaf", "va", "ikf", "ik", "ise", "ne", "var", "vb", "ikr", "isc", "nc", "rb", "irb", "rbm",
    "re", "rc", "vje", "pe", "mje", "me", "tf", "xtf", "vtf", "itf", "ptf", "vjc", "pc",
    "mjc", "mc", "xcjc", "tr", "cjs", "ccs", "vjs", "ps", "mjs", "ms", "xtb", "eg", "xti", "kf",
    "af", "fc", "tnom", "tref", "level", "subs", "iss", "ns", "nkf", "quasimod", "rco", "vo",
    "gamma", "qco", "tlev", "tlevc", "temp", "dtemp", "vceo", "icrating", "icrate", "mfg", "type", "bvcbo",
    "bvebo", "bvceo", "iave", "vpk", "isub", "xcjc2", "vg", "cn", "d", "vbe", "vce",
    // PSpice's NK (ngspice's NKF) and the temperature coefficients of PSpice and ngspice's
    // level 1 (TBF1 ... TTR2): no temperature model here, nominal values only.
    "nk", "trb1", "trb2", "trm1", "trm2", "tre1", "tre2", "trc1", "trc2", "tbf1", "tbf2", "tbr1",
    "tbr2", "tikf1", "tikf2", "tikr1", "tikr2", "tis1", "tis2", "tise1", "tise2", "tisc1", "tisc2",
    "tiss1", "tiss2", "tnf1", "tnf2", "tnr1", "tnr2", "tne1", "tne2", "tnc1", "tnc2", "tns1",
    "tns2", "tvaf1", "tvaf2", "tvar1", "tvar2", "titf1", "titf2", "ttf1", "ttf2", "ttr1", "ttr2",
    "tmje1", "tmje2", "tmjc1", "tmjc2", "tmjs1", "tmjs2"};

template <std::size_t N>
bool listed(const char* const (&list)[N], const std::string& key) {
  return std::any_of(std::begin(list), std::end(list), [&](const char* p) { return key == p; });
}

void add_ignored(std::vector<std::string>& ignored, SourceLocation& first, const SourceLocation& at,
                 const std::string& key) {
  if (ignored.empty()) first = at;
  if (std::find(ignored.begin(), ignored.end(), key) == ignored.end()) ignored.push_back(key);
}

void warn_ignored(const std::vector<std::string>& ignored, const SourceLocation& first, const char* what,
                  const std::string& name, std::vector<std::string>& warnings) {
  if (ignored.empty()) return;
  std::string list;
  for (const std::string& p : ignored) list += (list.empty() ? "" : ", ") + p;
  warnings.push_back(warning_line(first, std::string(what) + " model " + quote(name) + ": parameter" +
                                             (ignored.size() > 1 ? "s " : " ") + list + " ignored by lcspice"));
}

void read_bjt_params(const Card& card, const std::vector<Assignment>& params, const ParamScope& scope,
                     BjtModel& q, std::vector<std::string>& warnings) {
  SourceLocation first_ignored;
  for (const Assignment& a : params) {
    const Token& key = card[a.name];
    if (listed(kIgnoredBjtParams, key.lower)) {
      add_ignored(q.ignored, first_ignored, card.at(key), key.lower);
      continue;
    }
    if (a.flag()) throw NetlistError(card.at(key), "missing '=' after " + quote(key.text));
    const double v = value_of(card, a.value_first, a.value_last, scope);
    const SourceLocation at_value = card.at(a.value_first);
    auto check = [&](bool ok, const char* rule) {
      if (!ok) throw NetlistError(at_value, "transistor parameter " + quote(key.lower) + " must " + rule);
    };
    const std::string& k = key.lower;
    if (k == "bf") {
      check(v > 0, "be positive");
      q.bf = v;
    } else if (k == "br") {
      check(v >= 0, "not be negative");
      q.br = v;
    } else if (k == "von" || k == "vone" || k == "vonc") {
      (k == "von" ? q.von : k == "vone" ? q.vone : q.vonc) = v;
    } else if (k == "ron" || k == "rone" || k == "ronc") {
      check(v >= 0, "not be negative");
      (k == "ron" ? q.ron : k == "rone" ? q.rone : q.ronc) = v;
    } else if (k == "is") {
      check(v > 0, "be positive");
      q.is = v;
      q.has_is = true;
    } else if (k == "nf" || k == "nr") {
      check(v > 0, "be positive");
      (k == "nf" ? q.nf : q.nr) = v;
      (k == "nf" ? q.has_nf : q.has_nr) = true;
    } else if (k == "cje" || k == "cjc") {
      check(v >= 0, "not be negative");
      (k == "cje" ? q.cje : q.cjc) = v;
    } else {
      throw NetlistError(card.at(key), "unknown transistor model parameter " + quote(key.text));
    }
  }
  warn_ignored(q.ignored, first_ignored, "transistor", q.name, warnings);
}

const char* const kModelTypes[] = {"d", "npn", "pnp", "ltra", "sw", "csw", "vswitch", "iswitch"};

// One switch parameter's value: present and finite; `check(ok, rule)` throws at the value.
struct SwitchParam {
  const Token& key;
  double v;
  SourceLocation at;
  void check(bool ok, const char* rule) const {
    if (!ok) throw NetlistError(at, "switch parameter " + quote(key.lower) + " must " + rule);
  }
};

SwitchParam switch_param(const Card& card, const Assignment& a, const ParamScope& scope) {
  const Token& key = card[a.name];
  if (a.flag()) throw NetlistError(card.at(key), "missing value for switch parameter " + quote(key.text));
  SwitchParam p{key, value_of(card, a.value_first, a.value_last, scope), card.at(a.value_first)};
  p.check(std::isfinite(p.v), "be finite");
  return p;
}

// RON or ROFF, the same in both switch families: true when `p` was one of them.
bool read_switch_resistance(const SwitchParam& p, SwitchModel& sw) {
  if (p.key.lower != "ron" && p.key.lower != "roff") return false;
  p.check(p.v > 0, "be positive");
  (p.key.lower == "ron" ? sw.ron : sw.roff) = p.v;
  return true;
}

// .model NAME SW(VT= VH= RON= ROFF=) / CSW(IT= IH= RON= ROFF=), ngspice's defaults.
void read_switch_params(const Card& card, const std::vector<Assignment>& params, const ParamScope& scope,
                        SwitchModel& sw, std::vector<std::string>& warnings) {
  const char* threshold = sw.current_controlled ? "it" : "vt";
  const char* hysteresis = sw.current_controlled ? "ih" : "vh";
  for (const Assignment& a : params) {
    const SwitchParam p = switch_param(card, a, scope);
    const Token& key = p.key;
    const double v = p.v;
    if (read_switch_resistance(p, sw)) continue;
    if (key.lower == threshold) {
      sw.vt = v;
    } else if (key.lower == hysteresis) {
      // Negative: LTspice's smooth passage from ROFF to RON over VT -+ |VH|; ngspice's reversed band
      // (on when rising past VT - |VH|, off when falling past VT + |VH|). Neither is an ideal
      // switch; the switch at VT is (a control that crosses the band quickly, as a gate drive
      // does, switches within |VH| / slope of VT either way).
      if (v < 0)
        warnings.push_back(warning_line(p.at, "switch model " + quote(sw.name) + ": negative " +
                                                      (sw.current_controlled ? "IH" : "VH") +
                                                      " (LTspice: a smooth passage over VT -+ |VH|; ngspice: a reversed "
                                                      "band) is modelled as an ideal switch at VT, without hysteresis"));
      sw.vh = std::max(v, 0.0);
    } else {
      throw NetlistError(card.at(key), std::string("unknown ") + (sw.current_controlled ? "CSW" : "SW") +
                                           " model parameter " + quote(key.text));
    }
  }
}

// .model NAME VSWITCH(VON= VOFF= RON= ROFF=) / ISWITCH(ION= IOFF= RON= ROFF=): PSpice's switches
// (Xyce reads them too), PSpice's defaults. PSpice passes the resistance smoothly from ROFF at VOFF
// to RON at VON (log R cubic in the control, so sqrt(RON ROFF) at the midpoint); lcspice's switch
// is ideal, so it switches at the midpoint VT = (VON + VOFF) / 2 without hysteresis, and VON below
// VOFF (the switch closes as the control falls) reads the control with its sign reversed.
void read_pspice_switch_params(const Card& card, const std::vector<Assignment>& params, const ParamScope& scope,
                               SwitchModel& sw, std::vector<std::string>& warnings) {
  const bool current = sw.current_controlled;
  const char* on_key = current ? "ion" : "von";
  const char* off_key = current ? "ioff" : "voff";
  double on = current ? 1e-3 : 1.0, off = 0.0;
  sw.ron = 1.0;
  sw.roff = 1e6;
  for (const Assignment& a : params) {
    const SwitchParam p = switch_param(card, a, scope);
    const Token& key = p.key;
    const double v = p.v;
    if (read_switch_resistance(p, sw)) continue;
    if (key.lower == on_key) {
      on = v;
    } else if (key.lower == off_key) {
      off = v;
    } else {
      throw NetlistError(card.at(key), std::string("unknown ") + (current ? "ISWITCH" : "VSWITCH") +
                                           " model parameter " + quote(key.text) + " (PSpice's are " +
                                           (current ? "ION, IOFF" : "VON, VOFF") + ", RON and ROFF)");
    }
  }
  if (on == off)
    throw NetlistError(card.at(2), std::string("switch model ") + quote(sw.name) + ": " +
                                       (current ? "ION and IOFF" : "VON and VOFF") + " must differ");
  sw.reversed = on < off;
  sw.vt = 0.5 * (on + off);
  sw.vh = 0;
  const char* unit = current ? "A" : "V";
  char buf[400];
  std::snprintf(buf, sizeof buf,
                "switch model '%s': %s (PSpice): its smooth passage from ROFF at %s = %.6g %s to RON at %s = "
                "%.6g %s is modelled as an ideal switch at their midpoint, %s %.6g %s",
                sw.name.c_str(), current ? "ISWITCH" : "VSWITCH", current ? "IOFF" : "VOFF", off, unit,
                current ? "ION" : "VON", on, unit, sw.reversed ? "on below" : "on above", sw.vt, unit);
  warnings.push_back(warning_line(card.at(2), buf));
}

// ngspice LTRA controls (step and interpolation choices of its own convolution); lcspice's
// recursive convolution has none of them.
const char* const kIgnoredLineParams[] = {"rel", "abs", "nosteplimit", "nocontrol", "lininterp",
                                          "mixedinterp", "compactrel", "compactabs", "truncnr",
                                          "truncdontcut", "steplimit", "quadinterp", "noprint", "print"};

// .model NAME LTRA(R= L= G= C= LEN=): per-unit-length R, L, G, C and the length.
void read_line_params(const Card& card, const std::vector<Assignment>& params, const ParamScope& scope,
                      LineModel& line, std::vector<std::string>& warnings) {
  SourceLocation first_ignored;
  bool has_l = false, has_c = false, has_len = false;
  for (const Assignment& a : params) {
    const Token& key = card[a.name];
    if (listed(kIgnoredLineParams, key.lower)) {
      add_ignored(line.ignored, first_ignored, card.at(key), key.lower);
      continue;
    }
    if (a.flag()) throw NetlistError(card.at(key), "missing value for line parameter " + quote(key.text));
    const double v = value_of(card, a.value_first, a.value_last, scope);
    const SourceLocation at_value = card.at(a.value_first);
    auto check = [&](bool ok, const char* rule) {
      if (!ok) throw NetlistError(at_value, "line parameter " + quote(key.lower) + " must " + rule);
    };
    if (key.lower == "r") {
      check(v >= 0 && std::isfinite(v), "not be negative");
      line.r = v;
    } else if (key.lower == "g") {
      check(v >= 0 && std::isfinite(v), "not be negative");
      line.g = v;
    } else if (key.lower == "l") {
      check(v > 0 && std::isfinite(v), "be positive (an RC line, L = 0, is not modelled)");
      line.l = v;
      has_l = true;
    } else if (key.lower == "c") {
      check(v > 0 && std::isfinite(v), "be positive");
      line.c = v;
      has_c = true;
    } else if (key.lower == "len") {
      check(v > 0 && std::isfinite(v), "be positive");
      line.len = v;
      has_len = true;
    } else {
      throw NetlistError(card.at(key), "unknown LTRA model parameter " + quote(key.text));
    }
  }
  const char* missing = !has_l ? "L" : !has_c ? "C" : !has_len ? "LEN" : nullptr;
  if (missing)
    throw NetlistError(card.at(1), std::string("LTRA model ") + quote(line.name) + " needs " + missing +
                                       " (per-unit-length L and C and the length LEN are required)");
  warn_ignored(line.ignored, first_ignored, "line", line.name, warnings);
}

}  // namespace

ModelCard parse_model_card(const Card& card, const ParamScope& scope, const std::string& prefix,
                           std::vector<std::string>& warnings, bool diode_capacitance) {
  ModelCard m;
  if (card.size() < 2) throw NetlistError(card.after_last(), "missing model name after '.model'");
  if (!card[1].is_word()) throw NetlistError(card.at(1), "expected a model name, got " + quote(card[1].text));
  m.name = card[1].lower;
  if (card.size() < 3) throw NetlistError(card.after_last(), "missing model type for " + quote(m.name));
  const Token& type = card[2];
  if (!type.is_word()) throw NetlistError(card.at(2), "expected a model type, got " + quote(type.text));
  m.type = type.lower;
  if (std::none_of(std::begin(kModelTypes), std::end(kModelTypes), [&](const char* t) { return type.lower == t; })) {
    if (unsimulated_model_kind(type.lower).empty())
      throw NetlistError(card.at(2), "unsupported model type " + quote(type.text));
    m.unsimulated = true;  // its parameters are not read: an element that uses it is refused
    return m;
  }

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
  if (m.type == "npn" || m.type == "pnp") {
    m.bjt.name = prefix + m.name;
    m.bjt.pnp = m.type == "pnp";
    m.bjt.loc = card.at(1);
    read_bjt_params(card, params, scope, m.bjt, warnings);
    return m;
  }
  if (m.type == "sw" || m.type == "csw" || m.type == "vswitch" || m.type == "iswitch") {
    m.sw.name = prefix + m.name;
    m.sw.current_controlled = m.type == "csw" || m.type == "iswitch";
    m.sw.loc = card.at(1);
    if (m.type == "vswitch" || m.type == "iswitch")
      read_pspice_switch_params(card, params, scope, m.sw, warnings);
    else
      read_switch_params(card, params, scope, m.sw, warnings);
    return m;
  }
  if (m.type == "ltra") {
    m.line.name = prefix + m.name;
    m.line.loc = card.at(1);
    read_line_params(card, params, scope, m.line, warnings);
    return m;
  }

  DiodeModel& d = m.diode;
  d.name = prefix + m.name;
  d.loc = card.at(1);
  SourceLocation first_ignored;
  for (const Assignment& a : params) {
    const Token& key = card[a.name];
    if (listed(kVendorDiodeFields, key.lower)) {
      add_ignored(d.ignored, first_ignored, card.at(key), key.lower);
      continue;
    }
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
    } else if (key.lower == "bv" || key.lower == "vrev") {  // Vrev: LTspice's breakdown voltage
      check(v > 0, "be positive");
      d.bv = v;
    } else if (key.lower == "cjo" || key.lower == "cj0" || key.lower == "cj") {
      check(v >= 0 && std::isfinite(v), "not be negative");
      d.cjo = v;
      if (!diode_capacitance) add_ignored(d.ignored, first_ignored, card.at(key), key.lower);
    } else if (key.lower == "ibv") {
      check(v > 0, "be positive");
      d.ibv = v;
    } else if (key.lower == "nbv") {
      check(v > 0, "be positive");
      d.nbv = v;
    } else if (key.lower == "vfwd") {  // LTspice's forward threshold (Ron is lcspice's RON already)
      d.von = v;
    } else if (key.lower == "rrev") {  // LTspice's breakdown resistance (default: Ron)
      check(v >= 0, "not be negative");
      d.rrev = v;
    } else if (key.lower == "roff") {
      // LTspice puts Roff across the blocking diode; lcspice's blocking diode is an open circuit.
      warnings.push_back(warning_line(card.at(key), "diode model " + quote(d.name) +
                                                        ": Roff (LTspice) is not modelled: the "
                                                        "blocking diode is an open circuit"));
    } else if (listed(kIgnoredDiodeParams, key.lower) || listed(kIgnoredLtspiceDiodeParams, key.lower)) {
      add_ignored(d.ignored, first_ignored, card.at(key), key.lower);
    } else {
      throw NetlistError(card.at(key), "unknown diode model parameter " + quote(key.text));
    }
  }
  warn_ignored(d.ignored, first_ignored, "diode", d.name, warnings);
  return m;
}

}  // namespace lcs::parse
