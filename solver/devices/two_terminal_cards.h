// The ngspice card of a plain two-terminal element (`NAME n+ n- VALUE...`), behind a 0 V ammeter
// between n+ and the element when its current is probed (i(element) is then the ammeter's
// branch current, in the direction of SPEC §3).
#pragma once

#include "solver/devices/device.h"

namespace lcs {

NgspiceCards two_terminal_cards(const std::string& deck_name, const std::string& plus,
                                const std::string& minus, const std::string& value_text,
                                const std::string& element_name, const NgspiceDeckContext& context);

}  // namespace lcs
