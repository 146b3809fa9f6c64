#include "netlist/out_of_scope.h"

#include <algorithm>
#include <cctype>
#include <functional>
#include <set>
#include <utility>
#include <vector>

namespace lcs::parse {
namespace {

const char* const kScope = " are outside lcspice's scope (ideal diodes and bipolar transistors)";

// Element letters whose devices lcspice does not simulate.
const std::pair<char, const char*> kElements[] = {
    {'m', "MOSFETs"},
    {'j', "JFETs"},
    {'z', "MESFETs"},
    {'a', "XSPICE code-model instances ('A' cards)"},
    {'b', "behavioural sources ('B' cards)"},
    {'u', "uniform distributed RC lines ('U' cards)"},
    {'n', "numerical and Verilog-A devices ('N' cards)"},
    {'p', "coupled multiconductor lines ('P' cards)"},
    {'y', "TXL transmission lines ('Y' cards)"},
};

const std::pair<const char*, const char*> kModelTypes[] = {
    {"nmos", "MOSFET"}, {"pmos", "MOSFET"}, {"vdmos", "MOSFET (VDMOS)"},
    {"njf", "JFET"}, {"pjf", "JFET"}, {"nmf", "MESFET"}, {"pmf", "MESFET"},
    {"numd", "CIDER numerical device"}, {"nbjt", "CIDER numerical device"}, {"numos", "CIDER numerical device"},
    {"urc", "uniform distributed RC line"}, {"txl", "TXL transmission line"}, {"cpl", "coupled line"},
    {"r", "semiconductor resistor"}, {"c", "semiconductor capacitor"}, {"l", "inductor model"},
    // XSPICE code models
    {"lcouple", "XSPICE code model"}, {"core", "XSPICE code model"}, {"aswitch", "XSPICE code model"},
    {"gain", "XSPICE code model"}, {"summer", "XSPICE code model"}, {"mult", "XSPICE code model"},
    {"divide", "XSPICE code model"}, {"limit", "XSPICE code model"}, {"climit", "XSPICE code model"},
    {"int", "XSPICE code model"}, {"d_dt", "XSPICE code model"}, {"s_xfer", "XSPICE code model"},
    {"slew", "XSPICE code model"}, {"hyst", "XSPICE code model"}, {"pwl", "XSPICE code model"},
    {"sine", "XSPICE code model"}, {"triangle", "XSPICE code model"}, {"square", "XSPICE code model"},
    {"oneshot", "XSPICE code model"}, {"zener", "XSPICE code model"}, {"ilimit", "XSPICE code model"},
    {"cmeter", "XSPICE code model"}, {"lmeter", "XSPICE code model"}, {"filesource", "XSPICE code model"},
    {"adc_bridge", "XSPICE code model"}, {"dac_bridge", "XSPICE code model"},
};

bool starts_with(const std::string& s, const char* prefix) { return s.rfind(prefix, 0) == 0; }

// Does the expression text call v(...) or i(...) (a node voltage or a branch current)?
bool reads_circuit_quantity(const std::string& lower) {
  for (std::size_t k = 0; k + 1 < lower.size(); ++k) {
    if (lower[k] != 'v' && lower[k] != 'i') continue;
    if (k > 0 && (std::isalnum(static_cast<unsigned char>(lower[k - 1])) || lower[k - 1] == '_')) continue;
    std::size_t j = k + 1;
    while (j < lower.size() && lower[j] == ' ') ++j;
    if (j < lower.size() && lower[j] == '(') return true;
  }
  return false;
}

}  // namespace

std::string unsimulated_model_kind(const std::string& t) {
  for (const auto& [type, kind] : kModelTypes)
    if (t == type) return kind;
  if (starts_with(t, "d_") || starts_with(t, "real_")) return "XSPICE digital code model";
  return "";
}

std::string unsimulated_model_reason(const std::string& t) {
  const std::string kind = unsimulated_model_kind(t);
  std::string plural = kind;
  if (!plural.empty() && plural.back() != ')') plural += "s";
  return plural + " (model type " + to_lower(t) + ")" + kScope;
}

void refuse_out_of_scope(const Card& card) {
  const Token& head = card[0];
  if (!head.is_word() || head.lower.empty()) return;
  for (const auto& [letter, what] : kElements)
    if (head.lower[0] == letter) throw NetlistError(card.at(0), std::string(what) + kScope);
  for (std::size_t i = 1; i < card.size(); ++i) {
    const Token& t = card[i];
    if (t.is_expression() && reads_circuit_quantity(t.lower))
      throw NetlistError(card.at(t), "expressions of node voltages or branch currents (behavioural sources)" +
                                         std::string(kScope));
    if (t.is_word("value") && i + 1 < card.size() && card[i + 1].is(Token::Kind::Equals))
      throw NetlistError(card.at(t), "behavioural sources (VALUE=)" + std::string(kScope));
  }
  // D anode cathode tj model thermal: ngspice's self-heating diode (a third, thermal node).
  if (head.lower[0] == 'd')
    for (std::size_t i = 3; i < card.size(); ++i)
      if (card[i].is_word("thermal"))
        throw NetlistError(card.at(i), "thermal diodes (self-heating, with a thermal node)" + std::string(kScope));
}

void refuse_out_of_scope_elements(const SubcktDef& top) {
  std::set<const SubcktDef*> reached;
  std::vector<const SubcktDef*> todo = {&top};
  std::vector<const Card*> elements;
  while (!todo.empty()) {
    const SubcktDef* def = todo.back();
    todo.pop_back();
    if (!reached.insert(def).second) continue;
    for (const Card* card : def->body) {
      const Token& head = (*card)[0];
      if (!head.is_word() || head.lower[0] == '.') continue;
      if (head.lower[0] != 'x') {
        elements.push_back(card);
        continue;
      }
      // X nodes... NAME [params:] [a=1 ...]: the subcircuit is the last word before the parameters.
      const Token* name = nullptr;
      for (std::size_t i = 1; i < card->size(); ++i) {
        const Token& t = (*card)[i];
        if (t.is_word("params:") || (i + 1 < card->size() && (*card)[i + 1].is(Token::Kind::Equals))) break;
        if (t.is_word()) name = &t;
      }
      if (const SubcktDef* d = name ? def->find(name->lower) : nullptr) todo.push_back(d);
    }
  }
  std::sort(elements.begin(), elements.end(), std::less<const Card*>());  // the deck's cards are one vector
  for (const Card* card : elements) refuse_out_of_scope(*card);
}

}  // namespace lcs::parse
