// Instance, debug messenger, surface, physical device selection and logical device creation.
#include "VkContext.h"

#include "VkCheck.h"

#include "platforms/Log.h"
#include "platforms/Window.h"
#include "rhi/Error.h"

// vulkan.h must come first so GLFW declares its Vulkan entry points.
#include <GLFW/glfw3.h>

#include <cstring>
#include <vector>

namespace lpv::rhi::vk {
namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

bool hasInstanceExtension(const std::vector<VkExtensionProperties>& list, const char* name) {
    for (const auto& e : list)
        if (std::strcmp(e.extensionName, name) == 0) return true;
    return false;
}

std::vector<VkExtensionProperties> deviceExtensions(VkPhysicalDevice pd) {
    uint32_t count = 0;
    vkEnumerateDeviceExtensionProperties(pd, nullptr, &count, nullptr);
    std::vector<VkExtensionProperties> list(count);
    vkEnumerateDeviceExtensionProperties(pd, nullptr, &count, list.data());
    return list;
}

std::string versionString(uint32_t v) {
    return std::to_string(VK_API_VERSION_MAJOR(v)) + "." + std::to_string(VK_API_VERSION_MINOR(v)) + "." +
           std::to_string(VK_API_VERSION_PATCH(v));
}

int typeScore(VkPhysicalDeviceType type) {
    switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
        return 4;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
        return 3;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
        return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU:
        return 1;
    default:
        return 0;
    }
}

} // namespace

VulkanContext::VulkanContext(const DeviceConfig& config) {
    try {
        createInstance(config);
        if (config.window) createSurface(config);
        choosePhysicalDevice(config.window != nullptr);
        createDevice(config.window != nullptr);
    } catch (...) {
        release();
        throw;
    }
}

VulkanContext::~VulkanContext() {
    release();
}

void VulkanContext::release() {
    if (device) vkDestroyDevice(device, nullptr);
    device = VK_NULL_HANDLE;
    if (surface) vkDestroySurfaceKHR(instance, surface, nullptr);
    surface = VK_NULL_HANDLE;
    if (messenger) {
        auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance, "vkDestroyDebugUtilsMessengerEXT"));
        if (destroy) destroy(instance, messenger, nullptr);
        messenger = VK_NULL_HANDLE;
    }
    if (instance) vkDestroyInstance(instance, nullptr);
    instance = VK_NULL_HANDLE;
}

VKAPI_ATTR VkBool32 VKAPI_CALL VulkanContext::onMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                        VkDebugUtilsMessageTypeFlagsEXT,
                                                        const VkDebugUtilsMessengerCallbackDataEXT* data,
                                                        void* user) {
    const auto* sink = static_cast<const DebugSink*>(user);
    DebugMessage m;
    m.severity = (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) ? DebugSeverity::Error
                                                                            : DebugSeverity::Warning;
    m.text = data && data->pMessage ? data->pMessage : "(no message)";
    if (sink && sink->forward) {
        sink->forward(m);
    } else {
        const std::string line = "vulkan validation: " + m.text;
        if (m.severity == DebugSeverity::Error)
            log::error(line);
        else
            log::warn(line);
    }
    return VK_FALSE; // never abort the call that triggered the message
}

