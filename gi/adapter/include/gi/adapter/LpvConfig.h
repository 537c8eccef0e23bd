// The engine's adapter for the GI's settings: the gi.* keys of a TOML file and --set, read into
// the plain gi::LpvSettings the GI takes. A game with its own settings system fills LpvSettings
// itself and needs none of this.
#pragma once

#include "engine/config/Config.h"
#include "gi/LpvSettings.h"

namespace lpv::gi {

// gi.* as they are, not cross-checked: LightPropagationVolume::update() refuses settings that do
// not hold together (validateLpvSettings) and keeps what it ran before.
LpvSettings lpvSettingsFrom(const engine::Config& config);

// gi.* cross-checked, for a configuration checked before anything runs: throws engine::ConfigError
// naming where the refused setting, and the one it contradicts, came from.
LpvSettings readLpvSettings(const engine::Config& config);

} // namespace lpv::gi
