// TEMPORARY: replaced by the real Vulkan backend.
#include "../src/BackendFactory.h"
#include "rhi/Error.h"
namespace lpv::rhi {
std::unique_ptr<Device> createVulkanDevice(const DeviceConfig&) { throw BackendUnavailable("vulkan backend not built yet"); }
}
