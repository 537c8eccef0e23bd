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
    return d;
}

uint32_t renderWidth(const Config& config) {
    return uint32_t(config.get(kWidth));
}
uint32_t renderHeight(const Config& config) {
    return uint32_t(config.get(kHeight));
}

} // namespace lpv::engine
