// `.measure` / `.meas` cards (netlist/measure_card.h): every kind, the measures skipped with a
// warning, and the located errors of bad syntax and unknown probes.
#include <map>
#include <stdexcept>

#include <gtest/gtest.h>

#include "netlist/test/parse_helpers.h"

namespace lcs {
namespace {

using test::diag;
using test::parse;

// An RC deck with the measure card(s) from line 6 on.
std::string deck(const std::string& meas) {
  return "t\nV1 a 0 1\nR1 a b 1k\nC1 b 0 1u\n.tran 1u 5m\n" + meas + "\n";
}

const Measure& only_measure(const Netlist& n) {
  if (n.measures.size() != 1) throw std::runtime_error("expected one measure, got " + std::to_string(n.measures.size()));
  return n.measures.front();
}

TEST(MeasureCard, StatisticsWithWindow) {
  Netlist n = parse("t\n.param tp=1m\nV1 a 0 1\nR1 a b 1k\nC1 b 0 1u\n.tran 1u 5m\n"
                    ".MEAS TRAN Avg1 AVG V(b) FROM=1m TO={2*tp}\n");
  const Measure& m = only_measure(n);
  EXPECT_EQ(m.name, "avg1");
  EXPECT_EQ(m.kind, Measure::Kind::Avg);
  EXPECT_EQ(m.probe.name(), "v(b)");
  EXPECT_DOUBLE_EQ(m.from, 1e-3);
  ASSERT_TRUE(m.to.has_value());
  EXPECT_DOUBLE_EQ(*m.to, 2e-3);
  EXPECT_EQ(m.loc.line, 7);
  EXPECT_EQ(m.loc.column, 12);
  EXPECT_TRUE(n.warnings.empty());
}

TEST(MeasureCard, EveryStatisticKind) {
  const std::pair<const char*, Measure::Kind> cases[] = {
      {"avg", Measure::Kind::Avg},       {"rms", Measure::Kind::Rms},       {"min", Measure::Kind::Min},
      {"max", Measure::Kind::Max},       {"pp", Measure::Kind::Pp},         {"integ", Measure::Kind::Integ},
      {"INTEGRAL", Measure::Kind::Integ}, {"min_at", Measure::Kind::MinAt}, {"MAX_AT", Measure::Kind::MaxAt},
  };
  for (const auto& [word, kind] : cases) {
    const Measure m = only_measure(parse(deck(std::string(".meas tran x ") + word + " v(a,b)")));
    EXPECT_EQ(m.kind, kind) << word;
    EXPECT_EQ(m.probe.name(), "v(a,b)") << word;
    EXPECT_EQ(m.from, 0) << word;
    EXPECT_FALSE(m.to.has_value()) << word;
  }
}

TEST(MeasureCard, MeasureAliasAndNoAnalysisName) {
  // `.measure`, and LTspice's card without an analysis name (a transient measure).
  const Measure m = only_measure(parse(deck(".measure peak max i(v1) to=4m")));
  EXPECT_EQ(m.name, "peak");
  EXPECT_EQ(m.kind, Measure::Kind::Max);
  EXPECT_EQ(m.probe.name(), "i(v1)");
  EXPECT_DOUBLE_EQ(*m.to, 4e-3);
}

TEST(MeasureCard, FindAt) {
  const Measure m = only_measure(parse(deck(".meas tran v1ms find v(b) at=2.5m")));
  EXPECT_EQ(m.kind, Measure::Kind::FindAt);
  EXPECT_EQ(m.probe.name(), "v(b)");
  EXPECT_DOUBLE_EQ(m.at, 2.5e-3);
}

TEST(MeasureCard, FindWhenWithCount) {
  const Measure m = only_measure(parse(deck(".meas tran ix find i(v1) when v(b) = 0.5 fall=2 td=1m")));
  EXPECT_EQ(m.kind, Measure::Kind::FindWhen);
  EXPECT_EQ(m.probe.name(), "i(v1)");
  EXPECT_EQ(m.when.probe.name(), "v(b)");
  EXPECT_FALSE(m.when.other.has_value());
  EXPECT_DOUBLE_EQ(m.when.level, 0.5);
  EXPECT_EQ(m.when.edge, MeasureCrossing::Edge::Fall);
  EXPECT_EQ(m.when.count, 2);
  EXPECT_FALSE(m.when.last);
  EXPECT_DOUBLE_EQ(m.when.td, 1e-3);
}

TEST(MeasureCard, WhenProbeEqualsProbe) {
  const Measure m = only_measure(parse(deck(".meas tran tx when v(a)=v(b) cross=LAST from=1m to=4m")));
  EXPECT_EQ(m.kind, Measure::Kind::When);
  EXPECT_EQ(m.when.probe.name(), "v(a)");
  ASSERT_TRUE(m.when.other.has_value());
  EXPECT_EQ(m.when.other->name(), "v(b)");
  EXPECT_EQ(m.when.edge, MeasureCrossing::Edge::Cross);
  EXPECT_TRUE(m.when.last);
  EXPECT_DOUBLE_EQ(m.when.from, 1e-3);
  EXPECT_DOUBLE_EQ(*m.when.to, 4e-3);
  // The default: the first crossing of either kind.
  const Measure first = only_measure(parse(deck(".meas tran t50 when v(b)={1/2}")));
  EXPECT_EQ(first.when.edge, MeasureCrossing::Edge::First);
  EXPECT_DOUBLE_EQ(first.when.level, 0.5);
}

// A bare LAST is CROSS=LAST (ngspice 39.3: `when v(a)=0.5 last` is the last crossing), also in TRIG/TARG.
TEST(MeasureCard, BareLastIsCrossLast) {
  const Measure m = only_measure(parse(deck(".meas tran tl when v(b)=0.5 LAST td=1m")));
  EXPECT_EQ(m.when.edge, MeasureCrossing::Edge::Cross);
  EXPECT_TRUE(m.when.last);
  EXPECT_DOUBLE_EQ(m.when.td, 1e-3);
  const Measure f = only_measure(parse(deck(".meas tran fl find v(a) when v(b)=v(a) last")));
  EXPECT_EQ(f.when.edge, MeasureCrossing::Edge::Cross);
  EXPECT_TRUE(f.when.last);
  const Measure t = only_measure(parse(deck(".meas tran d trig v(b) val=0.5 last targ v(b) val=0.5 last")));
  EXPECT_EQ(t.when.edge, MeasureCrossing::Edge::Cross);
  EXPECT_TRUE(t.when.last);
  EXPECT_EQ(t.targ.edge, MeasureCrossing::Edge::Cross);
  EXPECT_TRUE(t.targ.last);
}

TEST(MeasureCard, TrigTarg) {
  const Measure m = only_measure(parse(deck(".meas tran trise trig v(b) val=0.1 rise=1 targ v(b) val=0.9 rise=last")));
  EXPECT_EQ(m.kind, Measure::Kind::TrigTarg);
  EXPECT_FALSE(m.when.at.has_value());
  EXPECT_EQ(m.when.probe.name(), "v(b)");
  EXPECT_DOUBLE_EQ(m.when.level, 0.1);
  EXPECT_EQ(m.when.edge, MeasureCrossing::Edge::Rise);
  EXPECT_EQ(m.when.count, 1);
  EXPECT_DOUBLE_EQ(m.targ.level, 0.9);
  EXPECT_EQ(m.targ.edge, MeasureCrossing::Edge::Rise);
  EXPECT_TRUE(m.targ.last);

  const Measure at = only_measure(parse(deck(".meas tran d trig at=1m targ v(b) val=0.5 cross=2")));
  ASSERT_TRUE(at.when.at.has_value());
  EXPECT_DOUBLE_EQ(*at.when.at, 1e-3);
  EXPECT_EQ(at.targ.edge, MeasureCrossing::Edge::Cross);
  EXPECT_EQ(at.targ.count, 2);

  // As ngspice: a FROM= on TRIG applies to TARG too (and the other way round).
  const Measure from = only_measure(parse(deck(".meas tran d trig v(b) val=.1 rise=1 from=1m targ v(b) val=.9 rise=1")));
  EXPECT_DOUBLE_EQ(from.when.from, 1e-3);
  EXPECT_DOUBLE_EQ(from.targ.from, 1e-3);
}

TEST(MeasureCard, ProbeOfAnElementLeftOutReadsZero) {
  Netlist n = parse("t\nV1 a 0 1\nR1 a b 1k\nC1 b 0 1u\nR2 b b 1\n.tran 1u 5m\n.meas tran x avg i(r2)\n");
  const Measure& m = only_measure(n);
  EXPECT_EQ(m.probe.kind, Probe::Kind::NodePairVoltage);
  EXPECT_EQ(m.probe.name(), "i(r2)");
}

TEST(MeasureCard, SkippedWithAWarning) {
  struct Case {
    const char* card;
    const char* warning;
  };
  const Case cases[] = {
      {".meas ac x max vdb(b)", "t.cir:6:7: warning: '.meas ac' is ignored (lcspice runs transient analyses)"},
      {".measure dc x find v(b) at=1", "t.cir:6:10: warning: '.measure dc' is ignored (lcspice runs transient analyses)"},
      {".meas tran x deriv v(b) at=1m",
       "t.cir:6:14: warning: '.meas' DERIV is not supported by lcspice: measure 'x' is skipped"},
      {".meas tran x err v(a) v(b)", "t.cir:6:14: warning: '.meas' ERR is not supported by lcspice: measure 'x' is skipped"},
      {".meas tran x max v(b)*2",
       "t.cir:6:18: warning: expressions of probes are not measured by lcspice (only v(node), v(node1,node2) or "
       "i(element)): measure 'x' is skipped"},
      {".meas tran x avg v(b) * 2",
       "t.cir:6:18: warning: expressions of probes are not measured by lcspice (only v(node), v(node1,node2) or "
       "i(element)): measure 'x' is skipped"},
      {".meas tran x avg v(b) -v(a) from=1m",
       "t.cir:6:18: warning: expressions of probes are not measured by lcspice (only v(node), v(node1,node2) or "
       "i(element)): measure 'x' is skipped"},
      {".meas tran x when v(b)=v(a) / 2 rise=1",
       "t.cir:6:24: warning: expressions of probes are not measured by lcspice (only v(node), v(node1,node2) or "
       "i(element)): measure 'x' is skipped"},
      {".meas tran x max par('v(b)*2')",
       "t.cir:6:18: warning: expressions of probes are not measured by lcspice (only v(node), v(node1,node2) or "
       "i(element)): measure 'x' is skipped"},
  };
  for (const Case& c : cases) {
    Netlist n = parse(deck(c.card));
    EXPECT_TRUE(n.measures.empty()) << c.card;
    ASSERT_EQ(n.warnings.size(), 1u) << c.card;
    EXPECT_EQ(n.warnings[0], c.warning);
  }
}

// The value of a PARAM measure given other measures' results.
double param_value(const Measure& m, const std::map<std::string, double>& results) {
  return m.expression.evaluate([&](const std::string& name) -> std::optional<double> {
    auto it = results.find(name);
    if (it == results.end()) return std::nullopt;
    return it->second;
  });
}

TEST(MeasureCard, ParamInEveryWritingNgspiceAccepts) {
  struct Case {
    const char* card;
    const char* text;
  };
  // ngspice 39.3 takes 'expr', {expr} and the bare expression; LTspice writes PARAM without '='.
  const Case cases[] = {
      {".meas tran r param='vmax*k+dbl(vmin)'", "vmax*k+dbl(vmin)"},
      {".meas tran r param={vmax*k+dbl(vmin)}", "vmax*k+dbl(vmin)"},
      {".meas tran r param=vmax*k+dbl(vmin)", "vmax*k+dbl(vmin)"},
      {".MEAS TRAN R PARAM VMAX*K+DBL(VMIN)", "VMAX*K+DBL(VMIN)"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.card);
    Netlist n = parse("t\n.param k=3\n.func dbl(x) {2*x}\nV1 a 0 1\nR1 a b 1k\nC1 b 0 1u\n.tran 1u 5m\n"
                      ".meas tran vmax max v(b)\n.meas tran vmin min v(b)\n" + std::string(c.card) + "\n");
    ASSERT_EQ(n.measures.size(), 3u);
    const Measure& m = n.measures[2];
    EXPECT_EQ(m.kind, Measure::Kind::Param);
    EXPECT_EQ(m.expression.text, c.text);
    ASSERT_EQ(m.expression.names.size(), 2u);
    EXPECT_EQ(m.expression.names[0].name, "vmax");
    EXPECT_EQ(m.expression.names[1].name, "vmin");
    EXPECT_EQ(m.expression.loc.line, 10);
    EXPECT_DOUBLE_EQ(param_value(m, {{"vmax", 0.5}, {"vmin", 0.25}}), 0.5 * 3 + 2 * 0.25);
    EXPECT_TRUE(n.warnings.empty()) << n.warnings.front();
  }
}

TEST(MeasureCard, ParamResultHidesAParameterOfItsName) {
  // ngspice 39.3 stores a result as a parameter: the .param is read until the measure has one.
  Netlist n = parse(deck(".param vmax=7\n.meas tran vmax max v(b)\n.meas tran r param='vmax+1'"));
  ASSERT_EQ(n.measures.size(), 2u);
  const Measure& m = n.measures[1];
  EXPECT_TRUE(m.expression.names.empty());  // read as the parameter when the card was read
  EXPECT_DOUBLE_EQ(param_value(m, {{"vmax", 0.5}}), 1.5);
  EXPECT_DOUBLE_EQ(param_value(m, {}), 8);
  EXPECT_DOUBLE_EQ(m.expression.evaluate([](const std::string&) -> std::optional<double> {
    throw std::runtime_error("measure 'vmax' failed");
  }), 8);
}

TEST(MeasureCard, ParamFailuresAtRunTimeSayWhy) {
  Netlist n = parse(deck(".meas tran vmax max v(b)\n.meas tran r param='1/(vmax-1)'"));
  ASSERT_EQ(n.measures.size(), 2u);
  const Measure& m = n.measures[1];
  EXPECT_DOUBLE_EQ(param_value(m, {{"vmax", 3}}), 0.5);
  try {
    param_value(m, {{"vmax", 1}});
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "PARAM '1/(vmax-1)': division by zero");
  }
  try {
    param_value(m, {});
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "PARAM '1/(vmax-1)': 'vmax' is neither a measure lcspice computes nor a parameter");
  }
  try {
    m.expression.evaluate([](const std::string&) -> std::optional<double> { throw std::runtime_error("measure 'vmax' failed"); });
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "PARAM '1/(vmax-1)': measure 'vmax' failed");
  }
  EXPECT_TRUE(n.warnings.empty());  // the division by zero at vmax = 1 is not the card's
}

