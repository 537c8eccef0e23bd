// The engine's indirect light for one view (EngineIndirect.h).
#include "EngineIndirect.h"

#include "engine/render/CameraMatrices.h"
#include "engine/render/Renderer.h"
#include "gi/LightPropagationVolume.h"
#include "gi/adapter/EngineFrame.h"
#include "platforms/PlatformProfile.h"

#include <glm/gtc/packing.hpp>

#include <stdexcept>

namespace lpv::bench {

std::vector<glm::vec3> renderEngineIndirect(rhi::Device& device, const engine::Scene& scene,
                                            const engine::Camera& camera, uint32_t width, uint32_t height,
                                            engine::Config config, int frames) {
    config.applyOverride("render.debug_view=indirect", "the fidelity benchmark");
    // The reference has no ambient occlusion term: SSAO would darken corners it already traces.
    config.applyOverride("render.ssao=false", "the fidelity benchmark");
    engine::Renderer renderer(device, width, height);
    renderer.setScene(scene);
    gi::LightPropagationVolume lpv(device, platforms::loadPlatformProfile("pc"));
    lpv.setScene(scene);
    const engine::CameraMatrices m = engine::cameraMatrices(camera, float(width) / float(height));
    for (int f = 0; f < frames; ++f) {
        if (const gi::GiConfigResult r = gi::updateFromConfig(lpv, config, renderer, m); !r)
            throw std::runtime_error(r.message());
        rhi::CommandList& cmd = device.beginFrame();
        renderer.render(cmd, m, config, nullptr, &lpv);
        device.endFrame();
    }
    device.waitIdle();
    std::vector<uint16_t> half(size_t(width) * height * 4);
    device.readTexture(renderer.hdr(), 0, half.data(), half.size() * sizeof(uint16_t));
    std::vector<glm::vec3> out(size_t(width) * height);
    for (size_t i = 0; i < out.size(); ++i)
        out[i] = {glm::unpackHalf1x16(half[4 * i]), glm::unpackHalf1x16(half[4 * i + 1]),
                  glm::unpackHalf1x16(half[4 * i + 2])};
    return out;
}

} // namespace lpv::bench
