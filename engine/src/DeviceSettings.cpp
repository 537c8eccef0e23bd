// Device choice from config: backend, GL platform, fallback rule, validation, frame size.
#include "engine/DeviceSettings.h"

namespace lpv::engine {
namespace {

const EnumSetting<rhi::BackendKind> kBackend{"render.backend",
                                             rhi::BackendKind::Auto,
                                             {{rhi::BackendKind::Auto, "auto"},
                                              {rhi::BackendKind::OpenGL, "gl"},
                                              {rhi::BackendKind::Vulkan, "vulkan"},
                                              {rhi::BackendKind::Null, "null"}},
                                             "Graphics backend; auto tries vulkan, then gl",
                                             Apply::Restart};
const EnumSetting<rhi::GlHeadless> kGlPlatform{
    "render.gl_platform",
    rhi::GlHeadless::EglSurfaceless,
    {{rhi::GlHeadless::EglSurfaceless, "egl"}, {rhi::GlHeadless::OSMesa, "osmesa"}},
    "Headless OpenGL context: EGL surfaceless or OSMesa",
    Apply::Restart};
const BoolSetting kAllowFallback{"render.allow_fallback", true,
                                 "Continue on the other backend when the chosen one cannot start",
                                 Apply::Restart};
const BoolSetting kValidation{"render.validation", false,
                              "Vulkan validation layer / GL debug output to the log", Apply::Restart};
const IntSetting kWidth{"render.width", 1280, 16, 8192, "Frame width in pixels", Apply::Restart};
const IntSetting kHeight{"render.height", 720, 16, 8192, "Frame height in pixels", Apply::Restart};

} // namespace

rhi::DeviceConfig deviceConfigFrom(const Config& config) {
    rhi::DeviceConfig d;
    d.backend = config.get(kBackend);
    d.glHeadless = config.get(kGlPlatform);
    d.allowFallback = config.get(kAllowFallback);
    d.validation = config.get(kValidation);
    // "auto" is an order to try (vulkan, then gl), not one backend to stay on: refusing to fall
    // back from it has no meaning, and quietly trying gl anyway would ignore what was asked.
    if (d.backend == rhi::BackendKind::Auto && !d.allowFallback)
        throw ConfigError(config.origin(kAllowFallback.decl()), 0,
                          "render.allow_fallback=false needs a named render.backend (vulkan, gl or null); "
                          "auto tries vulkan, then gl");
    return d;
}

uint32_t renderWidth(const Config& config) {
    return uint32_t(config.get(kWidth));
}
uint32_t renderHeight(const Config& config) {
    return uint32_t(config.get(kHeight));
}

} // namespace lpv::engine
