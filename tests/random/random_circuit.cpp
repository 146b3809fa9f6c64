#include "tests/random/random_circuit.h"

#include <algorithm>
#include <map>
#include <random>
#include <sstream>
#include <utility>
#include <vector>

namespace lcs::random_circuit {

namespace {

// An exact decimal m * 10^e. Sums align the exponents; nothing here rounds.
struct Dec {
  std::int64_t m = 0;
  int e = 0;
};

Dec operator+(Dec a, Dec b) {
  while (a.e > b.e) a.m *= 10, --a.e;
  while (b.e > a.e) b.m *= 10, --b.e;
  return {a.m + b.m, a.e};
}
Dec times(Dec a, std::int64_t k) { return {a.m * k, a.e}; }
Dec shift(Dec a, int decades) { return {a.m, a.e + decades}; }

std::string str(Dec d) { return spice_number(d.m, d.e); }

// Draws from mt19937_64 through integer arithmetic only (std::uniform_int_distribution's
// algorithm is the library's choice, so its sequence differs between implementations).
class Draw {
 public:
  explicit Draw(std::uint64_t seed) : rng_(seed) {}
  // Uniform in [lo, hi]; the modulo bias (< 2^-50 for these ranges) does not matter here.
  int in(int lo, int hi) {
    return lo + static_cast<int>(rng_() % static_cast<std::uint64_t>(hi - lo + 1));
  }
  bool chance(int percent) { return in(0, 99) < percent; }
  template <class T>
  const T& pick(const std::vector<T>& v) {
    return v[static_cast<std::size_t>(in(0, static_cast<int>(v.size()) - 1))];
  }
  // A value of the E12 series in [10^decade, 8.2 * 10^decade].
  Dec e12(int decade) {
    static const std::vector<int> kE12 = {10, 12, 15, 18, 22, 27, 33, 39, 47, 56, 68, 82};
    return {pick(kE12), decade - 1};
  }

