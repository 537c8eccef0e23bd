// Names of VkResult codes for error messages.
#include "VkCheck.h"

namespace lpv::rhi::vk {

const char* resultName(VkResult result) {
    switch (result) {
#define LPV_VK_RESULT(r)                                                                                     \
    case r:                                                                                                  \
        return #r;
        LPV_VK_RESULT(VK_SUCCESS)
        LPV_VK_RESULT(VK_NOT_READY)
        LPV_VK_RESULT(VK_TIMEOUT)
        LPV_VK_RESULT(VK_EVENT_SET)
        LPV_VK_RESULT(VK_EVENT_RESET)
        LPV_VK_RESULT(VK_INCOMPLETE)
        LPV_VK_RESULT(VK_ERROR_OUT_OF_HOST_MEMORY)
        LPV_VK_RESULT(VK_ERROR_OUT_OF_DEVICE_MEMORY)
        LPV_VK_RESULT(VK_ERROR_INITIALIZATION_FAILED)
        LPV_VK_RESULT(VK_ERROR_DEVICE_LOST)
        LPV_VK_RESULT(VK_ERROR_MEMORY_MAP_FAILED)
        LPV_VK_RESULT(VK_ERROR_LAYER_NOT_PRESENT)
        LPV_VK_RESULT(VK_ERROR_EXTENSION_NOT_PRESENT)
        LPV_VK_RESULT(VK_ERROR_FEATURE_NOT_PRESENT)
        LPV_VK_RESULT(VK_ERROR_INCOMPATIBLE_DRIVER)
        LPV_VK_RESULT(VK_ERROR_TOO_MANY_OBJECTS)
        LPV_VK_RESULT(VK_ERROR_FORMAT_NOT_SUPPORTED)
        LPV_VK_RESULT(VK_ERROR_FRAGMENTED_POOL)
        LPV_VK_RESULT(VK_ERROR_UNKNOWN)
        LPV_VK_RESULT(VK_ERROR_OUT_OF_POOL_MEMORY)
        LPV_VK_RESULT(VK_ERROR_INVALID_EXTERNAL_HANDLE)
        LPV_VK_RESULT(VK_ERROR_FRAGMENTATION)
        LPV_VK_RESULT(VK_ERROR_SURFACE_LOST_KHR)
        LPV_VK_RESULT(VK_ERROR_NATIVE_WINDOW_IN_USE_KHR)
        LPV_VK_RESULT(VK_SUBOPTIMAL_KHR)
        LPV_VK_RESULT(VK_ERROR_OUT_OF_DATE_KHR)
        LPV_VK_RESULT(VK_ERROR_VALIDATION_FAILED_EXT)
#undef LPV_VK_RESULT
    default:
        return "VkResult(unknown)";
    }
}

void throwVkError(VkResult result, const char* what) {
    throw Error(std::string("vulkan: ") + what + " failed: " + resultName(result) + " (" +
                std::to_string(int(result)) + ")");
}

} // namespace lpv::rhi::vk