void VulkanContext::createInstance(const DeviceConfig& config) {
    uint32_t loaderVersion = VK_API_VERSION_1_0;
    if (vkEnumerateInstanceVersion(&loaderVersion) != VK_SUCCESS || loaderVersion < VK_API_VERSION_1_3)
        throw BackendUnavailable("the Vulkan loader supports only " + versionString(loaderVersion) +
                                 "; Vulkan 1.3 is required (update libvulkan1)");

    uint32_t count = 0;
    vkEnumerateInstanceExtensionProperties(nullptr, &count, nullptr);
    std::vector<VkExtensionProperties> available(count);
    vkEnumerateInstanceExtensionProperties(nullptr, &count, available.data());

    std::vector<const char*> extensions;
    debugUtils = hasInstanceExtension(available, VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    if (debugUtils) extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    if (config.validation && !debugUtils)
        throw BackendUnavailable("validation requested but the instance lacks VK_EXT_debug_utils");
    if (config.window) {
        if (!glfwVulkanSupported())
            throw BackendUnavailable("GLFW found no Vulkan loader for window surfaces");
        uint32_t glfwCount = 0;
        const char** glfwExtensions = glfwGetRequiredInstanceExtensions(&glfwCount);
        if (!glfwExtensions) throw BackendUnavailable("GLFW cannot create Vulkan surfaces on this display");
        for (uint32_t i = 0; i < glfwCount; ++i) {
            if (!hasInstanceExtension(available, glfwExtensions[i]))
                throw BackendUnavailable(std::string("instance extension ") + glfwExtensions[i] +
                                         " (needed for the window surface) is missing");
            extensions.push_back(glfwExtensions[i]);
        }
    }

    std::vector<const char*> layers;
    if (config.validation) {
        vkEnumerateInstanceLayerProperties(&count, nullptr);
        std::vector<VkLayerProperties> layerList(count);
        vkEnumerateInstanceLayerProperties(&count, layerList.data());
        bool found = false;
        for (const auto& l : layerList)
            found = found || std::strcmp(l.layerName, kValidationLayer) == 0;
        if (!found)
            throw BackendUnavailable(std::string("validation requested but ") + kValidationLayer +
                                     " is not installed (install the package vulkan-validationlayers)");
        layers.push_back(kValidationLayer);
    }

    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "LPV Engine";
    app.pEngineName = "LPV Engine";
    app.apiVersion = VK_API_VERSION_1_3;

    debugSink_ = std::make_unique<DebugSink>(DebugSink{config.onDebugMessage});
    VkDebugUtilsMessengerCreateInfoEXT messengerInfo{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    messengerInfo.messageSeverity =
        VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    messengerInfo.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                                VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                                VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    messengerInfo.pfnUserCallback = &VulkanContext::onMessage;
    messengerInfo.pUserData = debugSink_.get();

    // Synchronization validation catches missing barriers, the RHI's main responsibility.
    const VkValidationFeatureEnableEXT enables[] = {
        VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT};
    VkValidationFeaturesEXT features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
    features.enabledValidationFeatureCount = 1;
    features.pEnabledValidationFeatures = enables;
    // Chained into instance creation too, so messages from vkCreate/DestroyInstance are forwarded.
    features.pNext = &messengerInfo;

    VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    info.pNext = config.validation ? &features : nullptr;
    info.pApplicationInfo = &app;
    info.enabledExtensionCount = uint32_t(extensions.size());
    info.ppEnabledExtensionNames = extensions.data();
    info.enabledLayerCount = uint32_t(layers.size());
    info.ppEnabledLayerNames = layers.data();
    const VkResult result = vkCreateInstance(&info, nullptr, &instance);
    if (result == VK_ERROR_INCOMPATIBLE_DRIVER)
        throw BackendUnavailable(
            "no Vulkan driver found: vkCreateInstance returned VK_ERROR_INCOMPATIBLE_DRIVER "
            "(check VK_DRIVER_FILES / mesa-vulkan-drivers)");
    if (result != VK_SUCCESS)
        throw BackendUnavailable(std::string("vkCreateInstance failed: ") + resultName(result));

    if (config.validation) {
        auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance, "vkCreateDebugUtilsMessengerEXT"));
        if (!create) throw BackendUnavailable("vkCreateDebugUtilsMessengerEXT is not available");
        const VkResult r = create(instance, &messengerInfo, nullptr, &messenger);
        if (r != VK_SUCCESS)
            throw BackendUnavailable(std::string("vkCreateDebugUtilsMessengerEXT: ") + resultName(r));
    }
    if (debugUtils) {
        setDebugUtilsObjectName = reinterpret_cast<PFN_vkSetDebugUtilsObjectNameEXT>(
            vkGetInstanceProcAddr(instance, "vkSetDebugUtilsObjectNameEXT"));
        cmdBeginDebugUtilsLabel = reinterpret_cast<PFN_vkCmdBeginDebugUtilsLabelEXT>(
            vkGetInstanceProcAddr(instance, "vkCmdBeginDebugUtilsLabelEXT"));
        cmdEndDebugUtilsLabel = reinterpret_cast<PFN_vkCmdEndDebugUtilsLabelEXT>(
            vkGetInstanceProcAddr(instance, "vkCmdEndDebugUtilsLabelEXT"));
    }
}

