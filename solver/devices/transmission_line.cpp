#include "solver/devices/transmission_line.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace lcs {

TransmissionLine::TransmissionLine(const Element& element, const Netlist& netlist,
                                   const DeviceOptions& options)
    : Device(element) {
  if (element.model.empty()) {  // T: Z0 and TD on the card
    z0_ = element.value;
    delay_ = element.delay;
    check_delay(options);
    return;
  }
  const LineModel& card = netlist.line_models.at(element.model);
  model_ = card.name;
  ignored_ = card.ignored;
  RlcgLine line{card.r, card.l, card.g, card.c, card.len};
  KernelFitOptions fit;
  // The band: from the run's length down to a tenth of the print step or of the delay.
  const double tau = card.len * std::sqrt(card.l * card.c);
  fit.t_long = options.tstop > 0 ? std::max(options.tstop, 10 * tau) : 1000 * tau;
  fit.t_short = options.tstep > 0 ? std::min(options.tstep, tau) / 10 : tau / 20;
  if (!(fit.t_short < fit.t_long)) fit.t_short = fit.t_long / 1e3;
  fit.tolerance = options.line_fit_tolerance;
  try {
    kernel_ = std::make_shared<LineKernel>(fit_line_kernel(line, fit));
  } catch (const std::invalid_argument& e) {
    throw NetlistError(element.loc, "line " + element.name + ": " + e.what());
  }
  z0_ = kernel_->z0;
  delay_ = kernel_->delay;
  admittance_ = modes_of(kernel_->admittance);
  propagation_ = modes_of(kernel_->propagation);
  check_delay(options);
}

// Every method steps at most one delay at a time: a delay a billion times shorter than the run
// is a run that never ends, refused at the card.
void TransmissionLine::check_delay(const DeviceOptions& options) const {
  if (options.tstop > 0 && options.tstop / delay_ > 1e9) {
    char buf[200];
    std::snprintf(buf, sizeof buf, "the delay of line %s (%.6g s) is too short for TSTOP = %.6g s: every method "
                  "steps at most one delay at a time (more than 1e9 steps)", name().c_str(), delay_, options.tstop);
    throw NetlistError(element_.loc, buf);
  }
}

std::vector<TransmissionLine::Mode> TransmissionLine::modes_of(const RationalFit& fit) {
  std::vector<Mode> out;
  for (size_t k = 0; k < fit.poles.size(); ++k) {
    const std::complex<double> p = fit.poles[k], r = fit.residues[k];
    if (p.imag() < 0) continue;  // the conjugate of the one before
    out.push_back({p.real(), p.imag(), r.real(), r.imag(), p.imag() > 0});
  }
  return out;
}

std::string TransmissionLine::internal_node(const std::string& what, int k) const {
  return name() + "#" + what + std::to_string(k);
}

// Branch 0: port 1 (named as the line, so i(t1) is its current), branch 1: port 2. Then, for a
// lossy line, per port: the admittance states xi, then the propagation states zeta, each a unit
// capacitor (internal node -> the port's minus node) and its driving current branch.
std::vector<BranchDecl> TransmissionLine::branches() const {
  const std::vector<std::string>& n = element_.nodes;
  std::vector<BranchDecl> out = {{name(), BranchClass::Resistor, n.at(0), n.at(1)},
                                 {name() + "#2", BranchClass::Resistor, n.at(2), n.at(3)}};
  for (int port = 0; port < 2; ++port) {
    const std::string& ref = n.at(2 * port + 1);
    int k = 0;
    for (const std::vector<Mode>* family : {&admittance_, &propagation_}) {
      const std::string tag = (family == &admittance_ ? "y" : "h") + std::to_string(port + 1) + "_";
      for (const Mode& m : *family)
        for (int part = 0; part < (m.pair ? 2 : 1); ++part, ++k) {
          const std::string node = internal_node(tag, k);
          out.push_back({node, BranchClass::Capacitor, node, ref});
          out.push_back({node + "i", BranchClass::CurrentSource, node, ref});
        }
    }
  }
  return out;
}

