// The ngspice card of a plain two-terminal element (`NAME n+ n- VALUE...`), behind a 0 V ammeter
// between n+ and the element when its current is probed (i(element) is then the ammeter's
// branch current, in the direction of SPEC §3).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "solver/devices/device.h"

namespace lcs {

NgspiceCards two_terminal_cards(const std::string& deck_name, const std::string& plus,
                                const std::string& minus, const std::string& value_text,
                                const std::string& element_name, const NgspiceDeckContext& context);

// Several cards (deck name, value text) in parallel between the same terminals, behind one
// ammeter when the element's current is probed: one element written as a sum of sources.
NgspiceCards parallel_two_terminal_cards(const std::vector<std::pair<std::string, std::string>>& cards,
                                         const std::string& plus, const std::string& minus,
                                         const std::string& element_name, const NgspiceDeckContext& context);

}  // namespace lcs
