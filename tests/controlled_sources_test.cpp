// Linear controlled sources E, G, F, H (SPEC §2) against their closed forms, with every method,
// in `op` and `run`; their topology errors; their names inside subcircuits.
#include <cmath>
#include <fstream>

#include <gtest/gtest.h>

#include "tests/cli_support.h"

namespace lcs {
namespace {

using namespace cli_testing;

// VIN ramps 0 -> 2 V over 1 ms (vin = 2000 t). Every output is memoryless in vin:
//   inverting amplifier, open-loop gain A = 1e5:   v(out1) = -A R2 vin / (R1 + R2 + A R1)
//   Norton, G1 = 1 mS into RN = 2 k:                v(n2) = gm RN vin = 2 vin
//   mirror, F1 = 2 i(vsense), i(vsense) = vin/RS:  v(out3) = 2 vin/RS R3 = vin
//   transresistance, H1 = 1 k i(vsense):           v(h) = vin, and through the diode (VON 0.7 V,
//   RON 1 ohm) into R4 = 1 k:                      v(out4) = max(0, vin - 0.7) 1000 / 1001
const char* const kClosedForms = R"(linear controlled sources: closed forms
VIN in 0 PWL(0 0 1m 2)
R1 in m 1k
R2 m out1 10k
E1 out1 0 0 m 1e5
G1 0 n2 in 0 1m
RN n2 0 2k
VSENSE in s 0
RS s 0 1k
F1 0 out3 vsense 2
R3 out3 0 500
H1 h 0 vsense 1k
D1 h out4 dmod
R4 out4 0 1k
.model dmod D(VON=0.7 RON=1)
.tran 20u 1m
.end
)";

double amplifier(double vin) {
  const double A = 1e5, R1 = 1e3, R2 = 1e4;
  return -A * R2 * vin / (R1 + R2 + A * R1);
}

const char* const kProbes = "--probe 'v(in),v(out1),v(n2),v(out3),v(h),v(out4),i(e1),i(g1)'";

TEST(ControlledSources, ClosedFormsWithEveryMethod) {
  const fs::path deck = write_deck("deck_", "closed_forms", kClosedForms);
  for (const char* method : {"event", "euler", "theta", "radau3", "radau5", "smooth"}) {
    SCOPED_TRACE(method);
    const bool smooth = std::string(method) == "smooth";
    const Csv csv = run_csv(deck, method, kProbes);
    ASSERT_GE(csv.rows.size(), 50u);
    const std::vector<double> t = column(csv, "time"), vin = column(csv, "v(in)");
    const std::vector<double> out1 = column(csv, "v(out1)"), n2 = column(csv, "v(n2)"),
                              out3 = column(csv, "v(out3)"), h = column(csv, "v(h)"),
                              out4 = column(csv, "v(out4)"), ie = column(csv, "i(e1)"), ig = column(csv, "i(g1)");
    for (size_t k = 0; k < t.size(); ++k) {
      const double u = 2000 * t[k];
      ASSERT_NEAR(vin[k], u, 1e-9) << t[k];
      EXPECT_NEAR(out1[k], amplifier(u), 1e-9) << t[k];
      EXPECT_NEAR(n2[k], 2 * u, 1e-9) << t[k];
      EXPECT_NEAR(out3[k], u, 1e-9) << t[k];
      EXPECT_NEAR(h[k], u, 1e-9) << t[k];
      // E1's current, n+ -> n- through it: it sinks what R2 brings from the summing node.
      const double vm = (u * 1e4 + amplifier(u) * 1e3) / 1.1e4;
      EXPECT_NEAR(ie[k], (vm - amplifier(u)) / 1e4, 1e-12) << t[k];
      EXPECT_NEAR(ig[k], 1e-3 * u, 1e-12) << t[k];  // from n+ (ground) through G1 into n2
      // The smooth method's Shockley junction needs N Vt ln(I/IS) = 27-33 mV more than VON.
      if (!smooth) {
        EXPECT_NEAR(out4[k], std::max(0.0, u - 0.7) * 1000 / 1001, 1e-9) << t[k];
      }
    }
    if (smooth) {
      EXPECT_NEAR(out4.back(), (2 - 0.7) * 1000 / 1001, 0.035);
    }
  }
}

// The operating point at t = 0.5 ms of the same circuit as a DC one (vin = 1 V).
TEST(ControlledSources, OperatingPoint) {
  std::string text = kClosedForms;
  text.replace(text.find("PWL(0 0 1m 2)"), 13, "DC 1");
  const fs::path deck = write_deck("deck_", "op", text);
  const Result r = run_lcspice("op '" + deck.string() + "'", deck.parent_path());
  ASSERT_EQ(r.code, 0) << r.err;
  auto value = [&](const std::string& name) {
    const size_t at = r.out.find(name + " ");
    EXPECT_NE(at, std::string::npos) << name << " in\n" << r.out;
    return at == std::string::npos ? NAN : std::strtod(r.out.c_str() + r.out.find_first_of("-0123456789", at + name.size()), nullptr);
  };
  EXPECT_NEAR(value("v(out1)"), amplifier(1), 1e-6);
  EXPECT_NEAR(value("v(n2)"), 2, 1e-6);
  EXPECT_NEAR(value("v(out3)"), 1, 1e-6);
  EXPECT_NEAR(value("v(out4)"), 0.3 * 1000 / 1001, 1e-6);
}

// A capacitor charged by a G source (Norton: gm vin into R || C) has the RC closed form, and the
// same with an F mirror of a source current and an H source behind a resistor.
TEST(ControlledSources, NortonChargesACapacitorWithItsTimeConstant) {
  const fs::path deck = write_deck("deck_", "norton", R"(Norton with a capacitor
VIN in 0 DC 1
RIN in 0 1k
G1 0 n in 0 2m
RN n 0 1k
CN n 0 1u
.tran 10u 5m UIC
.end
)");
  for (const char* method : {"event", "radau5"}) {
    SCOPED_TRACE(method);
    const Csv csv = run_csv(deck, method, "--probe 'v(n)'");
    const std::vector<double> t = column(csv, "time"), v = column(csv, "v(n)");
    const double tol = std::string(method) == "event" ? 1e-9 : 1e-5;
    for (size_t k = 0; k < t.size(); ++k) EXPECT_NEAR(v[k], 2 * (1 - std::exp(-t[k] / 1e-3)), tol) << t[k];
  }
}

// Inside a subcircuit F and H name the instance's own V source, as ngspice resolves them.
TEST(ControlledSources, ControlNamesResolveInsideTheirSubcircuit) {
  const fs::path deck = write_deck("deck_", "subckt", R"(current mirror in a subcircuit
.subckt mirror in out
VS in s 0
RS s 0 1k
F1 0 out vs 3
.ends
V1 a 0 DC 2
X1 a b mirror
R1 b 0 100
.tran 1u 10u
.end
)");
  const Csv csv = run_csv(deck, "euler", "--probe 'v(b),i(x1.vs)'");
  EXPECT_NEAR(column(csv, "v(b)").back(), 3 * 2e-3 * 100, 1e-12);
  EXPECT_NEAR(column(csv, "i(x1.vs)").back(), 2e-3, 1e-15);
}

struct TopologyCase {
  const char* text;
  const char* message;
};

TEST(ControlledSources, TopologyErrorsNameTheElements) {
  const TopologyCase cases[] = {
      {"E loop\nV1 a 0 1\nE1 a 0 b 0 2\nR1 b 0 1k\n.tran 1u 1m\n.end\n",
       "error: voltage sources form a loop: e1 and v1"},
      {"H on C\nV1 a 0 1\nR1 a 0 1k\nH1 b 0 v1 10\nC1 b 0 1u\n.tran 1u 1m\n.end\n",
       "error: capacitor c1 is in a loop of capacitors and voltage sources with a controlled voltage source "
       "(c1 and h1)"},
      {"G on L\nV1 a 0 1\nR1 a 0 1k\nG1 0 b a 0 1m\nL1 b 0 1m\n.tran 1u 1m\n.end\n",
       "error: inductor l1 is in a cutset of inductors and current sources with a controlled current source "
       "(l1 and g1)"},
      {"F series I\nV1 a 0 1\nR1 a 0 1k\nF1 b 0 v1 2\nI1 b 0 1m\n.tran 1u 1m\n.end\n",
       "error: current sources form a cutset: "},
      // A transistor's CJE and CJC with a controlled source across collector and emitter: the
      // loop is named by branch and the advice fits a capacitor inside a device.
      {"E across CE\nvin in 0 PULSE(0 5 10n 1n 1n 40n 100n)\ne1 c 0 in 0 1\nrb in b 10k\nq1 c b 0 qn\n"
       ".model qn NPN(BF=50 VON=0.7 RON=10 CJE=1p CJC=5p)\n.tran 1n 100n\n.end\n",
       "error: capacitor q1:cbc is in a loop of capacitors and voltage sources with a controlled voltage source "
       "(q1:cbc, e1 and q1:cbe): its voltage would follow the controlled source, not be a state; add a resistance in "
       "series with a terminal of q1 in that loop, or take the capacitance out of q1's model"},
  };
  int k = 0;
  for (const TopologyCase& c : cases) {
    const fs::path deck = write_deck("deck_", "topology" + std::to_string(k++), c.text);
    const Result r = run_lcspice("run '" + deck.string() + "' -o -", deck.parent_path());
    EXPECT_EQ(r.code, 2) << c.text << r.err;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << r.err;
  }
}

}  // namespace
}  // namespace lcs
