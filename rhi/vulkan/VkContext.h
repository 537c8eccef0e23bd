// The Vulkan instance, the chosen physical device, the logical device and its one queue: what every
// other part of the backend needs to talk to the driver. Creation fails with BackendUnavailable and
// the concrete reason (no driver, no 1.3 device, missing extension or feature, missing layer).
#pragma once

#include "rhi/Backend.h"

#include <vulkan/vulkan.h>

#include <functional>
#include <memory>
#include <string>

namespace lpv::rhi::vk {

class VulkanContext {
public:
    explicit VulkanContext(const DeviceConfig& config);
    ~VulkanContext();
    VulkanContext(const VulkanContext&) = delete;
    VulkanContext& operator=(const VulkanContext&) = delete;

    // Attaches a debug name to any Vulkan object (no-op without VK_EXT_debug_utils).
    void setName(VkObjectType type, uint64_t handle, const char* name) const;
    template <typename T> void name(VkObjectType type, T handle, const std::string& name) const {
        setName(type, uint64_t(handle), name.c_str());
    }
    // A memory type allowed by `typeBits` with all of `want`, else all of `fallback`; throws if none.
    uint32_t memoryType(uint32_t typeBits, VkMemoryPropertyFlags want, VkMemoryPropertyFlags fallback) const;

    VkInstance instance = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
    VkSurfaceKHR surface = VK_NULL_HANDLE;
    VkPhysicalDevice physical = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    VkQueue queue = VK_NULL_HANDLE;
    uint32_t queueFamily = 0;
    uint32_t timestampValidBits = 0;

    VkPhysicalDeviceProperties properties{};
    VkPhysicalDeviceMemoryProperties memoryProperties{};
    uint32_t maxPushDescriptors = 0;
    std::string driverName;
    bool samplerAnisotropy = false;
    bool shaderOutputLayer = false;   // gl_Layer from the vertex shader
    bool shaderStencilExport = false; // VK_EXT_shader_stencil_export enabled
    bool multiDrawIndirect = false;   // the multiDrawIndirect and drawIndirectFirstInstance features
    bool fragmentStores = false;      // the fragmentStoresAndAtomics feature
    // VK_IMAGE_LAYOUT_GENERAL costs nothing against the other layouts: a CPU device, which has no
    // layouts, or VK_KHR_unified_image_layouts (which guarantees it wherever GENERAL is valid).
    bool unifiedImageLayouts = false;
    bool debugUtils = false;

    PFN_vkCmdPushDescriptorSetKHR cmdPushDescriptorSet = nullptr;
    PFN_vkSetDebugUtilsObjectNameEXT setDebugUtilsObjectName = nullptr;
    PFN_vkCmdBeginDebugUtilsLabelEXT cmdBeginDebugUtilsLabel = nullptr;
    PFN_vkCmdEndDebugUtilsLabelEXT cmdEndDebugUtilsLabel = nullptr;

private:
    struct DebugSink {
        std::function<void(const DebugMessage&)> forward;
    };

    void createInstance(const DeviceConfig& config);
    void createSurface(const DeviceConfig& config);
    void choosePhysicalDevice(bool needPresent);
    void createDevice(bool needPresent);
    void release();
    static VKAPI_ATTR VkBool32 VKAPI_CALL onMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                    VkDebugUtilsMessageTypeFlagsEXT types,
                                                    const VkDebugUtilsMessengerCallbackDataEXT* data,
                                                    void* user);

    // Heap-held so the messenger's user pointer stays valid for the instance's whole life.
    std::unique_ptr<DebugSink> debugSink_;
};

} // namespace lpv::rhi::vk