TEST(MeasureCard, ParamNamingNoMeasureIsAWarning) {
  // ngspice runs such a deck and fails the measure; so does lcspice, warned as the deck is read,
  // at the first unknown name (past a division by zero of the values the names do not have yet).
  struct Case {
    const char* card;
    const char* warning;
  };
  const Case cases[] = {
      {".meas tran r param='vmx*2'",
       "t.cir:7:21: warning: 'vmx' is neither a measure lcspice computes nor a parameter: measure 'r' will fail"},
      {".meas tran r param='vmax*2 + vmx'",
       "t.cir:7:30: warning: 'vmx' is neither a measure lcspice computes nor a parameter: measure 'r' will fail"},
      {".meas tran r param='(vmax-vmax)/(vmax-vmax) + vmx + zz'",
       "t.cir:7:47: warning: 'vmx' and 'zz' are neither a measure lcspice computes nor a parameter: measure 'r' will "
       "fail"},
      {".meas tran r param='a+b+c+d+e+vmax'",
       "t.cir:7:21: warning: 'a', 'b', 'c' and 2 more are neither a measure lcspice computes nor a parameter: measure "
       "'r' will fail"},
  };
  for (const Case& c : cases) {
    Netlist n = parse(deck(std::string(".meas tran vmax max v(b)\n") + c.card));
    ASSERT_EQ(n.measures.size(), 2u) << c.card;
    ASSERT_EQ(n.warnings.size(), 1u) << c.card;
    EXPECT_EQ(n.warnings[0], c.warning);
  }
}

