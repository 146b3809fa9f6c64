#include "netlist/number.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>

namespace lcs::parse {
namespace {

bool is_digit(char c) { return c >= '0' && c <= '9'; }
bool is_letter(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); }
char lower(char c) { return (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c; }

// Scale of the letters after a number, as a power of ten (`mil` is not one: 25.4e-6). `meg` and
// `mil` are tried before the one-letter suffixes; letters that are no suffix are units (V, A, Hz,
// ohm, s, ...) and scale by 1.
struct Scale {
  int exponent = 0;
  bool mil = false;
};

Scale scale_of(std::string_view letters) {
  auto starts = [&](const char* w) {
    std::size_t n = std::char_traits<char>::length(w);
    if (letters.size() < n) return false;
    for (std::size_t k = 0; k < n; ++k)
      if (lower(letters[k]) != w[k]) return false;
    return true;
  };
  if (starts("meg")) return {6, false};
  if (starts("mil")) return {0, true};
  if (letters.empty()) return {};
  switch (lower(letters[0])) {
    case 't': return {12, false};
    case 'g': return {9, false};
    case 'k': return {3, false};
    case 'm': return {-3, false};
    case 'u': return {-6, false};
    case 'n': return {-9, false};
    case 'p': return {-12, false};
    case 'f': return {-15, false};
    default: return {};
  }
}

}  // namespace

bool scan_number(std::string_view s, std::size_t& i, double& value) {
  std::size_t k = i, digits = 0;
  while (k < s.size() && is_digit(s[k])) ++k, ++digits;
  if (k < s.size() && s[k] == '.') {
    ++k;
    while (k < s.size() && is_digit(s[k])) ++k, ++digits;
  }
  if (digits == 0) return false;
  std::string mantissa(s.substr(i, k - i));
  // An exponent only when digits follow the e (else the e is a unit letter). It is saturated, so
  // absurd exponents overflow to infinity or underflow to zero instead of wrapping around.
  long long exponent = 0;
  if (k < s.size() && (s[k] == 'e' || s[k] == 'E')) {
    std::size_t e = k + 1;
    bool negative = false;
    if (e < s.size() && (s[e] == '+' || s[e] == '-')) negative = s[e++] == '-';
    if (e < s.size() && is_digit(s[e])) {
      while (e < s.size() && is_digit(s[e])) {
        exponent = std::min<long long>(exponent * 10 + (s[e] - '0'), 100000);
        ++e;
      }
      if (negative) exponent = -exponent;
      k = e;
    }
  }
  std::size_t letters = k;
  // LTspice writes micro as the micro sign µ (UTF-8 C2 B5) or the Greek mu μ (CE BC): 'u'.
  Scale scale;
  if (k + 1 < s.size() && ((s[k] == '\xC2' && s[k + 1] == '\xB5') || (s[k] == '\xCE' && s[k + 1] == '\xBC'))) {
    scale.exponent = -6;
    k += 2;
    while (k < s.size() && is_letter(s[k])) ++k;
  } else {
    while (k < s.size() && is_letter(s[k])) ++k;
    scale = scale_of(s.substr(letters, k - letters));
  }
  // A unit written as the ohm symbol, Ω (U+03A9, CE A9) or the ohm sign (U+2126, E2 84 A6), after
  // the suffix: `1.5kΩ` (schematic exports), read as ngspice reads unit letters.
  if (s.substr(k, 2) == "\xCE\xA9") k += 2;
  else if (s.substr(k, 3) == "\xE2\x84\xA6") k += 3;
  // One decimal conversion of mantissa * 10^(exponent + suffix), so 10u is exactly 1e-05.
  std::string decimal = mantissa + "e" + std::to_string(exponent + scale.exponent);
  value = std::strtod(decimal.c_str(), nullptr);
  if (scale.mil) value *= 25.4e-6;
  i = k;
  return true;
}

std::optional<double> parse_number(std::string_view text) {
  std::size_t i = 0;
  double sign = 1.0;
  if (i < text.size() && (text[i] == '+' || text[i] == '-')) sign = text[i++] == '-' ? -1.0 : 1.0;
  double value = 0;
  if (!scan_number(text, i, value) || i != text.size() || !std::isfinite(value)) return std::nullopt;
  return sign * value;
}

}  // namespace lcs::parse