void TransmissionLine::stamp(const StampContext& context, Stamps& stamps) const {
  const int port[2] = {context.branch(0), context.branch(1)};
  // Internal states: local branch 2 + 2 s is state s's capacitor, 3 + 2 s its driving branch.
  int next_state = 0;
  struct Block { int first; const Mode* mode; };
  std::vector<Block> xi[2], zeta[2];
  for (int p = 0; p < 2; ++p) {
    for (const Mode& m : admittance_) {
      xi[p].push_back({next_state, &m});
      next_state += m.pair ? 2 : 1;
    }
    for (const Mode& m : propagation_) {
      zeta[p].push_back({next_state, &m});
      next_state += m.pair ? 2 : 1;
    }
  }
  auto cap = [&](int s) { return context.branch(2 + 2 * s); };
  auto drive = [&](int s) { return context.branch(3 + 2 * s); };
  // sum_i a_i xi_i over a family, in the scaled states X = |p| Re xi, Y = |p| Im xi:
  // a xi + conj(a xi) = 2 (a_r Re xi - a_i Im xi) for a pair, a xi for a real pole.
  auto contribution = [&](const std::vector<Block>& blocks, double scale, std::vector<Term>& terms) {
    for (const Block& b : blocks) {
      const Mode& m = *b.mode;
      const double mag = std::hypot(m.re, m.im);
      if (m.pair) {
        terms.push_back({Term::Of::Voltage, cap(b.first), scale * 2 * m.res_re / mag});
        terms.push_back({Term::Of::Voltage, cap(b.first + 1), -scale * 2 * m.res_im / mag});
      } else {
        terms.push_back({Term::Of::Voltage, cap(b.first), scale * m.res_re / mag});
      }
    }
  };
  // The wave port p sends: W_p = v_p + Z0 i_p + Z0 sum a xi_p (the line's Z0 b_p, b = Yc v + i).
  auto wave = [&](int p) {
    std::vector<Term> w = {{Term::Of::Voltage, port[p], 1.0}, {Term::Of::Current, port[p], z0_}};
    contribution(xi[p], z0_, w);
    return w;
  };
  // State equations: X' = sigma X - omega Y + |p| drive, Y' = omega X + sigma Y (pair), with
  // the capacitor current X' carried by the driving branch: i_drive + X' = 0.
  auto states = [&](const std::vector<Block>& blocks, const std::vector<Term>& driver) {
    for (const Block& b : blocks) {
      const Mode& m = *b.mode;
      const double mag = std::hypot(m.re, m.im);
      stamps.storage.push_back({cap(b.first), 1.0, std::nullopt});
      std::vector<Term> x = {{Term::Of::Current, drive(b.first), 1.0}, {Term::Of::Voltage, cap(b.first), m.re}};
      if (m.pair) x.push_back({Term::Of::Voltage, cap(b.first + 1), -m.im});
      for (const Term& t : driver) x.push_back({t.of, t.index, mag * t.coeff});
      stamps.relations.push_back({drive(b.first), x});
      if (!m.pair) continue;
      stamps.storage.push_back({cap(b.first + 1), 1.0, std::nullopt});
      stamps.relations.push_back({drive(b.first + 1),
                                  {{Term::Of::Current, drive(b.first + 1), 1.0},
                                   {Term::Of::Voltage, cap(b.first), m.im},
                                   {Term::Of::Voltage, cap(b.first + 1), m.re}}});
    }
  };
  int input[2];
  for (int p = 0; p < 2; ++p) {
    InputSignal in;
    in.quantity = InputSignal::Quantity::History;
    in.label = name() + ".port" + std::to_string(p + 1);
    in.element = element_index();
    input[p] = stamps.input(in);
  }
  for (int p = 0; p < 2; ++p) {
    // v_p - Z0 i_p + Z0 sum a xi_p - u_p = 0
    std::vector<Term> rel = {{Term::Of::Voltage, port[p], 1.0}, {Term::Of::Current, port[p], -z0_}};
    contribution(xi[p], z0_, rel);
    rel.push_back({Term::Of::Input, input[p], -1.0});
    stamps.relations.push_back({port[p], rel});
    states(xi[p], {{Term::Of::Voltage, port[p], 1.0}});
    states(zeta[p], wave(p));
  }
  // u_p(t) = [d W_q + sum c zeta_q](t - tau), q the other port. Before a run from rest (UIC):
  // the waves of the IC= port values, v + Z0 i.
  const double d = kernel_ ? kernel_->propagation.direct : 1.0;
  for (int p = 0; p < 2; ++p) {
    const int q = 1 - p;
    std::vector<Term> w;
    for (const Term& t : wave(q)) w.push_back({t.of, t.index, d * t.coeff});
    contribution(zeta[q], 1.0, w);
    double before = 0;
    if (element_.line_ic.size() == 4) before = d * (element_.line_ic[2 * q] + z0_ * element_.line_ic[2 * q + 1]);
    stamps.delayed.push_back({input[p], delay_, w, before});
  }
  // At DC (from (1.11)-(1.12) with d/dt = 0): v2 = cosh(th) v1 - Zc sinh(th) i1 and
  // -i2 = -(sinh(th)/Zc) v1 + cosh(th) i1, th = len sqrt(RG), Zc = sqrt(R/G); written with
  // sinh(th)/th so that G = 0 (v1 - v2 = R len i1) and R = 0 are the limits, not divisions.
  double series = 0, shunt = 0, ch = 1;
  if (kernel_) {
    const RlcgLine& l = kernel_->line;
    const double th = l.length * std::sqrt(l.r * l.g);
    const double shc = th > 0 ? std::sinh(th) / th : 1.0;
    series = l.r * l.length * shc;
    shunt = l.g * l.length * shc;
    ch = std::cosh(th);
  }
  stamps.dc_relations.push_back({{Term::Of::Voltage, port[1], 1.0},
                                 {Term::Of::Voltage, port[0], -ch},
                                 {Term::Of::Current, port[0], series}});
  stamps.dc_relations.push_back({{Term::Of::Current, port[1], 1.0},
                                 {Term::Of::Current, port[0], ch},
                                 {Term::Of::Voltage, port[0], -shunt}});
}