 private:
  std::mt19937_64 rng_;
};

// splitmix64's finaliser: neighbouring (seed, variant) pairs get unrelated streams.
std::uint64_t mix(std::uint64_t seed, int variant) {
  std::uint64_t z = seed * 0x9e3779b97f4a7c15ull + static_cast<std::uint64_t>(variant) + 1;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

class Generator {
 public:
  Generator(std::uint64_t seed, int variant) : draw_(mix(seed, variant)) {
    // TSTOP = tm * 10^tp, tm in {1, 2, 5}: every fraction and reciprocal below is exact.
    tm_ = draw_.pick(std::vector<int>{1, 2, 5});
    tp_ = draw_.in(-6, 0);
    tstop_ = {tm_, tp_};
    numbered_nodes_ = draw_.chance(30);
    ground_ = draw_.chance(20) ? "gnd" : "0";
  }

  bool rough() const { return rough_; }  // Deck::rough

  std::string deck(std::uint64_t seed, int variant) {
    const int named = draw_.in(2, 7);
    for (int k = 0; k < named; ++k) nodes_.push_back(node_name(k + 1));
    // Resistor spanning tree: node k hangs from ground or an earlier node.
    for (int k = 0; k < named; ++k) {
      const int parent = draw_.in(-1, k - 1);
      cards_.push_back(card("R", nodes_[static_cast<std::size_t>(k)],
                            parent < 0 ? ground_ : nodes_[static_cast<std::size_t>(parent)],
                            resistance(), false));
    }
    source_cards();
    for (int k = draw_.in(0, 2); k > 0; --k) between_nodes("R", resistance());
    for (int k = draw_.in(0, 3); k > 0; --k) between_nodes("C", capacitance());
    for (int k = draw_.in(0, 2); k > 0; --k) between_nodes("L", inductance());
    for (int k = draw_.in(1, 6); k > 0; --k) diode();

    std::ostringstream out;
    out << "random circuit, seed " << seed << " variant " << variant << "\n";
    for (const std::string& c : cards_) out << c << "\n";
    for (const std::string& m : models_) out << m << "\n";
    out << tran_card() << "\n";
    if (draw_.chance(30)) out << print_card() << "\n";
    out << ".end\n";
    return out.str();
  }

 private:
  std::string node_name(int k) const {
    return numbered_nodes_ ? std::to_string(k) : "n" + std::to_string(k);
  }
  std::string fresh_name(const std::string& letter) { return letter + std::to_string(++count_[letter]); }

  // A random node (ground included) and a different one.
  std::pair<std::string, std::string> node_pair() {
    const int n = static_cast<int>(nodes_.size());
    const int a = draw_.in(-1, n - 1);
    int b = draw_.in(-1, n - 2);
    if (b >= a) ++b;
    auto name = [&](int k) { return k < 0 ? ground_ : nodes_[static_cast<std::size_t>(k)]; };
    if (draw_.chance(50)) return {name(a), name(b)};
    return {name(b), name(a)};
  }

  std::string card(const std::string& letter, const std::string& a, const std::string& b,
                   const std::string& value, bool with_ic) {
    const std::string name = fresh_name(letter);
    names_.push_back(name);
    std::string c = name + " " + a + " " + b + " " + value;
    if (with_ic) c += " IC=" + str(letter == "C" ? voltage() : current());
    return c;
  }
  void between_nodes(const std::string& letter, const std::string& value) {
    auto [a, b] = node_pair();
    if (letter == "L" && !join_shorted(a, b)) return;
    cards_.push_back(card(letter, a, b, value, uic_ && draw_.chance(50)));
  }

  // Nodes tied together by inductors and the voltage source (shorts at DC). An inductor that
  // would close a loop of them is left out: with the source in the loop there is no operating
  // point (it shorts the source), without it the loop's current is undetermined.
  std::string root(const std::string& node) {
    auto it = shorted_.find(node);
    if (it == shorted_.end() || it->second == node) return node;
    return it->second = root(it->second);
  }
  bool join_shorted(const std::string& a, const std::string& b) {
    const std::string ra = root(a), rb = root(b);
    if (ra == rb) return false;
    shorted_[ra] = rb;
    return true;
  }

  // Resistances 10 Ω .. 82 kΩ. With the nominal 1 kΩ, capacitances and inductances give time
  // constants RC and L/R of 10^-3..0.82 TSTOP and LC periods of at least 2π·0.03 TSTOP.
  std::string resistance() { return str(draw_.e12(draw_.in(1, 4))); }
  std::string capacitance() { return str(draw_.e12(tp_ - 3 + draw_.in(-3, -1))); }
  std::string inductance() { return str(draw_.e12(tp_ + 3 + draw_.in(-1, 0))); }

  // Source values: volts in [-9.9, 9.9] (currents the same in mA, through the nominal 1 kΩ).
  Dec voltage() { return {draw_.in(-99, 99), -1}; }
  Dec current() { return {draw_.in(-99, 99), -4}; }
  Dec level(bool amps) { return amps ? current() : voltage(); }
  Dec amplitude(bool amps) { return shift(draw_.e12(draw_.in(0, 1)), amps ? -4 : -1); }
  Dec of_tstop(int num, int den_decades) { return times(shift(tstop_, -den_decades), num); }
  // k / TSTOP, exactly: 1 / (tm 10^tp) = (10 / tm) 10^(-tp - 1).
  Dec per_tstop(int k_tenths) { return {static_cast<std::int64_t>(k_tenths) * (10 / tm_), -tp_ - 2}; }

  std::string waveform(bool amps) {
    switch (draw_.in(0, 3)) {
      case 0:
      {  // two draws, one per statement, in the order gcc gave the operands of + (unspecified)
        const Dec value = level(amps);
        const bool dc = draw_.chance(50);
        return (dc ? "DC " : "") + str(value);
      }
      case 1:
        return sin_waveform(amps);
      case 2:
        return pulse_waveform(amps);
      default:
        return pwl_waveform(amps);
    }
  }

  std::string sin_waveform(bool amps) {
    std::vector<std::string> p = {str(level(amps)), str(amplitude(amps)),
                                  str(per_tstop(draw_.pick(std::vector<int>{5, 10, 20, 30, 50})))};
    const int optional = draw_.in(0, 3);  // how many of TD THETA PHASE are written
    if (optional >= 1) p.push_back(draw_.chance(50) ? "0" : str(of_tstop(draw_.in(1, 3), 1)));
    if (optional >= 2) p.push_back(draw_.chance(50) ? "0" : str(per_tstop(10 * draw_.in(1, 5))));
    if (optional >= 3) p.push_back(std::to_string(draw_.in(-180, 180)));
    return "SIN(" + join(p) + ")";
  }

  std::string pulse_waveform(bool amps) {
    const Dec tr = edge(), tf = edge(), pw = of_tstop(draw_.in(1, 6), 1), td = of_tstop(draw_.in(0, 5), 1);
    const Dec per = tr + tf + pw + of_tstop(draw_.in(1, 8), 1);
    const std::vector<std::string> all = {str(level(amps)), str(level(amps)), str(td),
                                          str(tr), str(tf), str(pw), str(per)};
    // Written: V1 V2 and 0-5 more; the rest take the ngspice defaults (TR = TF = TSTEP, PW = PER = TSTOP).
    const int written = draw_.in(2, 7);
    if ((written >= 4 && tr.m == 0) || (written >= 5 && tf.m == 0)) rough_ = true;
    return "PULSE(" + join({all.begin(), all.begin() + written}) + ")";
  }
  // A PULSE edge: a jump (1 in 10), else 1/1000 to 50/1000 of TSTOP.
  Dec edge() {
    if (draw_.chance(10)) return {0, 0};
    return of_tstop(draw_.pick(std::vector<int>{1, 2, 5, 10, 20, 50}), 3);
  }

  std::string pwl_waveform(bool amps) {
    std::vector<std::string> p;
    Dec t = draw_.chance(50) ? Dec{0, 0} : of_tstop(draw_.in(1, 3), 1);
    bool last_was_jump = true;  // no jump at the first point
    for (int k = draw_.in(2, 6); k > 0; --k) {
      if (p.size() >= 2 && str(t) == p[p.size() - 2]) rough_ = true;  // a jump
      p.push_back(str(t));
      p.push_back(str(level(amps)));
      const bool jump = !last_was_jump && draw_.chance(10);
      t = t + (jump ? Dec{0, 0} : of_tstop(draw_.in(1, 4), 1));
      last_was_jump = jump;
    }
    return "PWL(" + join(p) + ")";
  }

  void source_cards() {
    uic_ = draw_.chance(25);
    rough_ = rough_ || uic_;
    // The voltage source from a node to ground (or between two nodes), sometimes a current source.
    const std::string a = nodes_[static_cast<std::size_t>(draw_.in(0, static_cast<int>(nodes_.size()) - 1))];
    if (draw_.chance(70)) {
      cards_.push_back(card("V", a, ground_, waveform(false), false));
      join_shorted(a, ground_);
    } else {
      auto [p, n] = node_pair();
      cards_.push_back(card("V", p, n, waveform(false), false));
      join_shorted(p, n);
    }
    if (draw_.chance(30)) {
      auto [p, n] = node_pair();
      cards_.push_back(card("I", p, n, waveform(true), false));
    }
  }

  // A diode with its own model, between two nodes or (1 in 5, while there is room for a node)
  // in series with an inductor through a node that only they reach.
  void diode() {
    const std::string model = "dm" + std::to_string(models_.size() + 1);
    models_.push_back(".model " + model + " D(" + diode_params() + ")");
    auto [a, b] = node_pair();
    if (nodes_.size() < 7 && draw_.chance(20)) {
      const std::string mid = numbered_nodes_ ? std::to_string(nodes_.size() + 1) : "m" + std::to_string(nodes_.size() + 1);
      cards_.push_back(card("D", a, mid, model, false));
      // Its IC= flows in the diode's forward direction: a current the diode cannot carry has no
      // solution at t = 0 (an ideal diode cannot stop an inductor's current; exit 3, SPEC §4).
      join_shorted(mid, b);  // mid is new: no loop
      std::string l = card("L", mid, b, inductance(), false);
      if (uic_ && draw_.chance(50)) l += " IC=" + str({draw_.in(0, 99), -4});
      cards_.push_back(l);
      nodes_.push_back(mid);
      return;
    }
    cards_.push_back(card("D", a, b, model, false));
  }
  std::string diode_params() {
    const int mv = draw_.in(0, 1000);
    std::string p;
    if (mv > 0 || draw_.chance(50)) p = "VON=" + str({mv, -3}) + " ";
    const Dec ron = draw_.chance(5) ? Dec{100, 0} : draw_.e12(draw_.in(-2, 1));
    return p + "RON=" + str(ron);
  }

  std::string tran_card() {
    // TSTEP = TSTOP / N, N in {100, 200, 500, 1000}.
    const Dec tstep = times(shift(tstop_, -3), draw_.pick(std::vector<int>{10, 5, 2, 1}));
    std::string c = ".tran " + str(tstep) + " " + str(tstop_);
    if (uic_) c += draw_.chance(50) ? " 0 " + str(tstep) + " UIC" : " UIC";
    return c;
  }

  std::string print_card() {
    std::vector<std::string> probes;
    for (int k = draw_.in(1, 4); k > 0; --k) {
      switch (draw_.in(0, 2)) {
        case 0:
          probes.push_back("v(" + draw_.pick(nodes_) + ")");
          break;
        case 1: {
          auto [a, b] = node_pair();
          probes.push_back("v(" + a + "," + b + ")");
          break;
        }
        default:
          probes.push_back("i(" + draw_.pick(names_) + ")");
      }
    }
    std::sort(probes.begin(), probes.end());
    probes.erase(std::unique(probes.begin(), probes.end()), probes.end());
    return ".print tran " + join(probes);
  }

  static std::string join(const std::vector<std::string>& parts) {
    std::string out;
    for (const std::string& p : parts) out += (out.empty() ? "" : " ") + p;
    return out;
  }

  Draw draw_;
  int tm_ = 1, tp_ = 0;
  Dec tstop_;
  bool numbered_nodes_ = false, uic_ = false, rough_ = false;
  std::string ground_;
  std::vector<std::string> nodes_, names_, cards_, models_;
  std::map<std::string, int> count_;
  std::map<std::string, std::string> shorted_;
};

}  // namespace

std::string spice_number(std::int64_t m, int e) {
  if (m == 0) return "0";
  const bool negative = m < 0;
  std::uint64_t u = negative ? static_cast<std::uint64_t>(-m) : static_cast<std::uint64_t>(m);
  while (u % 10 == 0) u /= 10, ++e;
  std::string digits = std::to_string(u);
  // Exponent of the leading digit, and the suffix at or below it.
  const int lead = e + static_cast<int>(digits.size()) - 1;
  static const std::pair<int, const char*> kSuffixes[] = {
      {9, "g"}, {6, "meg"}, {3, "k"}, {0, ""}, {-3, "m"}, {-6, "u"}, {-9, "n"}, {-12, "p"}, {-15, "f"}};
  int s = -15;
  const char* suffix = "f";
  for (const auto& [power, name] : kSuffixes)
    if (lead >= power) {
      s = power;
      suffix = name;
      break;
    }
  // Value = digits * 10^(e - s) in units of the suffix.
  const int point = static_cast<int>(digits.size()) + (e - s);  // digits before the decimal point
  std::string text;
  if (point <= 0)
    text = "0." + std::string(static_cast<std::size_t>(-point), '0') + digits;
  else if (point >= static_cast<int>(digits.size()))
    text = digits + std::string(static_cast<std::size_t>(point - static_cast<int>(digits.size())), '0');
  else
    text = digits.substr(0, static_cast<std::size_t>(point)) + "." + digits.substr(static_cast<std::size_t>(point));
  return (negative ? "-" : "") + text + suffix;
}

Deck generate(std::uint64_t seed, int variant) {
  Deck d;
  d.seed = seed;
  d.variant = variant;
  Generator g(seed, variant);
  d.text = g.deck(seed, variant);
  d.rough = g.rough();
  return d;
}

}  // namespace lcs::random_circuit
