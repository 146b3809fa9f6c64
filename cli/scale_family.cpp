#include "cli/scale_family.h"

#include <cstdio>
#include <sstream>
#include <stdexcept>

namespace lcs {

namespace {

constexpr int kPeriods = 5;           // the interval, in source periods
constexpr int kStepsPerPeriod = 200;  // TSTEP = period / 200

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

// `.tran` over kPeriods periods of `frequency`.
std::string tran_card(double frequency, bool uic) {
  const double period = 1 / frequency;
  return ".tran " + number(period / kStepsPerPeriod) + " " + number(kPeriods * period) + (uic ? " UIC" : "") + "\n";
}

// Stage k (1-based) adds the pushing capacitor into a_k, the smoothing capacitor into b_k, and
// the two diodes b_{k-1} -> a_k -> b_k (a_0 is the source, b_0 ground), as in
// circuits/cockcroft_walton.cir.
std::string cockcroft_walton(int n) {
  std::ostringstream s;
  s << "Cockcroft-Walton multiplier, " << n << " stages (" << 2 * n
    << " diodes): 100 V peak, 50 Hz, starting empty, towards 2N (100 V - 0.7 V) at b" << n << "\n";
  s << "V1 in 0 SIN(0 100 50)\n";
  for (int k = 1; k <= n; ++k) {
    const std::string a_prev = k == 1 ? "in" : "a" + std::to_string(k - 1);
    const std::string b_prev = k == 1 ? "0" : "b" + std::to_string(k - 1);
    const std::string a = "a" + std::to_string(k), b = "b" + std::to_string(k);
    s << "C" << 2 * k - 1 << " " << a_prev << " " << a << " 10u\n";
    s << "D" << 2 * k - 1 << " " << b_prev << " " << a << " dcw\n";
    s << "D" << 2 * k << " " << a << " " << b << " dcw\n";
    s << "C" << 2 * k << " " << b_prev << " " << b << " 10u\n";
  }
  s << "RL b" << n << " 0 1g\n";
  s << ".model dcw D(VON=0.7 RON=1)\n";
  s << tran_card(50, true);
  s << ".print tran v(b" << n << ")\n.end\n";
  return s.str();
}

// Node k of the line is n_k (n_0 is the source).
std::string clamped_ladder(int n) {
  std::ostringstream s;
  s << "Clamped RC ladder, " << n << " sections of one 1 kohm, 10 nF line, a clamp diode to 2 V at every node ("
    << n << " diodes), 5 V 1 kHz\n";
  s << "V1 in 0 SIN(0 5 1k)\n";
  s << "VCL clamp 0 DC 2\n";
  const std::string r = number(1e3 / n), c = number(10e-9 / n);
  for (int k = 1; k <= n; ++k) {
    const std::string prev = k == 1 ? "in" : "n" + std::to_string(k - 1), node = "n" + std::to_string(k);
    s << "R" << k << " " << prev << " " << node << " " << r << "\n";
    s << "C" << k << " " << node << " 0 " << c << "\n";
    s << "D" << k << " " << node << " clamp dcl\n";
  }
  s << ".model dcl D(VON=0.6 RON=" << number(1e3 * n) << ")\n";
  s << tran_card(1e3, true);
  s << ".print tran v(n" << n << ")\n.end\n";
  return s.str();
}

// Branch k: in -> RS_k -> a_k -> D_k -> o_k, with C_k and RL_k from o_k to ground.
std::string rectifier_bank(int n) {
  std::ostringstream s;
  s << n << " half-wave rectifiers on one 10 V 50 Hz source, each 1 ohm, a diode, 100 uF and a 1.0-1.9 kohm load\n";
  s << "V1 in 0 SIN(0 10 50)\n";
  for (int k = 1; k <= n; ++k) {
    const std::string a = "a" + std::to_string(k), o = "o" + std::to_string(k);
    s << "RS" << k << " in " << a << " 1\n";
    s << "D" << k << " " << a << " " << o << " drect\n";
    s << "C" << k << " " << o << " 0 100u\n";
    s << "RL" << k << " " << o << " 0 " << number(1e3 + 100.0 * ((k - 1) % 10)) << "\n";
  }
  s << ".model drect D(VON=0.7 RON=0.1)\n";
  s << tran_card(50, true);
  s << ".print tran v(o1)" << (n > 1 ? " v(o" + std::to_string(n) + ")" : "") << "\n.end\n";
  return s.str();
}

}  // namespace

const char* scale_family_name(ScaleFamily family) {
  switch (family) {
    case ScaleFamily::CockcroftWalton: return "cw";
    case ScaleFamily::Ladder: return "ladder";
    case ScaleFamily::Rectifiers: return "rectifiers";
  }
  return "?";
}

std::optional<ScaleFamily> find_scale_family(const std::string& name) {
  for (ScaleFamily f : {ScaleFamily::CockcroftWalton, ScaleFamily::Ladder, ScaleFamily::Rectifiers})
    if (name == scale_family_name(f)) return f;
  return std::nullopt;
}

std::string scale_family_names() { return "cw, ladder, rectifiers"; }

int scale_family_diodes(ScaleFamily family, int n) {
  return family == ScaleFamily::CockcroftWalton ? 2 * n : n;
}

std::vector<int> default_scale_sizes(ScaleFamily family) {
  if (family == ScaleFamily::CockcroftWalton) return {5, 10, 25, 50, 100, 250, 500};
  return {10, 20, 50, 100, 200, 500, 1000};
}

std::string scale_family_output_node(ScaleFamily family, int n) {
  switch (family) {
    case ScaleFamily::CockcroftWalton: return "b" + std::to_string(n);
    case ScaleFamily::Ladder: return "n" + std::to_string(n);
    case ScaleFamily::Rectifiers: return "o" + std::to_string(n);
  }
  return "";
}

std::string scale_family_deck_name(ScaleFamily family, int n) {
  return std::string(scale_family_name(family)) + "_" + std::to_string(n) + ".cir";
}

std::string scale_family_netlist(ScaleFamily family, int n) {
  if (n < 1) throw std::invalid_argument("a circuit family needs a size of at least 1");
  switch (family) {
    case ScaleFamily::CockcroftWalton: return cockcroft_walton(n);
    case ScaleFamily::Ladder: return clamped_ladder(n);
    case ScaleFamily::Rectifiers: return rectifier_bank(n);
  }
  return "";
}

}  // namespace lcs
