// VkResult -> a readable rhi::Error. Every Vulkan call that can fail goes through vkCheck(), so an
// error names the call that failed and the result code instead of surfacing as a crash later.
#pragma once

#include "rhi/Error.h"

#include <vulkan/vulkan.h>

#include <string>

namespace lpv::rhi::vk {

const char* resultName(VkResult result);

[[noreturn]] void throwVkError(VkResult result, const char* what);

inline void vkCheck(VkResult result, const char* what) {
    if (result != VK_SUCCESS) throwVkError(result, what);
}

} // namespace lpv::rhi::vk
