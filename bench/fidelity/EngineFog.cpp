// The engine's fog for one view (EngineFog.h).
#include "EngineFog.h"

#include "EngineIndirect.h"

#include <cstdio>

namespace lpv::bench {

namespace {

std::string number(float v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.9g", double(v));
    return buf;
}

} // namespace

std::vector<std::string> fogAssignments(const reference::Medium& medium) {
    return {"fog.enabled=true",
            "fog.density=" + number(medium.density),
            "fog.albedo=" + number(medium.albedo.r) + "," + number(medium.albedo.g) + "," +
                number(medium.albedo.b),
            "fog.height_falloff=" + number(medium.heightFalloff),
            "fog.base_height=" + number(medium.baseHeight),
            "fog.anisotropy=" + number(medium.anisotropy)};
}

std::vector<glm::vec3> renderEngineFog(rhi::Device& device, const engine::Scene& scene,
                                       const engine::Camera& camera, uint32_t width, uint32_t height,
                                       engine::Config config, const reference::Medium& medium, int frames) {
    for (const std::string& s : fogAssignments(medium))
        config.applyOverride(s, "the fidelity benchmark's medium");
    config.applyOverride("render.debug_view=fog", "the fidelity benchmark");
    // Every pixel marched: the comparison is of the march, not of the depth-aware upsampling.
    config.applyOverride("fog.resolution=full", "the fidelity benchmark");
    return renderEngineFrame(device, scene, camera, width, height, config, frames);
}

EngineFogParts renderEngineFogParts(rhi::Device& device, const engine::Scene& scene,
                                    const engine::Camera& camera, uint32_t width, uint32_t height,
                                    const engine::Config& config, const reference::Medium& medium,
                                    int frames) {
    EngineFogParts parts;
    parts.total = renderEngineFog(device, scene, camera, width, height, config, medium, frames);
    engine::Config sunOnly = config;
    sunOnly.applyOverride("gi.enabled=false", "the fidelity benchmark's sun-only fog");
    parts.sun = renderEngineFog(device, scene, camera, width, height, sunOnly, medium, frames);
    parts.indirect.resize(parts.total.size());
    for (size_t i = 0; i < parts.total.size(); ++i)
        parts.indirect[i] = parts.total[i] - parts.sun[i];
    return parts;
}

} // namespace lpv::bench
