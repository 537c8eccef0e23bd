// The GPU copy of specularAlbedoTable() (SpecularAlbedo.h), laid out as shaders/specular_albedo.glsl
// samples it: RGBA16F, kSize texels wide and two blocks of kSize rows tall. Made once by the
// renderer (its lighting pass, the GI's lookup and RSMs read it), or by whoever draws one of those
// passes without a renderer (a test of an RSM).
#pragma once

#include "rhi/Device.h"

namespace lpv::engine {

class SpecularAlbedoTexture {
public:
    explicit SpecularAlbedoTexture(rhi::Device& device);
    ~SpecularAlbedoTexture();
    SpecularAlbedoTexture(const SpecularAlbedoTexture&) = delete;
    SpecularAlbedoTexture& operator=(const SpecularAlbedoTexture&) = delete;

    rhi::TextureHandle texture() const { return texture_; }

private:
    rhi::Device& device_;
    rhi::TextureHandle texture_;
};

} // namespace lpv::engine
