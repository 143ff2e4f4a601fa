// The inspector's window: a GLFW window presenting through a Vulkan swapchain on the device the
// graph runs on. One frame in flight (the graph itself waits for every frame), a render pass that
// LOADs the swapchain image so the preview copied into it first stays under the ImGui windows,
// and a read-back of the whole swapchain image for --screenshot.
#pragma once
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>
#include <vulkan/vulkan_raii.hpp>

#include "core/image/ImageIO.h"

struct GLFWwindow;

namespace fovea::gpu {
class Context;
class Buffer;
}  // namespace fovea::gpu

namespace fovea::editor {

// glfwInit/glfwTerminate. Throws RuntimeError naming the cause (no DISPLAY, no Vulkan loader
// support) when no window can be opened: `fovea inspect` exits 1 with that message.
class WindowSystem {
public:
    WindowSystem();
    ~WindowSystem();
    WindowSystem(const WindowSystem&) = delete;
    WindowSystem& operator=(const WindowSystem&) = delete;
    // The instance extensions the platform's surface needs (VK_KHR_surface + xcb/xlib/wayland).
    std::vector<std::string> requiredInstanceExtensions() const;
};

// Pixels to copy into a rectangle of the swapchain image before the UI is drawn.
struct PreviewBlit {
    int x = 0, y = 0;
    uint32_t width = 0, height = 0;
    std::vector<uint8_t> bytes;  // width*height*4, in the swapchain's channel order (see bgra())
};

class VulkanWindow {
public:
    VulkanWindow(gpu::Context& ctx, uint32_t width, uint32_t height, const std::string& title);
    ~VulkanWindow();
    VulkanWindow(const VulkanWindow&) = delete;
    VulkanWindow& operator=(const VulkanWindow&) = delete;

    GLFWwindow* handle() const { return mWindow; }
    bool shouldClose() const;
    vk::RenderPass renderPass() const { return *mRenderPass; }
    vk::DescriptorPool descriptorPool() const { return *mDescriptorPool; }
    uint32_t imageCount() const { return uint32_t(mImages.size()); }
    uint32_t minImageCount() const { return mMinImageCount; }
    vk::Extent2D extent() const { return mExtent; }
    bool bgra() const { return mFormat == vk::Format::eB8G8R8A8Unorm; }
    // Bytes of the host-visible preview staging and screenshot read-back buffers.
    uint64_t bufferBytes() const;

    // Records the UI into the render pass with `recordUi`, copies `preview` (if any) under it,
    // reads the whole image back into `screenshot` (if non-null), presents and waits. Returns
    // false when the frame was skipped (swapchain out of date: recreated for the next frame).
    bool drawFrame(const std::function<void(vk::CommandBuffer)>& recordUi,
                   const PreviewBlit* preview, image::ImageRGBA* screenshot);
    // One-shot recording on the window's queue (font upload).
    void submitOnce(const std::function<void(vk::CommandBuffer)>& record);

private:
    void createSwapchain();
    void recordFrame(const vk::raii::CommandBuffer& cmd, uint32_t index,
                     const std::function<void(vk::CommandBuffer)>& recordUi,
                     const PreviewBlit* preview, bool readback);

    gpu::Context& mCtx;
    GLFWwindow* mWindow = nullptr;
    vk::raii::SurfaceKHR mSurface = nullptr;
    vk::Format mFormat = vk::Format::eUndefined;
    vk::raii::RenderPass mRenderPass = nullptr;
    vk::raii::DescriptorPool mDescriptorPool = nullptr;
    vk::raii::SwapchainKHR mSwapchain = nullptr;
    vk::Extent2D mExtent;
    uint32_t mMinImageCount = 2;
    std::vector<vk::Image> mImages;
    std::vector<vk::raii::ImageView> mViews;
    std::vector<vk::raii::Framebuffer> mFramebuffers;
    std::vector<vk::raii::Semaphore> mRenderDone;  // per swapchain image
    vk::raii::Semaphore mImageReady = nullptr;
    vk::raii::Fence mFence = nullptr;
    vk::raii::CommandPool mPool = nullptr;
    vk::raii::CommandBuffer mCmd = nullptr;
    std::unique_ptr<gpu::Buffer> mStaging;   // preview pixels
    std::unique_ptr<gpu::Buffer> mReadback;  // screenshot
};

}  // namespace fovea::editor
