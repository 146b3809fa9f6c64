// Netlists built in code, so model and integrator tests do not depend on the parser.
#pragma once

#include <utility>

#include <optional>
#include <string>
#include <vector>

#include "netlist/netlist.h"

namespace lcs::testing {

class NetlistBuilder {
 public:
  NetlistBuilder& r(const std::string& name, const std::string& a, const std::string& b, double v) {
    return add(ElementKind::Resistor, name, a, b, v);
  }
  NetlistBuilder& c(const std::string& name, const std::string& a, const std::string& b, double v,
                    std::optional<double> ic = {}) {
    add(ElementKind::Capacitor, name, a, b, v);
    net_.elements.back().ic = ic;
    return *this;
  }
  NetlistBuilder& l(const std::string& name, const std::string& a, const std::string& b, double v,
                    std::optional<double> ic = {}) {
    add(ElementKind::Inductor, name, a, b, v);
    net_.elements.back().ic = ic;
    return *this;
  }
  NetlistBuilder& k(const std::string& name, const std::string& l1, const std::string& l2, double k) {
    Element e;
    e.kind = ElementKind::Coupling;
    e.name = name;
    e.value = k;
    e.coupled = {l1, l2};
    net_.elements.push_back(e);
    return *this;
  }
  NetlistBuilder& v(const std::string& name, const std::string& a, const std::string& b, Waveform w) {
    add(ElementKind::VoltageSource, name, a, b, 0);
    w.resolve(tstep_, tstop_);
    net_.elements.back().waveform = w;
    return *this;
  }
  NetlistBuilder& i(const std::string& name, const std::string& a, const std::string& b, Waveform w) {
    add(ElementKind::CurrentSource, name, a, b, 0);
    w.resolve(tstep_, tstop_);
    net_.elements.back().waveform = w;
    return *this;
  }
  NetlistBuilder& d(const std::string& name, const std::string& a, const std::string& b,
                    double von = 0, double ron = 0) {
    const std::string model = "m_" + name;
    add(ElementKind::Diode, name, a, b, 0);
    net_.elements.back().model = model;
    DiodeModel m;
    m.name = model;
    m.von = von;
    m.ron = ron;
    net_.diode_models[model] = m;
    return *this;
  }
  NetlistBuilder& tran(double tstep, double tstop, bool uic) {
    tstep_ = tstep;
    tstop_ = tstop;
    TranSpec t;
    t.tstep = tstep;
    t.tstop = tstop;
    t.uic = uic;
    net_.tran = t;
    for (Element& e : net_.elements) e.waveform.resolve(tstep, tstop);
    return *this;
  }
  Netlist build() const { return net_; }

  static Waveform dc(double v) {
    Waveform w;
    w.dc = v;
    return w;
  }
  static Waveform sin(double vo, double va, double freq) {
    Waveform w;
    w.kind = Waveform::Kind::Sin;
    w.params = {vo, va, freq};
    return w;
  }
  static Waveform pulse(std::vector<double> p) {
    Waveform w;
    w.kind = Waveform::Kind::Pulse;
    w.params = std::move(p);
    return w;
  }

 private:
  NetlistBuilder& add(ElementKind kind, const std::string& name, const std::string& a,
                      const std::string& b, double value) {
    Element e;
    e.kind = kind;
    e.name = name;
    e.nodes = {a, b};
    e.value = value;
    e.loc.file = "built.cir";
    e.loc.line = static_cast<int>(net_.elements.size()) + 2;
    e.loc.column = 1;
    net_.elements.push_back(e);
    return *this;
  }
  Netlist net_ = [] {
    Netlist n;
    n.file = "built.cir";
    n.title = "built in code";
    return n;
  }();
  double tstep_ = 0, tstop_ = 0;
};

}  // namespace lcs::testing