void VulkanContext::createSurface(const DeviceConfig& config) {
    GLFWwindow* window = config.window->native(platforms::WindowApi::Vulkan);
    const VkResult r = glfwCreateWindowSurface(instance, window, nullptr, &surface);
    if (r != VK_SUCCESS)
        throw BackendUnavailable(std::string("glfwCreateWindowSurface failed: ") + resultName(r));
}

void VulkanContext::choosePhysicalDevice(bool needPresent) {
    uint32_t count = 0;
    VkResult r = vkEnumeratePhysicalDevices(instance, &count, nullptr);
    if (r != VK_SUCCESS && r != VK_INCOMPLETE)
        throw BackendUnavailable(std::string("vkEnumeratePhysicalDevices failed: ") + resultName(r));
    if (count == 0)
        throw BackendUnavailable("no Vulkan driver found: vkEnumeratePhysicalDevices returned 0 devices "
                                 "(check VK_DRIVER_FILES / mesa-vulkan-drivers)");
    std::vector<VkPhysicalDevice> devices(count);
    vkEnumeratePhysicalDevices(instance, &count, devices.data());

    std::string rejected;
    int bestScore = 0;
    for (VkPhysicalDevice pd : devices) {
        VkPhysicalDeviceProperties props;
        vkGetPhysicalDeviceProperties(pd, &props);
        std::string why;
        const auto extensions = deviceExtensions(pd);
        VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
        VkPhysicalDeviceFeatures2 f2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &f13};
        if (props.apiVersion < VK_API_VERSION_1_3) {
            why = "supports Vulkan " + versionString(props.apiVersion) + " only (1.3 required)";
        } else {
            vkGetPhysicalDeviceFeatures2(pd, &f2);
            if (!hasInstanceExtension(extensions, VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME))
                why = "lacks VK_KHR_push_descriptor";
            else if (needPresent && !hasInstanceExtension(extensions, VK_KHR_SWAPCHAIN_EXTENSION_NAME))
                why = "lacks VK_KHR_swapchain";
            else if (!f13.dynamicRendering)
                why = "lacks the dynamicRendering feature";
            else if (!f13.synchronization2)
                why = "lacks the synchronization2 feature";
        }
        uint32_t family = UINT32_MAX;
        if (why.empty()) {
            uint32_t qcount = 0;
            vkGetPhysicalDeviceQueueFamilyProperties(pd, &qcount, nullptr);
            std::vector<VkQueueFamilyProperties> families(qcount);
            vkGetPhysicalDeviceQueueFamilyProperties(pd, &qcount, families.data());
            for (uint32_t i = 0; i < qcount && family == UINT32_MAX; ++i) {
                const VkQueueFlags need = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
                if ((families[i].queueFlags & need) != need) continue;
                if (needPresent) {
                    VkBool32 present = VK_FALSE;
                    vkGetPhysicalDeviceSurfaceSupportKHR(pd, i, surface, &present);
                    if (!present) continue;
                }
                family = i;
                timestampValidBits = families[i].timestampValidBits;
            }
            if (family == UINT32_MAX)
                why = needPresent ? "has no graphics+compute queue that can present to the window"
                                  : "has no graphics+compute queue";
        }
        if (!why.empty()) {
            rejected += std::string(rejected.empty() ? "" : "; ") + props.deviceName + " " + why;
            continue;
        }
        const int score = typeScore(props.deviceType) + 1;
        if (score > bestScore) {
            bestScore = score;
            physical = pd;
            queueFamily = family;
            properties = props;
        }
    }
    if (!physical) throw BackendUnavailable("no usable Vulkan 1.3 device: " + rejected);
    // The family chosen last may not be the winner's; ask again for the winner.
    uint32_t qcount = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(physical, &qcount, nullptr);
    std::vector<VkQueueFamilyProperties> families(qcount);
    vkGetPhysicalDeviceQueueFamilyProperties(physical, &qcount, families.data());
    timestampValidBits = families[queueFamily].timestampValidBits;
    vkGetPhysicalDeviceMemoryProperties(physical, &memoryProperties);

    VkPhysicalDevicePushDescriptorPropertiesKHR push{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PUSH_DESCRIPTOR_PROPERTIES_KHR};
    VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES, &push};
    VkPhysicalDeviceProperties2 props2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &driver};
    vkGetPhysicalDeviceProperties2(physical, &props2);
    maxPushDescriptors = push.maxPushDescriptors;
    driverName = std::string(driver.driverName) + " " + driver.driverInfo;
}