TEST(MeasureCard, ParamExpressionErrorsAreLocatedWarningsAndTheMeasureFails) {
  // ngspice 39.3 runs the deck and prints `x = failed` for each of these.
  struct Case {
    const char* card;
    const char* warning;
    const char* failure;
  };
  const Case cases[] = {
      {".meas tran x param='y*'", "t.cir:6:23: warning: unexpected end of expression: measure 'x' will fail (as in ngspice)",
       "PARAM 'y*': unexpected end of expression"},
      {".meas tran x param={y+(2}", "t.cir:6:23: warning: missing ')': measure 'x' will fail (as in ngspice)",
       "PARAM 'y+(2': missing ')'"},
      {".meas tran x param='v(b)*2'", "t.cir:6:21: warning: unknown function 'v': measure 'x' will fail (as in ngspice)",
       "PARAM 'v(b)*2': unknown function 'v'"},
      {".meas tran x param='(y-y)/(y-y) +* 2'",
       "t.cir:6:34: warning: unexpected '*' in expression: measure 'x' will fail (as in ngspice)",
       "PARAM '(y-y)/(y-y) +* 2': unexpected '*' in expression"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.card);
    Netlist n = parse(deck(std::string(".meas tran y max v(b)\n") + c.card));
    ASSERT_EQ(n.measures.size(), 2u);
    ASSERT_EQ(n.warnings.size(), 1u);
    EXPECT_EQ(n.warnings[0], std::string(c.warning).replace(6, 1, "7"));
    try {
      param_value(n.measures[1], {{"y", 2}});
      ADD_FAILURE() << "no error";
    } catch (const std::runtime_error& e) {
      EXPECT_STREQ(e.what(), c.failure);
    }
  }
  // A constant one too: its division by zero is found when the run computes it.
  Netlist n = parse(deck(".meas tran x param='1/0'"));
  EXPECT_TRUE(n.warnings.empty());
  EXPECT_THROW(param_value(only_measure(n), {}), std::runtime_error);
}

