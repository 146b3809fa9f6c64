// `.options` read once into NetlistOptions: values, and a located NetlistError for each bad one.
#include "solver/model/netlist_options.h"

#include <gtest/gtest.h>

#include "solver/model/circuit_model.h"
#include "solver/model/smooth_netlist.h"

namespace lcs {
namespace {

const char* const kCircuit = "options\nV1 a 0 DC 5\nR1 a b 1k\nD1 b 0 dx\n.model dx D\n";

NetlistOptions read(const std::string& options_line) {
  return read_netlist_options(parse_netlist_string(kCircuit + options_line + "\n.end\n", "deck.cir"));
}

// The NetlistError of reading `options_line` (line 6 of the deck).
NetlistError error_of(const std::string& options_line) {
  const Netlist netlist = parse_netlist_string(kCircuit + options_line + "\n.end\n", "deck.cir");
  try {
    read_netlist_options(netlist);
  } catch (const NetlistError& e) {
    return e;
  }
  ADD_FAILURE() << "no error for " << options_line;
  return NetlistError(SourceLocation{}, "");
}

TEST(NetlistOptions, NothingGiven) {
  const NetlistOptions o = read("* no options");
  EXPECT_FALSE(o.ifit);
  EXPECT_EQ(o.method, "");
  EXPECT_FALSE(o.gear);
  EXPECT_FALSE(o.theta);
  EXPECT_TRUE(o.IsValid(nullptr));
}

TEST(NetlistOptions, ValuesAndUnknownNames) {
  const NetlistOptions o = read(".options reltol=1e-4 foo=bar noacct ifit=10m method=Theta theta=0.25");
  ASSERT_TRUE(o.ifit);
  EXPECT_DOUBLE_EQ(*o.ifit, 10e-3);  // a SPICE number: 10m is 10 mA
  EXPECT_EQ(o.method, "theta");
  ASSERT_TRUE(o.theta);
  EXPECT_EQ(*o.theta, 0.25);
  EXPECT_EQ(*read(".options ifit=2e-3").ifit, 2e-3);
  EXPECT_EQ(*read(".options ifit={1m*3}").ifit, 3e-3);
}

TEST(NetlistOptions, NgspiceMethodNames) {
  for (const std::string trap : {"trap", "trapezoidal"}) {
    const NetlistOptions o = read(".options method=" + trap);
    EXPECT_EQ(o.method, "theta") << trap;
    ASSERT_TRUE(o.theta) << trap;
    EXPECT_EQ(*o.theta, 0.5) << trap;
  }
  const NetlistOptions explicit_theta = read(".options method=trap theta=0.75");
  EXPECT_EQ(*explicit_theta.theta, 0.75);  // theta= wins over trap's 0.5
  const NetlistOptions gear = read(".options method=gear");
  EXPECT_TRUE(gear.gear);
  EXPECT_EQ(gear.method, "");
  EXPECT_EQ(read(".options method=event").method, "event");
}

TEST(NetlistOptions, UnknownMethodIsLocated) {
  const NetlistError e = error_of(".options reltol=1e-3 method=rk4");
  EXPECT_EQ(e.message(), "unknown method 'rk4' (known: euler, event, radau3, radau5, smooth, theta, trap)");
  EXPECT_EQ(e.location().file, "deck.cir");
  EXPECT_EQ(e.location().line, 6);
  EXPECT_EQ(e.location().column, 22);
}

TEST(NetlistOptions, ThetaOutsideTheUnitIntervalIsLocated) {
  for (const std::string bad : {"1.5", "-0.1", "abc", "0.5m"}) {
    const NetlistError e = error_of(".options theta=" + bad);
    EXPECT_EQ(e.message(), ".options theta must be a number in [0, 1]") << bad;
    EXPECT_EQ(e.location().line, 6) << bad;
    EXPECT_EQ(e.location().column, 10) << bad;
  }
  EXPECT_EQ(error_of(".options theta").message(), ".options theta must be a number in [0, 1]");
}

TEST(NetlistOptions, BadIfitIsLocated) {
  for (const std::string bad : {"ifit=0", "ifit=-1m", "ifit=abc", "ifit=1x2", "ifit=1e999", "ifit"}) {
    const NetlistError e = error_of(".options noacct " + bad);
    EXPECT_EQ(e.message(), ".options ifit must be a positive number of amperes") << bad;
    EXPECT_EQ(e.location().file, "deck.cir") << bad;
    EXPECT_EQ(e.location().line, 6) << bad;
    EXPECT_EQ(e.location().column, 17) << bad;
    EXPECT_EQ(e.formatted().rfind("deck.cir:6:17: error: .options ifit must be a positive number of amperes\n", 0), 0u)
        << e.formatted();
  }
}

TEST(NetlistOptions, IsValid) {
  NetlistOptions o;
  std::string why;
  EXPECT_TRUE(o.IsValid(&why));
  o.ifit = 0;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_EQ(why, ".options ifit must be a positive number of amperes");
  o.ifit = 1e-3;
  o.theta = 2;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_EQ(why, ".options theta must be a number in [0, 1]");
  o.theta = 1;
  o.method = "rk4";
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_EQ(why, "unknown method 'rk4' (known: euler, event, radau3, radau5, smooth, theta, trap)");
  o.method = "radau5";
  EXPECT_TRUE(o.IsValid(&why));
}

// The model and the smoothed netlist read ifit through read_netlist_options: the same value
// (10m is the default 10 mA, not 10 A) and the same error.
TEST(NetlistOptions, ModelAndSmoothNetlistUseIt) {
  auto law = [](const std::string& options_line) {
    const Netlist n = parse_netlist_string(kCircuit + options_line + "\n.tran 1u 10u\n.end\n", "deck.cir");
    const CircuitModel m = CircuitModel::build(n, ModelOptions{});
    EXPECT_TRUE(m.pairs().at(0).fitted);
    return m.pairs().at(0).law;
  };
  const IdealDiodeLaw by_default = law("* none"), ten_milli = law(".options ifit=10m"), one = law(".options ifit=1");
  EXPECT_EQ(ten_milli.von, by_default.von);
  EXPECT_EQ(ten_milli.ron, by_default.ron);
  EXPECT_NE(one.von, by_default.von);

  const Netlist bad = parse_netlist_string(kCircuit + std::string(".options ifit=0\n.tran 1u 10u\n.end\n"), "deck.cir");
  try {
    CircuitModel::build(bad, ModelOptions{});
    ADD_FAILURE() << "CircuitModel::build accepted ifit=0";
  } catch (const NetlistError& e) {
    EXPECT_EQ(e.message(), ".options ifit must be a positive number of amperes");
    EXPECT_EQ(e.location().line, 6);
  }
  try {
    smooth_netlist(bad, SmoothingOptions{});
    ADD_FAILURE() << "smooth_netlist accepted ifit=0";
  } catch (const NetlistError& e) {
    EXPECT_EQ(e.message(), ".options ifit must be a positive number of amperes");
    EXPECT_EQ(e.location().column, 10);
  }
  // A good value passes through (the smoothed card of a fitted diode keeps its own IS, N, RS).
  const Netlist ok = parse_netlist_string(kCircuit + std::string(".options ifit=1\n.end\n"), "deck.cir");
  EXPECT_EQ(smooth_netlist(ok, SmoothingOptions{}).diode_models.at("dx").n, 1.0);
}

}  // namespace
}  // namespace lcs