std::vector<std::pair<int, double>> TransmissionLine::terminal_current(char terminal) const {
  if (terminal == '2') return {{1, 1.0}};
  return {};
}

// ngspice's own lines: T (lossless) and O with an LTRA model, each port behind a 0 V ammeter
// (i(t1) and i2(t1) are their currents, into the line at p1+ and p2+).
NgspiceCards TransmissionLine::ngspice(const NgspiceDeckContext& context) const {
  NgspiceCards cards;
  const std::vector<std::string>& n = element_.nodes;
  std::string inner[2];
  for (int p = 0; p < 2; ++p) {
    const std::string meter = context.fresh(deck_name('v', "i" + std::to_string(p + 1) + "_" + name()));
    inner[p] = context.fresh("lcs_" + name() + "_" + std::to_string(p + 1));
    cards.lines.push_back(meter + " " + n.at(2 * p) + " " + inner[p] + " DC 0");
    cards.probes[p == 0 ? "i(" + name() + ")" : "i2(" + name() + ")"] = {meter + "#branch", ""};
  }
  const std::string ports = inner[0] + " " + n.at(1) + " " + inner[1] + " " + n.at(3);
  // With UIC ngspice starts a line discharged unless its card has IC=v1,i1,v2,i2 (T and LTRA).
  std::string ic;
  std::vector<double> start = element_.line_ic;
  if (context.line_initial) start.assign(context.line_initial->begin(), context.line_initial->end());
  if (start.size() == 4)
    ic = " IC=" + number(start[0]) + "," + number(start[1]) + "," + number(start[2]) + "," + number(start[3]);
  if (!kernel_) {
    cards.lines.push_back(deck_name('t', name()) + " " + ports + " Z0=" + number(z0_) + " TD=" + number(delay_) + ic);
    return cards;
  }
  const std::string model = context.fresh("lcs_ltra_" + name());
  const RlcgLine& l = kernel_->line;
  cards.lines.push_back(deck_name('o', name()) + " " + ports + " " + model + ic);
  cards.models.push_back(".model " + model + " LTRA(R=" + number(l.r) + " L=" + number(l.l) + " G=" +
                         number(l.g) + " C=" + number(l.c) + " LEN=" + number(l.length) + ")");
  return cards;
}

std::vector<std::string> TransmissionLine::notes() const {
  std::vector<std::string> out;
  char buf[320];
  if (!kernel_) {
    std::snprintf(buf, sizeof buf, "line %s: lossless, Z0 = %.6g ohm, TD = %.6g s (exact by characteristics)",
                  name().c_str(), z0_, delay_);
    out.push_back(buf);
    return out;
  }
  auto count = [](const std::vector<Mode>& modes) {
    int k = 0;
    for (const Mode& m : modes) k += m.pair ? 2 : 1;
    return k;
  };
  std::snprintf(buf, sizeof buf,
                "line %s: lossy (LTRA %s), Z0 = %.6g ohm at high frequency, delay %.6g s; kernel fitted "
                "over %.3g..%.3g rad/s: Yc by %d poles (max relative error %.2e), H e^{s tau} by %d "
                "poles (max relative error %.2e), attenuation at high frequency %.6g",
                name().c_str(), model_.c_str(), z0_, delay_, kernel_->omega_min, kernel_->omega_max,
                count(admittance_), kernel_->admittance.max_error, count(propagation_),
                kernel_->propagation.max_error, kernel_->propagation.direct);
  out.push_back(buf);
  for (const std::string& p : ignored_)
    out.push_back("line " + name() + ": LTRA parameter " + p + " is ignored (lcspice's convolution is recursive)");
  return out;
}

}  // namespace lcs
