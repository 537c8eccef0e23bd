// Barriers only where a hazard is (issue 46): one frame whose commands depend on each other with
// nothing between them, so a missing barrier shows as wrong values read back, and as a hazard that
// synchronization validation reports (TestDevice fails on any message).
#include "RhiScenarios.h"
#include "TestShaders.h"

#include "../support/TestDevice.h"

#include <doctest/doctest.h>

#include <cmath>
#include <vector>

using namespace lpv;
using namespace lpv::test;

TEST_CASE("rhi: a dispatch reads what the previous one wrote; a buffer is updated while read") {
    for (const auto& backend : selectedBackends()) {
        for (const bool conservative : {false, true}) {
            SUBCASE((backend.name + (conservative ? ", conservative barriers" : "")).c_str()) {
                rhi::DeviceConfig base;
                base.conservativeBarriers = conservative;
                TestDevice device(backend, base);
                using namespace rhi;
                const TextureDesc vd{TextureKind::Tex3D,
                                     Format::RGBA16F,
                                     kVolumeSize,
                                     kVolumeSize,
                                     kVolumeSize,
                                     1,
                                     kTextureStorage | kTextureSampled | kTextureTransfer,
                                     "volume",
                                     "test"};
                const TextureHandle first = device->createTexture(vd), second = device->createTexture(vd);
                const uint32_t count = kVolumeSize * kVolumeSize * kVolumeSize;
                const BufferHandle result =
                    device->createBuffer({count * 16ull, kBufferStorage | kBufferTransfer,
                                          MemoryAccess::GpuOnly, "result", "test"});
                const glm::vec4 scale{0.1f, 0.2f, 0.05f, 0.0f}, zero{0.0f};
                const BufferHandle params =
                    device->createBuffer({sizeof(scale), kBufferUniform | kBufferTransfer,
                                          MemoryAccess::GpuOnly, "params", "test"},
                                         &scale);
                const ComputePipelineHandle fill =
                    device->createPipeline(ComputePipelineDesc{&shaders::fill_volume_comp, "fill"});
                const ComputePipelineHandle sample =
                    device->createPipeline(ComputePipelineDesc{&shaders::sample_volume_comp, "sample"});
                const SamplerHandle point = device->createSampler({});

                CommandList& cmd = device->beginFrame();
                cmd.bindPipeline(fill); // writes `first` with `params`
                cmd.bindStorageImage(0, first);
                cmd.bindUniformBuffer(1, params);
                cmd.dispatch(kVolumeSize / 8, kVolumeSize / 8, kVolumeSize);
                cmd.bindPipeline(sample); // reads `first` at once: read after write
                cmd.bindTexture(0, first, point);
                cmd.bindStorageBuffer(1, result);
                cmd.dispatch(count / 64);
                cmd.updateBuffer(params, 0, &zero, sizeof(zero)); // written after the first read it
                cmd.bindPipeline(fill);
                cmd.bindStorageImage(0, second);
                cmd.bindUniformBuffer(1, params);
                cmd.dispatch(kVolumeSize / 8, kVolumeSize / 8, kVolumeSize);
                device->endFrame();
                device->waitIdle();

                std::vector<glm::vec4> got(count);
                device->readBuffer(result, 0, got.data(), count * 16ull);
                const Image zeroed = readImage(*device, second);
                uint32_t bad = 0;
                for (uint32_t z = 0; z < kVolumeSize; ++z)
                    for (uint32_t y = 0; y < kVolumeSize; ++y)
                        for (uint32_t x = 0; x < kVolumeSize; ++x) {
                            const glm::vec4 want = expectedVolumeTexel(x, y, z);
                            const glm::vec4 g = got[x + kVolumeSize * (y + kVolumeSize * z)];
                            const glm::vec4 w0{0.0f, 0.0f, float(int(x + 2 * y) - int(z)) / 64.0f, 1.0f};
                            const glm::vec4 g0 = zeroed.at(x, y, z);
                            for (int c = 0; c < 4; ++c) {
                                if (std::fabs(g[c] - want[c]) > 2e-3f + 1e-3f * std::fabs(want[c])) ++bad;
                                if (std::fabs(g0[c] - w0[c]) > 2e-3f) ++bad;
                            }
                        }
                CHECK(bad == 0);
                device->destroy(fill);
                device->destroy(sample);
                device->destroy(point);
                device->destroy(params);
                device->destroy(result);
                device->destroy(first);
                device->destroy(second);
                device.expectSilent();
            }
        }
    }
}