TEST(MeasureCard, ParamIsReadToTheFirstBlankAsNgspiceReadsIt) {
  // libngspice 39.3: `PARAM=vmax * 5` gives vmax, `'vmax'*7` and `{vmax}*6` too; a card with no
  // expression runs, that measure failed. LTspice's PARAM without '=' takes the rest of the line.
  struct Case {
    const char* card;
    const char* text;  // nullptr: skipped
    const char* warning;
  };
  const Case cases[] = {
      {".meas tran r param=vmax * 5", "vmax",
       "t.cir:7:25: warning: ignored after PARAM's expression, as ngspice ignores it (write PARAM='...' for one with "
       "blanks)"},
      {".meas tran r param = vmax*5 + 1", "vmax*5",
       "t.cir:7:29: warning: ignored after PARAM's expression, as ngspice ignores it (write PARAM='...' for one with "
       "blanks)"},
      {".meas tran r param='vmax'*7", "vmax",
       "t.cir:7:26: warning: ignored after PARAM's expression, as ngspice ignores it (write PARAM='...' for one with "
       "blanks)"},
      {".meas tran r param vmax * 5", "vmax * 5", nullptr},
      {".meas tran r param=", nullptr, "t.cir:7:20: warning: missing the expression after 'param=': measure 'r' is skipped"},
      {".meas tran r PARAM", nullptr, "t.cir:7:19: warning: missing the expression after 'PARAM': measure 'r' is skipped"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.card);
    Netlist n = parse(deck(std::string(".meas tran vmax max v(b)\n") + c.card));
    ASSERT_EQ(n.measures.size(), c.text ? 2u : 1u);
    if (c.text) {
      EXPECT_EQ(n.measures[1].expression.text, c.text);
    }
    if (c.warning) {
      ASSERT_EQ(n.warnings.size(), 1u);
      EXPECT_EQ(n.warnings[0], c.warning);
    } else {
      EXPECT_TRUE(n.warnings.empty());
    }
  }
}

