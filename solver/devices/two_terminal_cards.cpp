#include "solver/devices/two_terminal_cards.h"

namespace lcs {

NgspiceCards parallel_two_terminal_cards(const std::vector<std::pair<std::string, std::string>>& cards,
                                         const std::string& plus, const std::string& minus,
                                         const std::string& element_name, const NgspiceDeckContext& context) {
  NgspiceCards out;
  std::string a = plus;
  if (context.current_probed) {
    const std::string meter_name = context.fresh("v_amm_" + element_name);
    const std::string mid = context.fresh("lcs_" + element_name + "_amm");
    out.lines.push_back(meter_name + " " + a + " " + mid + " DC 0");
    out.probes["i(" + element_name + ")"] = {meter_name + "#branch", ""};
    a = mid;
  }
  for (const auto& [deck_name, value_text] : cards) out.lines.push_back(deck_name + " " + a + " " + minus + " " + value_text);
  return out;
}

NgspiceCards two_terminal_cards(const std::string& deck_name, const std::string& plus,
                                const std::string& minus, const std::string& value_text,
                                const std::string& element_name, const NgspiceDeckContext& context) {
  return parallel_two_terminal_cards({{deck_name, value_text}}, plus, minus, element_name, context);
}

}  // namespace lcs
