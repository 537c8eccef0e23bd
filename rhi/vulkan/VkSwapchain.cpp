// Swapchain creation, acquire, present and recreation.
#include "VkSwapchain.h"

#include "VkCheck.h"

#include "platforms/Log.h"
#include "platforms/Window.h"

#include <algorithm>
#include <string>

namespace lpv::rhi::vk {
namespace {

// Allocation-record keys of swapchain images: generation 0 is never a real handle, so these
// cannot collide with textures.
constexpr uint32_t kSwapchainRecordBase = 0x100;

} // namespace

Swapchain::Swapchain(const VulkanContext& ctx, platforms::Window& window, AllocationRecord& record)
    : ctx_(ctx), window_(window), record_(record) {
    create();
}

Swapchain::~Swapchain() {
    releaseImages();
    if (swapchain_) vkDestroySwapchainKHR(ctx_.device, swapchain_, nullptr);
}

void Swapchain::releaseImages() {
    for (VkSemaphore s : renderFinished_)
        vkDestroySemaphore(ctx_.device, s, nullptr);
    renderFinished_.clear();
    for (uint32_t i = 0; i < images_.size(); ++i)
        record_.remove(ResourceType::Texture, kSwapchainRecordBase + i);
    images_.clear();
}

void Swapchain::create() {
    VkSurfaceCapabilitiesKHR caps;
    vkCheck(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(ctx_.physical, ctx_.surface, &caps),
            "vkGetPhysicalDeviceSurfaceCapabilitiesKHR");
    VkExtent2D extent = caps.currentExtent;
    if (extent.width == UINT32_MAX) {
        uint32_t w = 0, h = 0;
        window_.framebufferSize(w, h);
        extent.width = std::clamp(w, caps.minImageExtent.width, caps.maxImageExtent.width);
        extent.height = std::clamp(h, caps.minImageExtent.height, caps.maxImageExtent.height);
    }
    if (!(caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_DST_BIT))
        throw Error("vulkan: the window surface does not accept transfers (VK_IMAGE_USAGE_TRANSFER_DST_BIT)");

    uint32_t count = 0;
    vkGetPhysicalDeviceSurfaceFormatsKHR(ctx_.physical, ctx_.surface, &count, nullptr);
    std::vector<VkSurfaceFormatKHR> formats(count);
    vkGetPhysicalDeviceSurfaceFormatsKHR(ctx_.physical, ctx_.surface, &count, formats.data());
    if (formats.empty()) throw Error("vulkan: the window surface reports no formats");
    // An sRGB swapchain: the frame presented is an sRGB texture, and a blit between two sRGB
    // images keeps its stored values, which is what the GL backend's raw copy shows too. A UNORM
    // swapchain would receive the decoded (linear) values and show the frame too dark.
    VkSurfaceFormatKHR chosen = formats[0];
    bool found = false;
    for (VkFormat wanted : {VK_FORMAT_B8G8R8A8_SRGB, VK_FORMAT_R8G8B8A8_SRGB, VK_FORMAT_B8G8R8A8_UNORM,
                            VK_FORMAT_R8G8B8A8_UNORM})
        for (const auto& f : formats)
            if (!found && f.format == wanted && f.colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR) {
                chosen = f;
                found = true;
            }

    extent_ = extent;
    if (extent.width == 0 || extent.height == 0) return; // minimised: try again at the next frame

    uint32_t imageCount = std::max(caps.minImageCount + 1, 2u);
    if (caps.maxImageCount) imageCount = std::min(imageCount, caps.maxImageCount);

    VkSwapchainCreateInfoKHR info{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
    info.surface = ctx_.surface;
    info.minImageCount = imageCount;
    info.imageFormat = chosen.format;
    info.imageColorSpace = chosen.colorSpace;
    info.imageExtent = extent;
    info.imageArrayLayers = 1;
    info.imageUsage = VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    info.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
    info.preTransform = caps.currentTransform;
    info.compositeAlpha =
        (caps.supportedCompositeAlpha & VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR)
            ? VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR
            : VkCompositeAlphaFlagBitsKHR(caps.supportedCompositeAlpha & -caps.supportedCompositeAlpha);
    info.presentMode = VK_PRESENT_MODE_FIFO_KHR; // always supported, and paces the frame loop
    info.clipped = VK_TRUE;
    info.oldSwapchain = swapchain_;
    VkSwapchainKHR created = VK_NULL_HANDLE;
    vkCheck(vkCreateSwapchainKHR(ctx_.device, &info, nullptr, &created), "vkCreateSwapchainKHR");
    if (swapchain_) vkDestroySwapchainKHR(ctx_.device, swapchain_, nullptr);
    swapchain_ = created;
    format_ = chosen.format;
    ctx_.name(VK_OBJECT_TYPE_SWAPCHAIN_KHR, swapchain_, "swapchain");

    vkGetSwapchainImagesKHR(ctx_.device, swapchain_, &count, nullptr);
    images_.resize(count);
    vkGetSwapchainImagesKHR(ctx_.device, swapchain_, &count, images_.data());
    renderFinished_.resize(count);
    for (uint32_t i = 0; i < count; ++i) {
        VkSemaphoreCreateInfo si{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
        vkCheck(vkCreateSemaphore(ctx_.device, &si, nullptr, &renderFinished_[i]), "vkCreateSemaphore");
        ctx_.name(VK_OBJECT_TYPE_SEMAPHORE, renderFinished_[i],
                  "rendered, swapchain image " + std::to_string(i));
        ctx_.name(VK_OBJECT_TYPE_IMAGE, images_[i], "swapchain image " + std::to_string(i));
        record_.add(ResourceType::Texture, kSwapchainRecordBase + i,
                    {ResourceType::Texture, "swapchain image " + std::to_string(i), "rhi.internal",
                     uint64_t(extent.width) * extent.height * 4});
    }
    stale_ = false;
    log::debug("rhi: vulkan swapchain " + std::to_string(extent.width) + "x" + std::to_string(extent.height) +
               ", " + std::to_string(count) + " images, VkFormat " + std::to_string(int(format_)));
}

bool Swapchain::acquire(VkSemaphore acquired, uint32_t& index) {
    if (stale_ || !swapchain_) {
        vkCheck(vkDeviceWaitIdle(ctx_.device), "vkDeviceWaitIdle");
        releaseImages();
        create();
        if (!swapchain_ || images_.empty()) return false;
    }
    const VkResult r =
        vkAcquireNextImageKHR(ctx_.device, swapchain_, UINT64_MAX, acquired, VK_NULL_HANDLE, &index);
    if (r == VK_ERROR_OUT_OF_DATE_KHR) {
        stale_ = true;
        return false;
    }
    // VK_SUBOPTIMAL_KHR still signals the semaphore: present this image, recreate afterwards.
    if (r == VK_SUBOPTIMAL_KHR) {
        stale_ = true;
        return true;
    }
    vkCheck(r, "vkAcquireNextImageKHR");
    return true;
}

void Swapchain::present(uint32_t index) {
    VkPresentInfoKHR info{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
    info.waitSemaphoreCount = 1;
    info.pWaitSemaphores = &renderFinished_[index];
    info.swapchainCount = 1;
    info.pSwapchains = &swapchain_;
    info.pImageIndices = &index;
    const VkResult r = vkQueuePresentKHR(ctx_.queue, &info);
    if (r == VK_ERROR_OUT_OF_DATE_KHR || r == VK_SUBOPTIMAL_KHR) {
        stale_ = true;
        return;
    }
    vkCheck(r, "vkQueuePresentKHR");
}

} // namespace lpv::rhi::vk
