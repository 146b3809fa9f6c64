// Exact diagnostics: FILE:LINE:COL: error: message, the line, and the caret under the token.
#include <gtest/gtest.h>

#include "netlist/test/parse_helpers.h"

namespace lcs {
namespace {

using test::diag;

struct Case {
  const char* text;
  const char* expected;
};

void check(const std::vector<Case>& cases) {
  for (const Case& c : cases) EXPECT_EQ(diag(c.text), c.expected) << "input:\n" << c.text;
}

TEST(ParseDiagnostics, SyntaxAndElements) {
  check({
      {"t\nY1 a b 1\n",
       "t.cir:2:1: error: TXL transmission lines ('Y' cards) are outside lcspice's scope (ideal diodes and bipolar "
       "transistors)\nY1 a b 1\n^~"},
      {"t\n1R a b 1\n", "t.cir:2:1: error: unknown element type '1'\n1R a b 1\n^~"},
      {"t\nE1 a 0 value={2*v(b)}\n",
       "t.cir:2:8: error: behavioural sources (VALUE=) are outside lcspice's scope (ideal diodes and bipolar "
       "transistors)\nE1 a 0 value={2*v(b)}\n       ^~~~~"},
      {"t\nV1 a 0 1\nF1 b 0 r9 2\n", "t.cir:3:8: error: 'f1': controlling voltage source 'r9' is not defined\nF1 b 0 r9 2\n       ^~"},
      {"t\nV1 a 0 1\nR9 a 0 1\nH1 b 0 r9 2\n",
       "t.cir:4:8: error: 'h1': 'r9' is not a voltage source (it is a resistor); F and H are controlled by a V "
       "source's current\nH1 b 0 r9 2\n       ^~"},
      {"t\nG1 a 0 b 0\n", "t.cir:2:11: error: missing value for 'g1'\nG1 a 0 b 0\n          ^"},
      {"t\nV1 c 0 1\nS1 a 0 c 0 m1\n.model m1 CSW(IT=1)\n",
       "t.cir:3:12: error: model 'm1' is not an SW model (it is CSW); S switches take SW (or VSWITCH) models\nS1 a 0 c 0 m1\n"
       "           ^~"},
      {"t\nV1 c 0 1\nW1 a 0 v1 m1 maybe\n.model m1 CSW\n",
       "t.cir:3:14: error: unexpected extra token 'maybe'\nW1 a 0 v1 m1 maybe\n             ^~~~~"},
      {"t\n( a b\n", "t.cir:2:1: error: expected an element or a control card, got '('\n( a b\n^"},
      {"t\nL1 a a 1m\n", "t.cir:2:6: error: l1 connects node 'a' to itself (the current of an inductor shorted by "
                          "itself is not set by the circuit)\nL1 a a 1m\n     ^"},
      {"t\nV1 0 gnd 1\n", "t.cir:2:6: error: v1 connects node '0' to itself (a voltage source cannot hold a "
                           "voltage across a short)\nV1 0 gnd 1\n     ^~~"},
      {"t\nR1 a b 1k\nR2 b 0 1\nr1 c d 2k\n",
       "t.cir:4:1: error: duplicate element name 'r1' (first defined at line 2)\nr1 c d 2k\n^~"},
      {"t\nR1 a b\n", "t.cir:2:7: error: missing value for 'r1'\nR1 a b\n      ^"},
      {"t\nC1 a\n", "t.cir:2:5: error: missing node for 'c1'\nC1 a\n    ^"},
      {"t\nR1 ( b 1\n", "t.cir:2:4: error: expected a node name, got '('\nR1 ( b 1\n   ^"},
      {"t\nR1 a b 1k extra\n", "t.cir:2:11: error: unexpected extra token 'extra'\nR1 a b 1k extra\n          ^~~~~"},
      {"t\nC1 a b 1u IC=1 foo=2\n",
       "t.cir:2:16: error: unknown parameter 'foo' for 'c1'\nC1 a b 1u IC=1 foo=2\n               ^~~"},
      {"t\nR1 a b 0\n", "t.cir:2:8: error: resistance of 'r1' must be positive\nR1 a b 0\n       ^"},
      {"t\nR1 a b 1k m=0\n", "t.cir:2:13: error: multiplier m of 'r1' must be positive\nR1 a b 1k m=0\n            ^"},
      {"t\nC1 a b 1u m=-2 IC=1\n",
       "t.cir:2:13: error: multiplier m of 'c1' must be positive\nC1 a b 1u m=-2 IC=1\n            ^~"},
      {"t\nR1 a b 1k IC=1\n", "t.cir:2:11: error: unknown parameter 'IC' for 'r1'\nR1 a b 1k IC=1\n          ^~"},
      {"t\nD1 a b dm 0\n.model dm D\n", "t.cir:2:11: error: area of 'd1' must be positive\nD1 a b dm 0\n          ^"},
      {"t\nD1 a b dm m=0\n.model dm D\n", "t.cir:2:13: error: multiplier m of 'd1' must be positive\nD1 a b dm m=0\n            ^"},
      {"t\nD1 a b dm xyz=2\n.model dm D\n", "t.cir:2:11: error: unknown parameter 'xyz' for 'd1'\nD1 a b dm xyz=2\n          ^~~"},
      {"t\nL1 a b -1m\n", "t.cir:2:8: error: inductance of 'l1' must be positive\nL1 a b -1m\n       ^~~"},
      {"t\nC1 a b {0*1}\n", "t.cir:2:8: error: capacitance of 'c1' must be positive\nC1 a b {0*1}\n       ^~~~~"},
      {"t\nD1 a b (m)\n", "t.cir:2:8: error: expected a model name, got '('\nD1 a b (m)\n       ^"},
      {"t\n+ R1 a b 1\n", "t.cir:2:1: error: continuation line without a card to continue\n+ R1 a b 1\n^"},
      {"t\nR1 a b 1k\n+ 2k\n", "t.cir:3:3: error: unexpected extra token '2k'\n+ 2k\n  ^~"},
  });
}

TEST(ParseDiagnostics, BipolarTransistorCards) {
  check({
      {"t\nQ1 c b e qmod\n", "t.cir:2:10: error: transistor model 'qmod' is not defined\nQ1 c b e qmod\n         ^~~~"},
      {"t\nQ1 c b e qm\n.model qm zz(bf=10)\n",
       "t.cir:3:11: error: unsupported model type 'zz'\n.model qm zz(bf=10)\n          ^~"},
      {"t\nD1 a 0 qm\n.model qm npn(bf=10)\n",
       "t.cir:2:8: error: model 'qm' is not a diode model (it is NPN)\nD1 a 0 qm\n       ^~"},
      {"t\nQ1 c b e dm\n.model dm d(von=0.7)\n",
       "t.cir:2:10: error: model 'dm' is not a transistor model (it is D)\nQ1 c b e dm\n         ^~"},
      {"t\nQ1 c b\n", "t.cir:2:7: error: missing node for 'q1'\nQ1 c b\n      ^"},
      {"t\nQ1 c b e\n", "t.cir:2:9: error: missing model name for 'q1'\nQ1 c b e\n        ^"},
      {"t\nQ1 c b e qm\n.model qm npn(bf=0)\n",
       "t.cir:3:18: error: transistor parameter 'bf' must be positive\n.model qm npn(bf=0)\n                 ^"},
      {"t\nQ1 c b e qm\n.model qm pnp(br=-1)\n",
       "t.cir:3:18: error: transistor parameter 'br' must not be negative\n.model qm pnp(br=-1)\n                 ^~"},
      {"t\nQ1 c b e qm\n.model qm npn(bogus=1)\n",
       "t.cir:3:15: error: unknown transistor model parameter 'bogus'\n.model qm npn(bogus=1)\n              ^~~~~"},
      {"t\nQ1 c b e qm 0\n.model qm npn\n",
       "t.cir:2:13: error: area of 'q1' must be positive\nQ1 c b e qm 0\n            ^"},
      {"t\nQ1 c c c qm\n.model qm npn\n",
       "t.cir:2:4: error: q1 connects all three terminals to node 'c'\nQ1 c c c qm\n   ^"},
      {"t\nQ1 c b e qm 2 3\n.model qm npn\n",
       "t.cir:2:15: error: unexpected extra token '3'\nQ1 c b e qm 2 3\n              ^"},
  });
}

TEST(ParseDiagnostics, UnsupportedCards) {
  check({
      {"t\n  tline a 0 b 0 z0=50\n", "t.cir:2:22: error: missing TD= (or F= [NL=]) for 'tline'\n  tline a 0 b 0 z0=50\n                     ^"},
      {"t\n  tline a 0 b 0 z0=-50 td=1n\n",
       "t.cir:2:20: error: Z0 of 'tline' must be positive\n  tline a 0 b 0 z0=-50 td=1n\n                   ^~~"},
      {"t\nT1 a a b 0 z0=50 td=1n\n", "t.cir:2:6: error: port 1 of 't1' connects node 'a' to itself\nT1 a a b 0 z0=50 td=1n\n     ^"},
      {"t\nT1 a 0 b 0 z0=50 td=1n ic=1,2\n",
       "t.cir:2:24: error: IC= of 't1' takes four values v1,i1,v2,i2\nT1 a 0 b 0 z0=50 td=1n ic=1,2\n                       ^~"},
      {"t\nO1 a 0 b 0 lmod\n", "t.cir:2:12: error: line model 'lmod' is not defined\nO1 a 0 b 0 lmod\n           ^~~~"},
      {"t\n.model lm ltra(l=1u c=1p len=-1)\n",
       "t.cir:2:30: error: line parameter 'len' must be positive\n.model lm ltra(l=1u c=1p len=-1)\n                             ^~"},
      {"t\nD1 a 0 dx\n.lib foo.lib\n",
       "t.cir:3:6: error: cannot open library file 'foo.lib'; the deck needs it: diode model 'dx' is not defined "
       "(t.cir:2:8)\n"
       ".lib foo.lib\n     ^~~~~~~"},
      {"t\n.endc\n", "t.cir:2:1: error: '.endc' without '.control'\n.endc\n^~~~~"},
  });
}

TEST(ParseDiagnostics, Numbers) {
  check({
      {"t\nR1 a b 1x2\n", "t.cir:2:8: error: invalid number '1x2'\nR1 a b 1x2\n       ^~~"},
      {"t\nR1 a b 1k5\n", "t.cir:2:8: error: invalid number '1k5' (a suffix in place of the decimal point is not read: write 1.5k)\nR1 a b 1k5\n       ^~~"},
      {"t\nV1 a 0 SIN(0 1 x)\n", "t.cir:2:16: error: invalid number 'x'\nV1 a 0 SIN(0 1 x)\n               ^"},
      {"t\nR1 a b 1k}\n", "t.cir:2:10: error: unmatched '}'\nR1 a b 1k}\n         ^"},
  });
}

TEST(ParseDiagnostics, Expressions) {
  check({
      {"t\nR1 a b {2*foo}\n", "t.cir:2:11: error: undefined parameter 'foo'\nR1 a b {2*foo}\n          ^~~"},
      {"t\n.param a=1\nR1 a b { a + Bogus }\n",
       "t.cir:3:14: error: undefined parameter 'Bogus'\nR1 a b { a + Bogus }\n             ^~~~~"},
      {"t\nR1 a b {1/0}\n", "t.cir:2:10: error: division by zero\nR1 a b {1/0}\n         ^"},
      {"t\nR1 a b {(1+2}\n", "t.cir:2:9: error: missing ')'\nR1 a b {(1+2}\n        ^"},
      {"t\nR1 a b {1+\n", "t.cir:2:8: error: missing '}'\nR1 a b {1+\n       ^"},
      {"t\nR1 a b {}\n", "t.cir:2:9: error: empty expression\nR1 a b {}\n        ^"},
      {"t\nR1 a b {1+}\n", "t.cir:2:11: error: unexpected end of expression\nR1 a b {1+}\n          ^"},
      {"t\nR1 a b {sqrt(-4)}\n", "t.cir:2:9: error: invalid argument to 'sqrt'\nR1 a b {sqrt(-4)}\n        ^~~~"},
      {"t\n.param a={b} b={a}\nR1 1 0 {a}\n",
       "t.cir:2:17: error: parameter 'a' is defined in terms of itself\n.param a={b} b={a}\n                ^"},
      {"t\n.param x = 2*y\n", "t.cir:2:14: error: undefined parameter 'y'\n.param x = 2*y\n             ^"},
      {"t\n.param 1a=2\n", "t.cir:2:8: error: invalid parameter name '1a'\n.param 1a=2\n       ^~"},
      {"t\n.param pi=3\n", "t.cir:2:8: error: cannot redefine 'pi'\n.param pi=3\n       ^~"},
      {"t\n.param a\n", "t.cir:2:9: error: missing '=' after 'a'\n.param a\n        ^"},
  });
}

TEST(ParseDiagnostics, Sources) {
  check({
      {"t\nV1 a 0 SIN(0 1 1k\n", "t.cir:2:11: error: missing ')'\nV1 a 0 SIN(0 1 1k\n          ^"},
      {"t\nV1 a 0 SIN(0)\n", "t.cir:2:8: error: 'sin' needs at least 2 parameters\nV1 a 0 SIN(0)\n       ^~~"},
      {"t\nV1 a 0 SIN(0 1 2 3 4 5 6 7)\n",
       "t.cir:2:26: error: 'sin' takes at most 7 parameters\nV1 a 0 SIN(0 1 2 3 4 5 6 7)\n                         ^"},
      {"t\nV1 a 0 SIN(0 1 -2 3 4 5 6)\n",
       "t.cir:2:16: error: sin NCYCLES needs a positive frequency (the cycles of FREQ -2 do not end)\n"
       "V1 a 0 SIN(0 1 -2 3 4 5 6)\n               ^~"},
      {"t\nV1 a 0 SIN(0 1 2 3 4 5 -6)\n",
       "t.cir:2:24: error: sin cycle count NCYCLES must not be negative\nV1 a 0 SIN(0 1 2 3 4 5 -6)\n"
       "                       ^~"},
      {"t\nV1 a 0 PULSE(0 1 0 -1n)\n",
       "t.cir:2:20: error: pulse rise time must not be negative\nV1 a 0 PULSE(0 1 0 -1n)\n                   ^~~"},
      {"t\nI1 a 0 PWL(0 0 1 1 0.5 2)\n",
       "t.cir:2:20: error: pwl times must not decrease\nI1 a 0 PWL(0 0 1 1 0.5 2)\n                   ^~~"},
      {"t\nV1 a 0 PWL(0 0 1)\n",
       "t.cir:2:16: error: 'pwl' needs time-value pairs (odd number of values)\nV1 a 0 PWL(0 0 1)\n               ^"},
      {"t\nV1 a 0 TRNOISE(0 1)\n",
       "t.cir:2:8: error: unsupported source function 'TRNOISE'\nV1 a 0 TRNOISE(0 1)\n       ^~~~~~~"},
      {"t\nV1 a 0 EXP(0)\n", "t.cir:2:8: error: 'exp' needs at least 2 parameters\nV1 a 0 EXP(0)\n       ^~~"},
      {"t\nV1 a 0 EXP(0 1 0 1 2 3 4)\n",
       "t.cir:2:24: error: 'exp' takes at most 6 parameters\nV1 a 0 EXP(0 1 0 1 2 3 4)\n                       ^"},
      {"t\nV1 a 0 EXP(0 1 0 -1)\n",
       "t.cir:2:18: error: exp time constant must not be negative\nV1 a 0 EXP(0 1 0 -1)\n                 ^~"},
      {"t\nI1 a 0 SFFM 0 1 2 3 4 5 6 7 8\n",
       "t.cir:2:29: error: 'sffm' takes at most 8 parameters\nI1 a 0 SFFM 0 1 2 3 4 5 6 7 8\n                            ^"},
      {"t\nV1 a 0 AM(1)\n", "t.cir:2:8: error: 'am' needs at least 2 parameters\nV1 a 0 AM(1)\n       ^~"},
      {"t\nV1 a 0 SINE(1)\n", "t.cir:2:8: error: 'sine' needs at least 2 parameters\nV1 a 0 SINE(1)\n       ^~~~"},
      {"t\nV1 a 0 1 m=2\n",
       "t.cir:2:10: error: unknown parameter 'm' for 'v1' (a voltage source has no multiplier)\nV1 a 0 1 m=2\n         ^"},
      {"t\nI1 a 0 1 m=0\n", "t.cir:2:12: error: multiplier m of 'i1' must be positive\nI1 a 0 1 m=0\n           ^"},
      {"t\nV1 a 0 DC 1 DC 2\n", "t.cir:2:13: error: second DC value for 'v1'\nV1 a 0 DC 1 DC 2\n            ^~"},
      {"t\nV1 a 0 5 6\n", "t.cir:2:10: error: unexpected extra token '6'\nV1 a 0 5 6\n         ^"},
  });
}

TEST(ParseDiagnostics, Models) {
  check({
      {"t\nD1 a b dx\n", "t.cir:2:8: error: diode model 'dx' is not defined\nD1 a b dx\n       ^~"},
      {"t\nD1 a b q\n.model q npn(bf=100)\n",
       "t.cir:2:8: error: model 'q' is not a diode model (it is NPN)\nD1 a b q\n       ^"},
      {"t\n.model d1 D(von=0.7 foo=1)\n",
       "t.cir:2:21: error: unknown diode model parameter 'foo'\n.model d1 D(von=0.7 foo=1)\n                    ^~~"},
      {"t\n.model d1 D(ron=-1)\n", "t.cir:2:17: error: diode parameter 'ron' must not be negative\n.model d1 D(ron=-1)\n                ^~"},
      {"t\n.model d1 D(is=0)\n", "t.cir:2:16: error: diode parameter 'is' must be positive\n.model d1 D(is=0)\n               ^"},
      {"t\n.model d1 d n=-1\n", "t.cir:2:15: error: diode parameter 'n' must be positive\n.model d1 d n=-1\n              ^~"},
      {"t\n.model d1 d\n+ rs=-2\n", "t.cir:3:6: error: diode parameter 'rs' must not be negative\n+ rs=-2\n     ^~"},
      {"t\n.model m1 NMOS(vto=1)\nM1 d g 0 0 m1\n",
       "t.cir:3:1: error: MOSFETs are outside lcspice's scope (ideal diodes and bipolar transistors)\nM1 d g 0 0 m1\n^~"},
      {"t\n.model d1 D(von=0.7\n", "t.cir:2:12: error: missing ')'\n.model d1 D(von=0.7\n           ^"},
      {"t\n.model d1 D\n.model D1 D\n", "t.cir:3:8: error: model 'd1' is already defined at line 2\n.model D1 D\n       ^~"},
  });
}

TEST(ParseDiagnostics, Couplings) {
  check({
      {"t\nK1 L1 L2 1.5\nL1 a 0 1\nL2 b 0 1\n",
       "t.cir:2:10: error: coupling coefficient of 'k1' must be in [-1, 1]\nK1 L1 L2 1.5\n         ^~~"},
      {"t\nK1 L1 L2 -1.005\nL1 a 0 1\nL2 b 0 1\n",
       "t.cir:2:10: error: coupling coefficient of 'k1' must be in [-1, 1]\nK1 L1 L2 -1.005\n         ^~~~~~"},
      {"t\nK1 L1 L3 0.5\nL1 a 0 1\nL2 b 0 1\n",
       "t.cir:2:7: error: coupled inductor 'l3' is not defined\nK1 L1 L3 0.5\n      ^~"},
      {"t\nK1 L1 R1 0.5\nL1 a 0 1\nR1 b 0 1\n", "t.cir:2:7: error: 'r1' is not an inductor\nK1 L1 R1 0.5\n      ^~"},
      {"t\nK1 L1 l1 0.5\nL1 a 0 1\n", "t.cir:2:7: error: 'k1' couples 'l1' with itself\nK1 L1 l1 0.5\n      ^~"},
      {"t\nL1 a 0 1\nL2 b 0 1\nK1 L1 L2 0.5\nK2 L2 L1 0.1\n",
       "t.cir:5:1: error: inductors 'l2' and 'l1' are already coupled by 'k1'\nK2 L2 L1 0.1\n^~"},
  });
}

TEST(ParseDiagnostics, Subcircuits) {
  const std::string sub = "t\n.subckt s a b\nR1 a b 1\n.ends\n";
  check({
      {(sub + "X1 a s\n").c_str(), "t.cir:5:6: error: 'x1' connects 1 node but subcircuit 's' has 2 ports\nX1 a s\n     ^"},
      {(sub + "X1 a b foo\n").c_str(), "t.cir:5:8: error: subcircuit 'foo' is not defined\nX1 a b foo\n       ^~~"},
      {(sub + "X1 a b s m=0\n").c_str(), "t.cir:5:12: error: multiplier m of 'x1' must be positive\nX1 a b s m=0\n           ^"},
      {(sub + "X1 a b s n=2\n").c_str(), "t.cir:5:10: error: subcircuit 's' has no parameter 'n'\nX1 a b s n=2\n         ^"},
      {(sub + "X1 a b s\nX1 c d s\n").c_str(),
       "t.cir:6:1: error: duplicate instance name 'x1' (first defined at line 5)\nX1 c d s\n^~"},
      {(sub + "X1 a b s r=1\n").c_str(), "t.cir:5:10: error: subcircuit 's' has no parameter 'r'\nX1 a b s r=1\n         ^"},
      {"t\n.subckt s a b\nX1 a b s\n.ends\nX1 a b s\n",
       "t.cir:3:8: error: recursive instantiation of subcircuit 's'\nX1 a b s\n       ^"},
      {"t\n.subckt s a b\nR1 a b 1\n", "t.cir:2:1: error: missing '.ends' for subcircuit 's'\n.subckt s a b\n^~~~~~~"},
      {"t\n.subckt s a b\nR1 a b 1\n.ends t\n", "t.cir:4:7: error: '.ends t' does not match '.subckt s'\n.ends t\n      ^"},
      {"t\n.ends\n", "t.cir:2:1: error: '.ends' without '.subckt'\n.ends\n^~~~~"},
      {"t\n.subckt s a a\n.ends\n", "t.cir:2:13: error: duplicate port 'a' in subcircuit 's'\n.subckt s a a\n            ^"},
      {"t\n.subckt s a\n.ends\n.subckt S b\n.ends\n",
       "t.cir:4:9: error: subcircuit 's' is already defined at line 2\n.subckt S b\n        ^"},
      {"t\n.subckt s a\n.tran 1 2\n.ends\n", "t.cir:3:1: error: '.tran' is not allowed inside a subcircuit\n.tran 1 2\n^~~~~"},
      {"t\n.subckt s a\nR1 a a2 1\nR1 a 0 1\n.ends\nX1 a s\n",
       "t.cir:4:1: error: duplicate element name 'x1.r1' (first defined at line 3)\nR1 a 0 1\n^~"},
      {"t\n.subckt s a b params: w=1\nR1 a b {w*h}\n.ends\nX1 n 0 s\n",
       "t.cir:3:11: error: undefined parameter 'h'\nR1 a b {w*h}\n          ^"},
      {"t\n.subckt s a b\nL1 a b 1\n.ends\nX1 n n s\n",
       "t.cir:3:6: error: x1.l1 connects node 'n' to itself (the current of an inductor shorted by itself is not "
       "set by the circuit)\nL1 a b 1\n     ^"},
  });
}

TEST(ParseDiagnostics, ControlCards) {
  check({
      {"t\n.tran -1u 1m\n", "t.cir:2:7: error: '.tran' step must be positive\n.tran -1u 1m\n      ^~~"},
      {"t\n.tran\n", "t.cir:2:6: error: '.tran' needs TSTEP and TSTOP\n.tran\n     ^"},
      {"t\n.tran -1u\n", "t.cir:2:7: error: '.tran' stop time must be positive\n.tran -1u\n      ^~~"},
      {"t\n.tran 1u 1m 2m\n",
       "t.cir:2:10: error: '.tran' stop time must be greater than the start time\n.tran 1u 1m 2m\n         ^~"},
      {"t\n.tran 1u 0\n", "t.cir:2:10: error: '.tran' stop time must be positive\n.tran 1u 0\n         ^"},
      {"t\n.tran 1u 1m -1\n", "t.cir:2:13: error: '.tran' start time must not be negative\n.tran 1u 1m -1\n            ^~"},
      {"t\n.tran 1u 1m 0 -1\n",
       "t.cir:2:15: error: '.tran' maximum step must not be negative\n.tran 1u 1m 0 -1\n              ^~"},
      {"t\n.tran 1u 1m 0 1n 5\n", "t.cir:2:18: error: unexpected extra token '5'\n.tran 1u 1m 0 1n 5\n                 ^"},
      {"t\n.tran 1u 1m\n.tran 1u 2m\n", "t.cir:3:1: error: duplicate '.tran' card (first at line 2)\n.tran 1u 2m\n^~~~~"},
      {"t\nR1 a 0 1\n.ic v(b)=1\n", "t.cir:3:5: error: unknown node 'b'\n.ic v(b)=1\n    ^~~~"},
      {"t\nR1 a 0 1\n.ic v(0)=1\n", "t.cir:3:7: error: cannot set the initial voltage of ground\n.ic v(0)=1\n      ^"},
      {"t\nR1 a 0 1\n.ic i(a)=1\n", "t.cir:3:5: error: expected 'v(node)=value', got 'i'\n.ic i(a)=1\n    ^"},
      {"t\nR1 a 0 1\n.ic v(a)\n", "t.cir:3:9: error: expected 'v(node)=value' after ')'\n.ic v(a)\n        ^"},
  });
}

TEST(ParseDiagnostics, Probes) {
  check({
      {"t\nR1 a 0 1\n.print tran v(a) x(b)\n",
       "t.cir:3:18: error: invalid probe 'x(b)': expected v(node), v(node1,node2), i(element), ic/ib/ie(transistor) or i2(line)\n"
       ".print tran v(a) x(b)\n                 ^~~~"},
      {"t\nR1 a 0 1\n.save v(a,0,1)\n",
       "t.cir:3:7: error: invalid probe 'v(a,0,1)': expected v(node), v(node1,node2), i(element), ic/ib/ie(transistor) or i2(line)\n"
       ".save v(a,0,1)\n      ^~~~~~~~"},
      {"t\nR1 a 0 1\n.save #r1[i]\n",
       "t.cir:3:7: error: invalid probe '#r1[i]': expected v(node), v(node1,node2), i(element), ic/ib/ie(transistor) or i2(line)\n"
       ".save #r1[i]\n      ^~~~~~"},
      {"t\nR1 a 0 1\n.print tran v(b)\n", "t.cir:3:13: error: unknown node 'b'\n.print tran v(b)\n            ^~~~"},
      {"t\nR1 a 0 1\n.print tran v(a,zz)\n", "t.cir:3:13: error: unknown node 'zz'\n.print tran v(a,zz)\n            ^~~~~~~"},
      {"t\nR1 a 0 1\n.print tran i(r2)\n", "t.cir:3:13: error: unknown element 'r2'\n.print tran i(r2)\n            ^~~~~"},
      {"t\nL1 a 0 1\nL2 a 0 1\nK1 l1 l2 1\n.print tran i(k1)\n",
       "t.cir:5:13: error: 'k1' has no current (it is a coupling)\n.print tran i(k1)\n            ^~~~~"},
      {"t\nR1 a 0 1\n.save v(a\n", "t.cir:3:8: error: missing ')'\n.save v(a\n       ^"},
  });
}

TEST(ParseDiagnostics, LexicalAndIncludes) {
  check({
      {"t\n.include \"x.inc\n", "t.cir:2:10: error: missing closing quote\n.include \"x.inc\n         ^"},
      {"t\n.include nowhere/x.inc\n",
       "t.cir:2:10: error: cannot open include file 'nowhere/x.inc'\n.include nowhere/x.inc\n         ^~~~~~~~~~~~~"},
      {"t\n.control\nrun\n", "t.cir:2:1: error: missing '.endc' for '.control'\n.control\n^~~~~~~~"},
      {"t\nR1 a\tb {x}\n", "t.cir:2:9: error: undefined parameter 'x'\nR1 a\tb {x}\n    \t   ^"},
  });
}

TEST(ParseDiagnostics, TabsKeepTheCaretAligned) {
  // format_diagnostic keeps tabs in the padding; the column counts characters.
  EXPECT_EQ(diag("t\n\tR1\ta\tb\t{x}\n"), "t.cir:2:10: error: undefined parameter 'x'\n\tR1\ta\tb\t{x}\n\t  \t \t \t ^");
}

}  // namespace
}  // namespace lcs
