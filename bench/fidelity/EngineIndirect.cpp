// The engine's indirect light for one view (EngineIndirect.h).
#include "EngineIndirect.h"

#include "engine/Screenshot.h"
#include "engine/render/CameraMatrices.h"
#include "engine/render/Renderer.h"
#include "gi/LightPropagationVolume.h"
#include "gi/adapter/EngineFrame.h"
#include "platforms/PlatformProfile.h"

#include <stdexcept>

namespace lpv::bench {

std::vector<glm::vec3> renderEngineFrame(rhi::Device& device, const engine::Scene& scene,
                                         const engine::Camera& camera, uint32_t width, uint32_t height,
                                         const engine::Config& config, int frames) {
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
    const std::vector<float> rgba = engine::readHdrFrame(device, renderer);
    std::vector<glm::vec3> out(size_t(width) * height);
    for (size_t i = 0; i < out.size(); ++i)
        out[i] = {rgba[4 * i], rgba[4 * i + 1], rgba[4 * i + 2]};
    return out;
}

std::vector<glm::vec3> renderEngineIndirect(rhi::Device& device, const engine::Scene& scene,
                                            const engine::Camera& camera, uint32_t width, uint32_t height,
                                            engine::Config config, int frames) {
    config.applyOverride("render.debug_view=indirect", "the fidelity benchmark");
    // The reference has no ambient occlusion term: SSAO would darken corners it already traces.
    config.applyOverride("render.ssao=false", "the fidelity benchmark");
    return renderEngineFrame(device, scene, camera, width, height, config, frames);
}

} // namespace lpv::bench
