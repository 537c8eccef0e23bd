// The gi.* settings' cross-checks (gi/LpvSettings.h), read through the engine's adapter
// (gi/adapter/LpvConfig.h): a value valid alone but not with another setting is a ConfigError
// naming where both came from and what was expected.
#include "gi/adapter/LpvConfig.h"

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
                         (path +
                          ":3: 'gi.debug_slice' = 63: outside the volume: gi.grid_size is 16, so expected 0 "
                          "to 15 (gi.grid_size: " +
                          path + ":2)")
                             .c_str(),
                         engine::ConfigError);
    config.applyOverride("gi.debug_slice=15");
    CHECK(gi::readLpvSettings(config).debugSlice == 15);
    // The default slice (16) is not the user's choice: a 16-cell grid shows its last slice instead.
    engine::Config defaults;
    defaults.applyOverride("gi.grid_size=16");
    CHECK(!gi::readLpvSettings(defaults).debugSlice);
    std::remove(path.c_str());
}

TEST_CASE("gi settings: gi.cell_size takes a number or auto, from a file and the command line") {
    engine::Config config;
    CHECK(!gi::readLpvSettings(config).cellSizeAuto);
    CHECK(gi::readLpvSettings(config).cellSize == doctest::Approx(0.25f));
    config.loadString("[gi]\ncell_size = \"auto\"\n", "auto.toml");
    CHECK(gi::readLpvSettings(config).cellSizeAuto);
    config.applyOverride("gi.cell_size=0.5");
    CHECK(!gi::readLpvSettings(config).cellSizeAuto);
    CHECK(gi::readLpvSettings(config).cellSize == doctest::Approx(0.5f));
    config.applyOverride("gi.cell_size=auto");
    CHECK(gi::readLpvSettings(config).cellSizeAuto);
    // Any other word, or a number out of range, names what is expected.
    CHECK_THROWS_WITH_AS(config.applyOverride("gi.cell_size=big"),
                         "--set: 'gi.cell_size' = 'big': expected a number in [0.01, 100] or auto",
                         engine::ConfigError);
    CHECK_THROWS_WITH_AS(config.loadString("[gi]\ncell_size = \"big\"\n", "big.toml"),
                         doctest::Contains("big.toml:2"), engine::ConfigError);
    CHECK_THROWS_AS(config.applyOverride("gi.cell_size=0"), engine::ConfigError);
}
