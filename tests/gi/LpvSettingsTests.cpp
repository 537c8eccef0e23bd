// The gi.* settings' cross-checks (gi/LpvSettings.h): a value valid alone but not with another
// setting is a ConfigError naming where it came from and what was expected.
#include "gi/LpvSettings.h"

#include <doctest/doctest.h>

#include <cstdio>
#include <fstream>
#include <string>

using namespace lpv;

TEST_CASE("gi settings: a debug slice outside the volume names both settings and the slices there are") {
    const std::string path = "/tmp/lpv_gisettingstest.toml";
    std::ofstream(path) << "[gi]\ngrid_size = 16\ndebug_slice = 63\n";
    engine::Config config;
    config.loadFile(path);
    CHECK_THROWS_WITH_AS(gi::readLpvSettings(config),
                         (path + ":3: 'gi.debug_slice' = 63: outside the volume: gi.grid_size is 16 (" +
                          path + ":2), so expected 0 to 15")
                             .c_str(),
                         engine::ConfigError);
    config.applyOverride("gi.debug_slice=15");
    CHECK(gi::readLpvSettings(config).debugSlice == 15);
    // The default slice (16) is not the user's choice: a 16-cell grid shows its last slice instead.
    engine::Config defaults;
    defaults.applyOverride("gi.grid_size=16");
    CHECK(gi::readLpvSettings(defaults).debugSlice == 16);
    std::remove(path.c_str());
}
