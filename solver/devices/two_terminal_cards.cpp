#include "solver/devices/two_terminal_cards.h"

namespace lcs {

NgspiceCards two_terminal_cards(const std::string& deck_name, const std::string& plus,
                                const std::string& minus, const std::string& value_text,
                                const std::string& element_name, const NgspiceDeckContext& context) {
  NgspiceCards cards;
  std::string a = plus;
  if (context.current_probed) {
    const std::string meter_name = context.fresh("v_amm_" + element_name);
    const std::string mid = context.fresh("lcs_" + element_name + "_amm");
    cards.lines.push_back(meter_name + " " + a + " " + mid + " DC 0");
    cards.probes["i(" + element_name + ")"] = {meter_name + "#branch", ""};
    a = mid;
  }
  cards.lines.push_back(deck_name + " " + a + " " + minus + " " + value_text);
  return cards;
}

}  // namespace lcs
