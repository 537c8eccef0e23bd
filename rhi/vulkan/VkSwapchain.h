// The window's swapchain: FIFO presentation of images the device blits its `present` texture into.
// Recreated when the window changes size (VK_ERROR_OUT_OF_DATE_KHR / VK_SUBOPTIMAL_KHR).
#pragma once

#include "VkContext.h"

#include "rhi/AllocationRecord.h"

#include <vector>

namespace lpv::platforms {
class Window;
}

namespace lpv::rhi::vk {

class Swapchain {
public:
    Swapchain(const VulkanContext& ctx, platforms::Window& window, AllocationRecord& record);
    ~Swapchain();
    Swapchain(const Swapchain&) = delete;
    Swapchain& operator=(const Swapchain&) = delete;

    // Acquires the next image, signalling `acquired`. False (nothing signalled) when the window is
    // minimised or the swapchain had to be recreated; the frame then is not presented.
    bool acquire(VkSemaphore acquired, uint32_t& index);
    // Presents image `index` once `rendered` is signalled; recreates the swapchain when needed.
    void present(uint32_t index);

    VkImage image(uint32_t index) const { return images_[index]; }
    // Signalled by the frame's submit, waited on by the present of that image. One per image, not
    // per frame slot: a present may still hold its semaphore when the slot comes round again.
    VkSemaphore renderFinished(uint32_t index) const { return renderFinished_[index]; }
    VkExtent2D extent() const { return extent_; }

private:
    void create();
    void releaseImages();

    const VulkanContext& ctx_;
    platforms::Window& window_;
    AllocationRecord& record_;
    VkSwapchainKHR swapchain_ = VK_NULL_HANDLE;
    VkFormat format_ = VK_FORMAT_UNDEFINED;
    VkExtent2D extent_{0, 0};
    std::vector<VkImage> images_;
    std::vector<VkSemaphore> renderFinished_;
    bool stale_ = false;
};

} // namespace lpv::rhi::vk
