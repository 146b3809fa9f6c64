// SPICE numbers: 1.5, -2e-3, .5, with a scale suffix (t g meg k m u n p f mil) and any trailing
// unit letters, which are ignored (10uF, 1kohm, 5V, 2.2e3k). Internal to the netlist reader.
#pragma once

#include <cstddef>
#include <optional>
#include <string_view>

namespace lcs::parse {

// Scans an unsigned SPICE number at s[i] (mantissa, exponent, then letters). On success moves i past
// it and returns true; `value` may be infinite when the number overflows. Returns false, leaving i
// unchanged, when no digit starts there.
bool scan_number(std::string_view s, std::size_t& i, double& value);

// The whole text as one number with an optional sign; nullopt when it is not exactly one finite
// number (e.g. "1x2", "1k5", "abc", "1e999").
std::optional<double> parse_number(std::string_view text);

}  // namespace lcs::parse
