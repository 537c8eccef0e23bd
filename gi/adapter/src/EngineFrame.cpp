// The GI's frame inputs from the engine's renderer.
#include "gi/adapter/EngineFrame.h"

#include "gi/adapter/LpvConfig.h"

namespace lpv::gi {

GiFrameInputs giFrameInputs(const engine::Renderer& renderer, const engine::CameraMatrices& camera) {
    GiFrameInputs in;
    in.camera = camera;
    in.sceneBounds = renderer.sceneBounds();
    in.punctualLights = renderer.punctualLights();
    in.scene = renderer.scene();
    in.sunDirection = renderer.sun().direction;
    in.sunRadiance = renderer.sun().radiance;
    in.specularAlbedo = renderer.specularAlbedoTexture();
    return in;
}

GiConfigResult updateFromConfig(LightPropagationVolume& lpv, const engine::Config& config,
                                const engine::Renderer& renderer, const engine::CameraMatrices& camera,
                                engine::FrameProfiler* profiler) {
    return lpv.update(lpvSettingsFrom(config), giFrameInputs(renderer, camera), profiler);
}

} // namespace lpv::gi
