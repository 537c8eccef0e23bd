// What LightPropagationVolume::update() says of the settings it was given: taken, or refused with
// the reason and, over the memory budget, the resources the configuration would hold. A refused
// configuration changes nothing: the GI goes on with the one it ran before.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace lpv::gi {

struct GiResource {
    std::string name;
    std::string category; // gi.rsm, gi.vpl, gi.lpv
    uint64_t bytes = 0;
};

struct GiConfigResult {
    bool accepted = true;
    // The gi.* setting refused ("gi.sh_format", "gi.debug_slice"); empty when the configuration as
    // a whole is over the memory budget.
    std::string setting;
    std::string reason; // one sentence naming the values and the limit
    // Over the memory budget: every resource of the refused configuration with its bytes.
    std::vector<GiResource> resources;

    explicit operator bool() const { return accepted; }
    // The reason, then a line per resource: what a log shows.
    std::string message() const;

    static GiConfigResult refused(std::string setting, std::string reason,
                                  std::vector<GiResource> resources = {});
};

} // namespace lpv::gi