TEST(MeasureCard, TdOnAStatisticIsIgnoredWithAWarning) {
  Netlist n = parse(deck(".meas tran x avg v(b) td=1m"));
  EXPECT_EQ(only_measure(n).from, 0);
  ASSERT_EQ(n.warnings.size(), 1u);
  EXPECT_EQ(n.warnings[0], "t.cir:6:23: warning: TD= is ignored by AVG (as in ngspice): FROM= starts its window");
}

TEST(MeasureCard, SyntaxErrors) {
  struct Case {
    const char* card;
    std::string expected;
  };
  const Case cases[] = {
      {".meas tran", "t.cir:6:11: error: missing the measure's name after 'tran'\n.meas tran\n          ^"},
      {".meas tran (", "t.cir:6:12: error: expected the measure's name, got '('\n.meas tran (\n           ^"},
      {".meas tran x",
       "t.cir:6:13: error: missing the measure's kind after 'x' (AVG, RMS, MIN, MAX, PP, INTEG, MIN_AT, MAX_AT, FIND, "
       "WHEN, TRIG or PARAM)\n.meas tran x\n            ^"},
      {".meas tran avg v(b)", "t.cir:6:12: error: missing the measure's name before 'avg'\n.meas tran avg v(b)\n           ^~~"},
      {".meas tran x foo v(b)",
       "t.cir:6:14: error: unknown measure kind 'foo' (expected AVG, RMS, MIN, MAX, PP, INTEG, MIN_AT, MAX_AT, FIND, "
       "WHEN, TRIG or PARAM)\n.meas tran x foo v(b)\n             ^~~"},
      {".meas tran x targ v(b) val=1 rise=1",
       "t.cir:6:14: error: TARG without TRIG (TRIG ... TARG ...)\n.meas tran x targ v(b) val=1 rise=1\n             ^~~~"},
      {".meas tran x avg",
       "t.cir:6:17: error: missing probe after 'avg' (v(node), v(node1,node2) or i(element))\n.meas tran x avg\n"
       "                ^"},
      {".meas tran x avg b",
       "t.cir:6:18: error: expected a probe (v(node), v(node1,node2) or i(element)), got 'b'\n.meas tran x avg b\n"
       "                 ^"},
      {".meas tran x avg v(b", "t.cir:6:19: error: missing ')'\n.meas tran x avg v(b\n                  ^"},
      {".meas tran x avg q(b)",
       "t.cir:6:18: error: invalid probe 'q(b)': expected v(node), v(node1,node2), i(element), ic/ib/ie(transistor) "
       "or i2(line)\n.meas tran x avg q(b)\n                 ^~~~"},
      {".meas tran x avg v(b) from",
       "t.cir:6:27: error: missing '=' after 'from'\n.meas tran x avg v(b) from\n                          ^"},
      {".meas tran x avg v(b) foo=1",
       "t.cir:6:23: error: unknown .meas parameter 'foo'\n.meas tran x avg v(b) foo=1\n                      ^~~"},
      {".meas tran x avg v(b) rise=1",
       "t.cir:6:23: error: RISE= does not apply to AVG\n.meas tran x avg v(b) rise=1\n                      ^~~~"},
      {".meas tran x avg v(b) from=1m from=2m",
       "t.cir:6:31: error: FROM= is given twice\n.meas tran x avg v(b) from=1m from=2m\n                              ^~~~"},
      {".meas tran x avg v(b) from=2m to=1m",
       "t.cir:6:34: error: TO= must be greater than FROM=\n.meas tran x avg v(b) from=2m to=1m\n"
       "                                 ^~"},
      {".meas tran x avg v(b) to=0", "t.cir:6:26: error: TO= must be positive\n.meas tran x avg v(b) to=0\n                         ^"},
      {".meas tran x avg v(b) from=abc",
       "t.cir:6:28: error: invalid number 'abc'\n.meas tran x avg v(b) from=abc\n                           ^~~"},
      {".meas tran x when v(b)=0.5 rise=0",
       "t.cir:6:33: error: RISE= must be a whole number from 1, or LAST\n.meas tran x when v(b)=0.5 rise=0\n"
       "                                ^"},
      {".meas tran x when v(b)=0.5 cross=1.5",
       "t.cir:6:34: error: CROSS= must be a whole number from 1, or LAST\n.meas tran x when v(b)=0.5 cross=1.5\n"
       "                                 ^~~"},
      {".meas tran x when v(b)=0.5 rise=1 fall=2",
       "t.cir:6:35: error: only one of RISE=, FALL=, CROSS= and LAST may be given\n.meas tran x when v(b)=0.5 rise=1 fall=2\n"
       "                                  ^~~~"},
      {".meas tran x when v(b)=0.5 rise=1 last",
       "t.cir:6:35: error: only one of RISE=, FALL=, CROSS= and LAST may be given\n.meas tran x when v(b)=0.5 rise=1 last\n"
       "                                  ^~~~"},
      {".meas tran x avg v(b) last",
       "t.cir:6:23: error: unexpected extra token 'last'\n.meas tran x avg v(b) last\n                      ^~~~"},
      {".meas tran x when v(b) 0.5",
       "t.cir:6:24: error: expected '=' after 'v(b)' (WHEN probe=level or probe=probe2)\n.meas tran x when v(b) 0.5\n"
       "                       ^~~"},
      {".meas tran x when v(b)=", "t.cir:6:24: error: missing level after 'v(b)='\n.meas tran x when v(b)=\n                       ^"},
      {".meas tran x trig v(a) rise=1 targ v(b) val=0.5 rise=1",
       "t.cir:6:19: error: TRIG v(a) needs VAL=level\n.meas tran x trig v(a) rise=1 targ v(b) val=0.5 rise=1\n"
       "                  ^~~~"},
      {".meas tran x trig v(a) val=0.5 targ v(b) val=0.5 rise=1",
       "t.cir:6:19: error: TRIG v(a) needs RISE=, FALL= or CROSS= (n or LAST)\n"
       ".meas tran x trig v(a) val=0.5 targ v(b) val=0.5 rise=1\n                  ^~~~"},
      {".meas tran x trig v(a) val=0.5 rise=1 targ v(b) val=0.5",
       "t.cir:6:44: error: TARG v(b) needs RISE=, FALL= or CROSS= (n or LAST)\n"
       ".meas tran x trig v(a) val=0.5 rise=1 targ v(b) val=0.5\n" + std::string(43, ' ') + "^~~~"},
      {".meas tran x trig v(a) val=0.5 rise=1",
       "t.cir:6:38: error: missing TARG after TRIG (TRIG ... TARG probe VAL=level RISE=n)\n"
       ".meas tran x trig v(a) val=0.5 rise=1\n                                     ^"},
      {".meas tran x trig at=1m rise=1 targ v(b) val=0.5 rise=1",
       "t.cir:6:25: error: RISE= does not apply to TRIG AT=\n.meas tran x trig at=1m rise=1 targ v(b) val=0.5 rise=1\n"
       "                        ^~~~"},
      {".meas tran x find v(b)", "t.cir:6:23: error: expected AT=time or WHEN after 'FIND v(b)'\n.meas tran x find v(b)\n"
                                 "                      ^"},
      {".meas tran x find v(b) at 1m",
       "t.cir:6:24: error: expected AT=time or WHEN after 'FIND v(b)'\n.meas tran x find v(b) at 1m\n                       ^~"},
      {".meas tran x find v(b) at=", "t.cir:6:27: error: missing value for 'at'\n.meas tran x find v(b) at=\n                          ^"},
      {".meas tran x find v(b) at=1m to=2m",
       "t.cir:6:30: error: TO= does not apply to FIND ... AT=\n.meas tran x find v(b) at=1m to=2m\n                             ^~"},
  };
  for (const Case& c : cases) EXPECT_EQ(diag(deck(c.card)), c.expected) << c.card;
}

