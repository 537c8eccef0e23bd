// Entry points of the backends, used only by createDevice(). A backend that is not compiled in
// still has its create function; it throws BackendUnavailable saying so.
#pragma once

#include "rhi/Backend.h"
#include "rhi/Device.h"

#include <memory>

namespace lpv::rhi {

std::unique_ptr<Device> createGlDevice(const DeviceConfig& config);
std::unique_ptr<Device> createVulkanDevice(const DeviceConfig& config);
std::unique_ptr<Device> createNullDevice(const DeviceConfig& config);

} // namespace lpv::rhi