void VulkanContext::createDevice(bool needPresent) {
    // Ask what the device has, then enable the subset the engine's shaders may use.
    VkPhysicalDeviceVulkan13Features has13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    VkPhysicalDeviceVulkan12Features has12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES, &has13};
    VkPhysicalDeviceVulkan11Features has11{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES, &has12};
    VkPhysicalDeviceFeatures2 has{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &has11};
    vkGetPhysicalDeviceFeatures2(physical, &has);

    VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    f13.dynamicRendering = VK_TRUE;
    f13.synchronization2 = VK_TRUE;
    f13.maintenance4 = has13.maintenance4;
    VkPhysicalDeviceVulkan12Features f12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES, &f13};
    f12.shaderFloat16 = has12.shaderFloat16;
    f12.shaderInt8 = has12.shaderInt8;
    f12.scalarBlockLayout = has12.scalarBlockLayout;
    f12.uniformBufferStandardLayout = has12.uniformBufferStandardLayout;
    f12.hostQueryReset = has12.hostQueryReset;
    f12.storageBuffer8BitAccess = has12.storageBuffer8BitAccess;
    f12.shaderOutputLayer = has12.shaderOutputLayer;
    VkPhysicalDeviceVulkan11Features f11{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES, &f12};
    f11.shaderDrawParameters = has11.shaderDrawParameters;
    f11.storageBuffer16BitAccess = has11.storageBuffer16BitAccess;
    VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &f11};
    VkPhysicalDeviceFeatures& f = features.features;
    const VkPhysicalDeviceFeatures& h = has.features;
    f.independentBlend = h.independentBlend;
    f.samplerAnisotropy = h.samplerAnisotropy;
    f.fragmentStoresAndAtomics = h.fragmentStoresAndAtomics;
    f.vertexPipelineStoresAndAtomics = h.vertexPipelineStoresAndAtomics;
    f.shaderStorageImageExtendedFormats = h.shaderStorageImageExtendedFormats;
    f.shaderStorageImageWriteWithoutFormat = h.shaderStorageImageWriteWithoutFormat;
    f.shaderStorageImageReadWithoutFormat = h.shaderStorageImageReadWithoutFormat;
    f.multiDrawIndirect = h.multiDrawIndirect;
    f.drawIndirectFirstInstance = h.drawIndirectFirstInstance;
    f.depthClamp = h.depthClamp;
    f.depthBiasClamp = h.depthBiasClamp;
    f.fillModeNonSolid = h.fillModeNonSolid;
    f.largePoints = h.largePoints;
    f.shaderInt16 = h.shaderInt16;
    f.imageCubeArray = h.imageCubeArray;
    samplerAnisotropy = h.samplerAnisotropy;
    multiDrawIndirect = h.multiDrawIndirect && h.drawIndirectFirstInstance;
    fragmentStores = h.fragmentStoresAndAtomics;
    shaderOutputLayer = has12.shaderOutputLayer;

    const float priority = 1.0f;
    VkDeviceQueueCreateInfo queueInfo{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    queueInfo.queueFamilyIndex = queueFamily;
    queueInfo.queueCount = 1;
    queueInfo.pQueuePriorities = &priority;

    std::vector<const char*> extensions{VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME};
    if (needPresent) extensions.push_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);
    shaderStencilExport =
        hasInstanceExtension(deviceExtensions(physical), VK_EXT_SHADER_STENCIL_EXPORT_EXTENSION_NAME);
    if (shaderStencilExport) extensions.push_back(VK_EXT_SHADER_STENCIL_EXPORT_EXTENSION_NAME);
    // VK_KHR_unified_image_layouts, spelled out: Debian 12's headers predate it (extension 528).
    struct UnifiedImageLayoutsFeatures {
        VkStructureType sType = VkStructureType(1000527000);
        void* pNext = nullptr;
        VkBool32 unifiedImageLayouts = VK_FALSE;
        VkBool32 unifiedImageLayoutsVideo = VK_FALSE;
    } unified;
    if (hasInstanceExtension(deviceExtensions(physical), "VK_KHR_unified_image_layouts")) {
        VkPhysicalDeviceFeatures2 query{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &unified};
        vkGetPhysicalDeviceFeatures2(physical, &query);
        if (unified.unifiedImageLayouts) {
            unified.unifiedImageLayoutsVideo = VK_FALSE;
            unified.pNext = f13.pNext;
            f13.pNext = &unified;
            extensions.push_back("VK_KHR_unified_image_layouts");
        }
    }
    unifiedImageLayouts = properties.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU || unified.unifiedImageLayouts;

    VkDeviceCreateInfo info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, &features};
    info.queueCreateInfoCount = 1;
    info.pQueueCreateInfos = &queueInfo;
    info.enabledExtensionCount = uint32_t(extensions.size());
    info.ppEnabledExtensionNames = extensions.data();
    const VkResult r = vkCreateDevice(physical, &info, nullptr, &device);
    if (r != VK_SUCCESS) throw BackendUnavailable(std::string("vkCreateDevice failed: ") + resultName(r));
    vkGetDeviceQueue(device, queueFamily, 0, &queue);

    cmdPushDescriptorSet = reinterpret_cast<PFN_vkCmdPushDescriptorSetKHR>(
        vkGetDeviceProcAddr(device, "vkCmdPushDescriptorSetKHR"));
    if (!cmdPushDescriptorSet) throw BackendUnavailable("vkCmdPushDescriptorSetKHR could not be loaded");
}

void VulkanContext::setName(VkObjectType type, uint64_t handle, const char* name) const {
    if (!setDebugUtilsObjectName || !handle || !name || !*name) return;
    VkDebugUtilsObjectNameInfoEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_OBJECT_NAME_INFO_EXT};
    info.objectType = type;
    info.objectHandle = handle;
    info.pObjectName = name;
    setDebugUtilsObjectName(device, &info);
}

uint32_t VulkanContext::memoryType(uint32_t typeBits, VkMemoryPropertyFlags want,
                                   VkMemoryPropertyFlags fallback) const {
    for (VkMemoryPropertyFlags flags : {want, fallback})
        for (uint32_t i = 0; i < memoryProperties.memoryTypeCount; ++i)
            if ((typeBits & (1u << i)) && (memoryProperties.memoryTypes[i].propertyFlags & flags) == flags)
                return i;
    throw Error("vulkan: no memory type with the required properties (type bits " + std::to_string(typeBits) +
                ")");
}

} // namespace lpv::rhi::vk