TEST(MeasureCard, ProbesAreCheckedAgainstTheCircuit) {
  EXPECT_EQ(diag(deck(".meas tran x avg v(zz)")),
            "t.cir:6:18: error: unknown node 'zz'\n.meas tran x avg v(zz)\n                 ^~~~~");
  EXPECT_EQ(diag(deck(".meas tran x when i(r9)=1m")),
            "t.cir:6:19: error: unknown element 'r9'\n.meas tran x when i(r9)=1m\n                  ^~~~~");
  EXPECT_EQ(diag(deck(".meas tran x trig v(b) val=.1 rise=1 targ v(b,q) val=.9 rise=1")),
            "t.cir:6:43: error: unknown node 'q'\n.meas tran x trig v(b) val=.1 rise=1 targ v(b,q) val=.9 rise=1\n" +
                std::string(42, ' ') + "^~~~~~");
  EXPECT_EQ(diag(deck(".meas tran x find v(b) when v(a)=v(nowhere)")),
            "t.cir:6:34: error: unknown node 'nowhere'\n.meas tran x find v(b) when v(a)=v(nowhere)\n"
            "                                 ^~~~~~~~~~");
}

TEST(MeasureCard, DuplicateNamesAndPlacement) {
  EXPECT_EQ(diag(deck(".meas tran x avg v(b)\n.meas tran X max v(b)")),
            "t.cir:7:12: error: duplicate measure name 'x' (first defined at line 6)\n.meas tran X max v(b)\n           ^");
  EXPECT_EQ(diag("t\n.subckt s p\nR1 p 0 1\n.meas tran x avg v(p)\n.ends\nX1 a s\nV1 a 0 1\n.tran 1u 1m\n"),
            "t.cir:4:1: error: '.meas' is not allowed inside a subcircuit\n.meas tran x avg v(p)\n^~~~~");
}

}  // namespace
}  // namespace lcs
