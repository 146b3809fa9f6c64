#include "solver/model/netlist_options.h"

#include <cmath>
#include <cstdlib>

#include "netlist/number.h"
#include "solver/integrators/method_registry.h"

namespace lcs {

namespace {

const char* const kThetaMessage = ".options theta must be a number in [0, 1]";
const char* const kIfitMessage = ".options ifit must be a positive number of amperes";
const char* const kBjtcapMessage = ".options bjtcap must be a capacitance in farads, not negative";

std::string unknown_method_message(const std::string& name) {
  return "unknown method '" + name + "' (known: " + spice_method_names() + ")";
}

bool valid_theta(double theta) { return theta >= 0 && theta <= 1; }
bool valid_ifit(double ifit) { return ifit > 0 && std::isfinite(ifit); }
bool valid_bjtcap(double c) { return c >= 0 && std::isfinite(c); }

[[noreturn]] void fail(const Netlist& netlist, const std::string& option, const std::string& message) {
  auto it = netlist.option_locs.find(option);
  SourceLocation loc;
  if (it != netlist.option_locs.end()) {
    loc = it->second;
  } else {
    loc.file = netlist.file;
  }
  throw NetlistError(loc, message);
}

const std::string* option_text(const Netlist& netlist, const std::string& name) {
  auto it = netlist.options.find(name);
  return it == netlist.options.end() ? nullptr : &it->second;
}

}  // namespace

bool NetlistOptions::IsValid(std::string* why) const {
  auto fail = [why](const std::string& m) {
    if (why) *why = m;
    return false;
  };
  if (ifit && !valid_ifit(*ifit)) return fail(kIfitMessage);
  if (bjtcap && !valid_bjtcap(*bjtcap)) return fail(kBjtcapMessage);
  if (!method.empty() && !find_method(method)) return fail(unknown_method_message(method));
  if (gear && !method.empty()) return fail("method=gear leaves the method to the caller");
  if (theta && !valid_theta(*theta)) return fail(kThetaMessage);
  return true;
}

NetlistOptions read_netlist_options(const Netlist& netlist) {
  NetlistOptions o;
  if (const std::string* m = option_text(netlist, "method")) {
    const SpiceMethod spice = find_spice_method(*m);
    if (spice.entry) {
      o.method = spice.entry->name;
      o.theta = spice.theta;
    } else if (spice.gear) {
      o.gear = true;
    } else {
      fail(netlist, "method", unknown_method_message(*m));
    }
  }
  if (const std::string* text = option_text(netlist, "theta")) {
    // As strict as it always was: a plain number, no SPICE scale suffix.
    char* end = nullptr;
    const double theta = std::strtod(text->c_str(), &end);
    if (text->empty() || *end != '\0' || !valid_theta(theta)) fail(netlist, "theta", kThetaMessage);
    o.theta = theta;
  }
  if (const std::string* text = option_text(netlist, "ifit")) {
    const std::optional<double> ifit = parse::parse_number(*text);
    if (!ifit || !valid_ifit(*ifit)) fail(netlist, "ifit", kIfitMessage);
    o.ifit = *ifit;
  }
  if (const std::string* text = option_text(netlist, "bjtcap")) {
    const std::optional<double> c = parse::parse_number(*text);
    if (!c || !valid_bjtcap(*c)) fail(netlist, "bjtcap", kBjtcapMessage);
    o.bjtcap = *c;
  }
  if (const std::string* text = option_text(netlist, "diodecap")) {
    const std::optional<double> v = text->empty() ? std::optional<double>(1.0) : parse::parse_number(*text);
    if (!v || (*v != 0.0 && *v != 1.0)) fail(netlist, "diodecap", ".options diodecap takes no value, or 0 or 1");
    o.diodecap = *v == 1.0;
  }
  return o;
}

}  // namespace lcs
