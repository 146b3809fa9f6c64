// The device interface: the registry, what each device stamps, and the history hooks
// (accept / max_step) every integrator must honour before a device with history exists.
#include "solver/devices/device.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "solver/devices/device_registry.h"
#include "solver/devices/diode.h"
#include "solver/integrators/method_registry.h"
#include "solver/integrators/transient.h"
#include "solver/model/circuit_model.h"
#include "tests/support/netlist_builder.h"

namespace lcs {
namespace {

using testing::NetlistBuilder;

// Every card the netlist reader makes has exactly one device, and the table is sorted by letter.
TEST(DeviceRegistry, SortedByLetterAndOneDevicePerElementKind) {
  const std::vector<DeviceEntry>& table = device_registry();
  for (size_t k = 1; k < table.size(); ++k) EXPECT_LT(table[k - 1].letter, table[k].letter);
  const ElementKind kinds[] = {ElementKind::Resistor,      ElementKind::Inductor,
                               ElementKind::Capacitor,     ElementKind::Coupling,
                               ElementKind::VoltageSource, ElementKind::CurrentSource,
                               ElementKind::Diode,         ElementKind::Bjt,
                               ElementKind::Line,          ElementKind::LossyLine,
                               ElementKind::Vcvs,          ElementKind::Vccs,
                               ElementKind::Cccs,          ElementKind::Ccvs,
                               ElementKind::VSwitch,       ElementKind::CSwitch};
  for (ElementKind kind : kinds) {
    const auto n = std::count_if(table.begin(), table.end(),
                                 [&](const DeviceEntry& e) { return e.kind == kind; });
    EXPECT_EQ(n, 1) << element_kind_name(kind);
  }
  EXPECT_EQ(table.size(), std::size(kinds));
}

// The stamps of a small circuit with every element kind, collected in card order.
struct Stamped {
  Netlist netlist;
  std::vector<std::shared_ptr<Device>> devices;
  CircuitGraph graph;
  Stamps stamps;
  int branch(const std::string& name) const {
    for (int b = 0; b < static_cast<int>(graph.branches.size()); ++b)
      if (graph.branches[b].name == name) return b;
    return -1;
  }
};

Stamped stamp_all(const NetlistBuilder& b) {
  Stamped s;
  s.netlist = b.build();
  s.devices = make_devices(s.netlist, {});
  s.graph = graph_of_devices(s.devices);
  int first = 0;
  for (const auto& d : s.devices) {
    d->stamp(StampContext{s.graph, first}, s.stamps);
    first += static_cast<int>(d->branches().size());
  }
  return s;
}

NetlistBuilder every_kind() {
  NetlistBuilder b;
  b.v("v1", "a", "0", NetlistBuilder::dc(5)).r("r1", "a", "b", 47);
  b.c("c1", "b", "0", 2e-6, 1.5).l("l1", "b", "c", 3e-3, 0.25).l("l2", "d", "0", 12e-3);
  b.k("k1", "l1", "l2", 0.9).d("d1", "c", "0", 0.7, 0.05).i("i1", "0", "d", NetlistBuilder::dc(2e-3));
  return b;
}

const Stamps::Relation* relation_of(const Stamps& s, int branch) {
  for (const auto& r : s.relations)
    if (r.branch == branch) return &r;
  return nullptr;
}

TEST(DeviceStamps, ResistorIsOhmsLawOverItsBranch) {
  const Stamped s = stamp_all(every_kind());
  const int b = s.branch("r1");
  const Stamps::Relation* r = relation_of(s.stamps, b);
  ASSERT_NE(r, nullptr);
  ASSERT_EQ(r->terms.size(), 2u);  // v_b - R i_b = 0
  EXPECT_EQ(r->terms[0].of, Term::Of::Voltage);
  EXPECT_EQ(r->terms[0].index, b);
  EXPECT_EQ(r->terms[0].coeff, 1.0);
  EXPECT_EQ(r->terms[1].of, Term::Of::Current);
  EXPECT_EQ(r->terms[1].index, b);
  EXPECT_EQ(r->terms[1].coeff, -47.0);
}

TEST(DeviceStamps, SourcesAreInputsInCardOrder) {
  const Stamped s = stamp_all(every_kind());
  ASSERT_EQ(s.stamps.inputs.size(), 2u);
  EXPECT_EQ(s.stamps.inputs[0].label, "v1");
  EXPECT_EQ(s.stamps.inputs[0].quantity, InputSignal::Quantity::Voltage);
  EXPECT_EQ(s.stamps.inputs[1].label, "i1");
  EXPECT_EQ(s.stamps.inputs[1].quantity, InputSignal::Quantity::Current);
  // v_b(v1) = u_1 and i_b(i1) = u_2 (u_0 = 1 is the thresholds' input).
  const Stamps::Relation* v = relation_of(s.stamps, s.branch("v1"));
  const Stamps::Relation* i = relation_of(s.stamps, s.branch("i1"));
  ASSERT_NE(v, nullptr);
  ASSERT_NE(i, nullptr);
  EXPECT_EQ(v->terms[0].of, Term::Of::Voltage);
  EXPECT_EQ(v->terms[1].of, Term::Of::Input);
  EXPECT_EQ(v->terms[1].index, 1);
  EXPECT_EQ(i->terms[0].of, Term::Of::Current);
  EXPECT_EQ(i->terms[1].index, 2);
}

TEST(DeviceStamps, StorageCouplingAndPair) {
  const Stamped s = stamp_all(every_kind());
  ASSERT_EQ(s.stamps.storage.size(), 3u);
  EXPECT_EQ(s.stamps.storage[0].branch, s.branch("c1"));
  EXPECT_EQ(s.stamps.storage[0].value, 2e-6);
  EXPECT_EQ(s.stamps.storage[0].ic, 1.5);
  EXPECT_EQ(s.stamps.storage[1].branch, s.branch("l1"));
  EXPECT_EQ(s.stamps.storage[1].ic, 0.25);
  EXPECT_FALSE(s.stamps.storage[2].ic.has_value());
  ASSERT_EQ(s.stamps.couplings.size(), 1u);
  EXPECT_EQ(s.stamps.couplings[0].branch_a, s.branch("l1"));
  EXPECT_EQ(s.stamps.couplings[0].branch_b, s.branch("l2"));
  EXPECT_EQ(s.stamps.couplings[0].k, 0.9);
  ASSERT_EQ(s.stamps.pairs.size(), 1u);
  EXPECT_EQ(s.stamps.pairs[0].branch, s.branch("d1"));
  EXPECT_EQ(s.stamps.pairs[0].law.name, "d1");
  EXPECT_EQ(s.stamps.pairs[0].law.law.von, 0.7);
  EXPECT_EQ(s.stamps.pairs[0].law.law.ron, 0.05);
  EXPECT_FALSE(s.stamps.pairs[0].law.fitted);
  // The coupling adds no branch; every other device adds one.
  EXPECT_EQ(s.graph.branches.size(), s.netlist.elements.size() - 1);
}

TEST(DeviceStamps, CouplingOfAMissingInductorPointsAtItsCard) {
  NetlistBuilder b;
  b.v("v1", "a", "0", NetlistBuilder::dc(1)).l("l1", "a", "0", 1e-3).k("k1", "l1", "lx", 0.5);
  try {
    stamp_all(b);
    FAIL() << "expected NetlistError";
  } catch (const NetlistError& e) {
    EXPECT_NE(std::string(e.what()).find("coupling k1 needs two inductors"), std::string::npos)
        << e.what();
  }
}

// A diode card without VON/RON gets the chord of its Shockley curve between ifit/10 and 10 ifit.
TEST(DeviceStamps, DiodeWithoutThresholdIsFittedAtIfit) {
  NetlistBuilder b;
  b.v("v1", "a", "0", NetlistBuilder::dc(1)).r("r1", "a", "b", 10);
  Netlist n = b.build();
  Element d;
  d.kind = ElementKind::Diode;
  d.name = "d1";
  d.nodes = {"b", "0"};
  d.model = "dm";
  n.elements.push_back(d);
  DiodeModel m;
  m.name = "dm";
  m.is = 1e-14;
  m.n = 1.0;
  n.diode_models["dm"] = m;
  DeviceOptions o;
  o.ifit = 0.1;
  std::unique_ptr<Device> dev = make_device(n.elements.back(), n, o);
  const auto* diode = dynamic_cast<const Diode*>(dev.get());
  ASSERT_NE(diode, nullptr);
  const double v1 = kThermalVoltage * std::log1p(0.01 / 1e-14);
  const double v2 = kThermalVoltage * std::log1p(1.0 / 1e-14);
  EXPECT_TRUE(diode->law().fitted);
  EXPECT_NEAR(diode->law().law.ron, (v2 - v1) / 0.99, 1e-12);
  EXPECT_NEAR(diode->law().law.von, v1 - diode->law().law.ron * 0.01, 1e-12);
}

// --- History hooks -------------------------------------------------------------------------

class HistoryHooks : public ::testing::TestWithParam<std::string> {};

// A half-wave rectifier (a switching diode) feeding a matched line of delay 70 us: every method
// records the waves after every step it accepts, in order, ends at TSTOP, and never steps
// further than the line's delay, even where its own step (fixed TSTEP, or the adaptive choice)
// would be longer.
TEST_P(HistoryHooks, EveryMethodAcceptsEachStepInOrderWithinMaxStep) {
  const double tstep = 2e-4, tstop = 20e-3, limit = 7e-5;  // limit < tstep: substeps
  const Netlist netlist = parse_netlist_string(
      "history hooks\nv1 in 0 sin(0 10 100)\nd1 in out dm\n.model dm d(von=0.7 ron=0.1)\n"
      "c1 out 0 10u\nr1 out 0 1k\nt1 out 0 far 0 z0=50 td=70u\nrl far 0 50\n.tran 0.2m 20m\n.end\n",
      "hooks.cir");
  ModelOptions mo;
  mo.t1 = tstop;
  CircuitModel model = CircuitModel::build(netlist, mo);
  ASSERT_TRUE(model.has_history());
  ASSERT_EQ(model.max_step(), limit);

  TransientOptions o;
  o.method = GetParam();
  o.step = tstep;
  o.tstop = tstop;
  MemorySink sink;
  run_transient(model, model.output_map(model.default_probes()), o, sink);

  const std::deque<double>& t = model.history().times();
  ASSERT_GE(t.size(), static_cast<size_t>(std::ceil(tstop / limit)));
  EXPECT_GE(t.front(), 0.0);
  EXPECT_LE(t.front(), limit * (1 + 1e-9));
  for (size_t k = 1; k < t.size(); ++k) {
    ASSERT_GE(t[k], t[k - 1]) << "accept " << k;
    ASSERT_LE(t[k] - t[k - 1], limit * (1 + 1e-9)) << "accept " << k << " at t = " << t[k];
  }
  EXPECT_NEAR(t.back(), tstop, 1e-12 * tstop);
  // Rows stay where the method puts them without the line: at least every TSTEP.
  EXPECT_NEAR(sink.times.back(), tstop, 1e-12 * tstop);
}

std::vector<std::string> every_method() {
  std::vector<std::string> names;
  for (const MethodEntry& e : method_registry()) names.push_back(e.name);
  return names;
}

INSTANTIATE_TEST_SUITE_P(Methods, HistoryHooks, ::testing::ValuesIn(every_method()),
                         [](const auto& info) { return info.param; });

// Without a device with history the hooks are inert: no limit on the step.
TEST(HistoryHooks, InertWithoutHistoryDevices) {
  NetlistBuilder b;
  b.v("v1", "a", "0", NetlistBuilder::dc(1)).r("r1", "a", "b", 1).c("c1", "b", "0", 1e-6);
  CircuitModel m = CircuitModel::build(b.build(), {});
  EXPECT_FALSE(m.has_history());
  EXPECT_TRUE(std::isinf(m.max_step()));
}

}  // namespace
}  // namespace lcs
