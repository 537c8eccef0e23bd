// The render.* settings that choose and configure the graphics device at startup.
#pragma once

#include "engine/config/Config.h"
#include "rhi/Backend.h"

namespace lpv::engine {

// Throws ConfigError for values the RHI cannot use, and for render.allow_fallback=false with
// render.backend=auto (the error names where allow_fallback was set, e.g. "--no-fallback").
rhi::DeviceConfig deviceConfigFrom(const Config& config);

uint32_t renderWidth(const Config& config);
uint32_t renderHeight(const Config& config);

} // namespace lpv::engine
