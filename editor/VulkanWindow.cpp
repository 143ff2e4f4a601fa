#include "editor/VulkanWindow.h"

#include "core/vk/Barriers.h"

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include <algorithm>
#include <cstring>

#include "core/util/Error.h"
#include "core/vk/Context.h"
#include "core/vk/Resources.h"

namespace fovea::editor {

namespace {

// The description of GLFW's last error (glfwGetError keeps it per thread: no callback, no global).
std::string glfwError() {
    const char* description = nullptr;
    glfwGetError(&description);
    return description ? description : "unknown GLFW error";
}

}  // namespace

WindowSystem::WindowSystem() {
    if (!glfwInit())
        throw RuntimeError("cannot open a window: " + glfwError() +
                           " (fovea inspect needs a display; without one run it under "
                           "xvfb-run -a, or use fovea run)");
    if (!glfwVulkanSupported()) {
        glfwTerminate();
        throw RuntimeError("cannot open a window: GLFW finds no Vulkan loader");
    }
}

WindowSystem::~WindowSystem() {
    glfwTerminate();
}

std::vector<std::string> WindowSystem::requiredInstanceExtensions() const {
    uint32_t count = 0;
    const char** names = glfwGetRequiredInstanceExtensions(&count);
    if (!names) throw RuntimeError("cannot open a window: " + glfwError());
    return std::vector<std::string>(names, names + count);
}

VulkanWindow::VulkanWindow(gpu::Context& ctx, uint32_t width, uint32_t height,
                           const std::string& title)
    : mCtx(ctx) {
    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
    glfwWindowHint(GLFW_RESIZABLE, GLFW_FALSE);  // screenshots of a known size
    mWindow = glfwCreateWindow(int(width), int(height), title.c_str(), nullptr, nullptr);
    if (!mWindow) throw RuntimeError("cannot create a window: " + glfwError());
    VkSurfaceKHR surface = VK_NULL_HANDLE;
    if (glfwCreateWindowSurface(*ctx.instance(), mWindow, nullptr, &surface) != VK_SUCCESS)
        throw RuntimeError("cannot create a Vulkan surface for the window: " + glfwError());
    mSurface = vk::raii::SurfaceKHR(ctx.instance(), surface);
    if (!ctx.physicalDevice().getSurfaceSupportKHR(ctx.queueFamily(), *mSurface))
        throw RuntimeError("the queue fovea computes on cannot present on '" + ctx.deviceName() +
                           "'");

    // A UNORM format: the preview bytes are copied as they are (already display-encoded), and
    // ImGui's colours are meant for a non-sRGB target.
    auto formats = ctx.physicalDevice().getSurfaceFormatsKHR(*mSurface);
    for (vk::Format f : {vk::Format::eB8G8R8A8Unorm, vk::Format::eR8G8B8A8Unorm})
        for (const auto& sf : formats)
            if (mFormat == vk::Format::eUndefined && sf.format == f &&
                sf.colorSpace == vk::ColorSpaceKHR::eSrgbNonlinear)
                mFormat = f;
    if (mFormat == vk::Format::eUndefined)
        throw RuntimeError("the window surface offers no B8G8R8A8/R8G8B8A8 UNORM format");

    vk::AttachmentDescription color{.format = mFormat,
                                    .samples = vk::SampleCountFlagBits::e1,
                                    .loadOp = vk::AttachmentLoadOp::eLoad,
                                    .storeOp = vk::AttachmentStoreOp::eStore,
                                    .stencilLoadOp = vk::AttachmentLoadOp::eDontCare,
                                    .stencilStoreOp = vk::AttachmentStoreOp::eDontCare,
                                    .initialLayout = vk::ImageLayout::eTransferDstOptimal,
                                    .finalLayout = vk::ImageLayout::eTransferSrcOptimal};
    vk::AttachmentReference ref{.attachment = 0,
                                .layout = vk::ImageLayout::eColorAttachmentOptimal};
    vk::SubpassDescription subpass{.pipelineBindPoint = vk::PipelineBindPoint::eGraphics,
                                   .colorAttachmentCount = 1,
                                   .pColorAttachments = &ref};
    // Clear + preview copy (transfer) before the UI; read-back/present transition after it.
    std::array<vk::SubpassDependency, 2> deps{
        vk::SubpassDependency{.srcSubpass = VK_SUBPASS_EXTERNAL,
                              .dstSubpass = 0,
                              .srcStageMask = vk::PipelineStageFlagBits::eTransfer,
                              .dstStageMask = vk::PipelineStageFlagBits::eColorAttachmentOutput,
                              .srcAccessMask = vk::AccessFlagBits::eTransferWrite,
                              .dstAccessMask = vk::AccessFlagBits::eColorAttachmentRead |
                                               vk::AccessFlagBits::eColorAttachmentWrite},
        vk::SubpassDependency{.srcSubpass = 0,
                              .dstSubpass = VK_SUBPASS_EXTERNAL,
                              .srcStageMask = vk::PipelineStageFlagBits::eColorAttachmentOutput,
                              .dstStageMask = vk::PipelineStageFlagBits::eTransfer,
                              .srcAccessMask = vk::AccessFlagBits::eColorAttachmentWrite,
                              .dstAccessMask = vk::AccessFlagBits::eTransferRead}};
    mRenderPass = vk::raii::RenderPass(
        ctx.device(), vk::RenderPassCreateInfo{.attachmentCount = 1,
                                               .pAttachments = &color,
                                               .subpassCount = 1,
                                               .pSubpasses = &subpass,
                                               .dependencyCount = uint32_t(deps.size()),
                                               .pDependencies = deps.data()});
    // ImGui 1.86 allocates one set (the font texture) from this pool.
    vk::DescriptorPoolSize poolSize{.type = vk::DescriptorType::eCombinedImageSampler,
                                    .descriptorCount = 4};
    mDescriptorPool = vk::raii::DescriptorPool(
        ctx.device(),
        vk::DescriptorPoolCreateInfo{.flags = vk::DescriptorPoolCreateFlagBits::eFreeDescriptorSet,
                                     .maxSets = 4,
                                     .poolSizeCount = 1,
                                     .pPoolSizes = &poolSize});
    mImageReady = vk::raii::Semaphore(ctx.device(), vk::SemaphoreCreateInfo{});
    mFence = vk::raii::Fence(ctx.device(), vk::FenceCreateInfo{});
    mPool = vk::raii::CommandPool(
        ctx.device(),
        vk::CommandPoolCreateInfo{.flags = vk::CommandPoolCreateFlagBits::eResetCommandBuffer,
                                  .queueFamilyIndex = ctx.queueFamily()});
    mCmd = std::move(
        vk::raii::CommandBuffers(
            ctx.device(), vk::CommandBufferAllocateInfo{.commandPool = *mPool,
                                                        .level = vk::CommandBufferLevel::ePrimary,
                                                        .commandBufferCount = 1})
            .front());
    createSwapchain();
}

VulkanWindow::~VulkanWindow() {
    try {
        mCtx.device().waitIdle();
    } catch (const vk::SystemError&) {
        // device lost: nothing left to wait for
    }
    mFramebuffers.clear();
    mViews.clear();
    mSwapchain.clear();
    mSurface.clear();
    if (mWindow) glfwDestroyWindow(mWindow);
}

uint64_t VulkanWindow::bufferBytes() const {
    return (mStaging ? mStaging->size() : 0) + (mReadback ? mReadback->size() : 0);
}

bool VulkanWindow::shouldClose() const {
    return glfwWindowShouldClose(mWindow);
}

void VulkanWindow::createSwapchain() {
    mCtx.device().waitIdle();
    mFramebuffers.clear();
    mViews.clear();
    const auto caps = mCtx.physicalDevice().getSurfaceCapabilitiesKHR(*mSurface);
    const vk::ImageUsageFlags usage = vk::ImageUsageFlagBits::eColorAttachment |
                                      vk::ImageUsageFlagBits::eTransferSrc |
                                      vk::ImageUsageFlagBits::eTransferDst;
    if ((caps.supportedUsageFlags & usage) != usage)
        throw RuntimeError(
            "the window's swapchain cannot be a transfer source/destination "
            "(needed for the preview and --screenshot)");
    int fbWidth = 0, fbHeight = 0;
    glfwGetFramebufferSize(mWindow, &fbWidth, &fbHeight);
    mExtent = caps.currentExtent.width != UINT32_MAX
                  ? caps.currentExtent
                  : vk::Extent2D{uint32_t(std::max(fbWidth, 1)), uint32_t(std::max(fbHeight, 1))};
    mMinImageCount = std::max(2u, caps.minImageCount + 1);
    if (caps.maxImageCount > 0) mMinImageCount = std::min(mMinImageCount, caps.maxImageCount);
    vk::SwapchainKHR old = *mSwapchain;
    vk::raii::SwapchainKHR next(
        mCtx.device(),
        vk::SwapchainCreateInfoKHR{.surface = *mSurface,
                                   .minImageCount = mMinImageCount,
                                   .imageFormat = mFormat,
                                   .imageColorSpace = vk::ColorSpaceKHR::eSrgbNonlinear,
                                   .imageExtent = mExtent,
                                   .imageArrayLayers = 1,
                                   .imageUsage = usage,
                                   .imageSharingMode = vk::SharingMode::eExclusive,
                                   .preTransform = caps.currentTransform,
                                   .compositeAlpha = vk::CompositeAlphaFlagBitsKHR::eOpaque,
                                   .presentMode = vk::PresentModeKHR::eFifo,  // always present
                                   .clipped = VK_TRUE,
                                   .oldSwapchain = old});
    mSwapchain = std::move(next);
    mImages = mSwapchain.getImages();
    mRenderDone.clear();
    for (vk::Image image : mImages) {
        mViews.emplace_back(mCtx.device(),
                            vk::ImageViewCreateInfo{
                                .image = image,
                                .viewType = vk::ImageViewType::e2D,
                                .format = mFormat,
                                .subresourceRange = {vk::ImageAspectFlagBits::eColor, 0, 1, 0, 1}});
        vk::ImageView view = *mViews.back();
        mFramebuffers.emplace_back(mCtx.device(),
                                   vk::FramebufferCreateInfo{.renderPass = *mRenderPass,
                                                             .attachmentCount = 1,
                                                             .pAttachments = &view,
                                                             .width = mExtent.width,
                                                             .height = mExtent.height,
                                                             .layers = 1});
        mRenderDone.emplace_back(mCtx.device(), vk::SemaphoreCreateInfo{});
    }
    const vk::DeviceSize bytes = vk::DeviceSize(mExtent.width) * mExtent.height * 4;
    mReadback = std::make_unique<gpu::Buffer>(mCtx, bytes, vk::BufferUsageFlagBits::eTransferDst,
                                              true, "inspector.screenshot");
}

void VulkanWindow::submitOnce(const std::function<void(vk::CommandBuffer)>& record) {
    mCtx.submitAndWait([&](const vk::raii::CommandBuffer& cmd) { record(*cmd); });
}

void VulkanWindow::recordFrame(const vk::raii::CommandBuffer& cmd, uint32_t index,
                               const std::function<void(vk::CommandBuffer)>& recordUi,
                               const PreviewBlit* preview, bool readback) {
    using Stage = vk::PipelineStageFlagBits2;
    using Access = vk::AccessFlagBits2;
    const vk::Image image = mImages[index];
    // The acquire semaphore is waited at the transfer stage: the clear is the first write.
    gpu::imageBarrier(cmd, image, vk::ImageLayout::eUndefined, vk::ImageLayout::eTransferDstOptimal,
                      Stage::eTransfer, {}, Stage::eTransfer, Access::eTransferWrite);
    vk::ClearColorValue background{std::array<float, 4>{0.06f, 0.06f, 0.07f, 1.0f}};
    vk::ImageSubresourceRange range{vk::ImageAspectFlagBits::eColor, 0, 1, 0, 1};
    cmd.clearColorImage(image, vk::ImageLayout::eTransferDstOptimal, background, range);
    if (preview && preview->width > 0 && preview->height > 0) {
        gpu::imageBarrier(cmd, image, vk::ImageLayout::eTransferDstOptimal,
                          vk::ImageLayout::eTransferDstOptimal, Stage::eTransfer,
                          Access::eTransferWrite, Stage::eTransfer, Access::eTransferWrite);
        vk::BufferImageCopy region{.bufferOffset = 0,
                                   .bufferRowLength = 0,
                                   .bufferImageHeight = 0,
                                   .imageSubresource = {vk::ImageAspectFlagBits::eColor, 0, 0, 1},
                                   .imageOffset = {preview->x, preview->y, 0},
                                   .imageExtent = {preview->width, preview->height, 1}};
        cmd.copyBufferToImage(mStaging->buffer(), image, vk::ImageLayout::eTransferDstOptimal,
                              region);
    }
    vk::RenderPassBeginInfo begin{.renderPass = *mRenderPass,
                                  .framebuffer = *mFramebuffers[index],
                                  .renderArea = {{0, 0}, mExtent}};
    cmd.beginRenderPass(begin, vk::SubpassContents::eInline);
    recordUi(*cmd);
    cmd.endRenderPass();
    if (readback) {
        vk::BufferImageCopy region{.imageSubresource = {vk::ImageAspectFlagBits::eColor, 0, 0, 1},
                                   .imageExtent = {mExtent.width, mExtent.height, 1}};
        cmd.copyImageToBuffer(image, vk::ImageLayout::eTransferSrcOptimal, mReadback->buffer(),
                              region);
        vk::BufferMemoryBarrier2 host{.srcStageMask = Stage::eTransfer,
                                      .srcAccessMask = Access::eTransferWrite,
                                      .dstStageMask = Stage::eHost,
                                      .dstAccessMask = Access::eHostRead,
                                      .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                                      .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                                      .buffer = mReadback->buffer(),
                                      .offset = 0,
                                      .size = VK_WHOLE_SIZE};
        cmd.pipelineBarrier2(
            vk::DependencyInfo{.bufferMemoryBarrierCount = 1, .pBufferMemoryBarriers = &host});
    }
    // Presentation needs no access mask: the present semaphore makes the writes visible.
    gpu::imageBarrier(
        cmd, image, vk::ImageLayout::eTransferSrcOptimal, vk::ImageLayout::ePresentSrcKHR,
        Stage::eTransfer | Stage::eColorAttachmentOutput,
        Access::eTransferRead | Access::eColorAttachmentWrite, Stage::eBottomOfPipe, {});
}

bool VulkanWindow::drawFrame(const std::function<void(vk::CommandBuffer)>& recordUi,
                             const PreviewBlit* preview, image::ImageRGBA* screenshot) {
    uint32_t index = 0;
    try {
        // eSuboptimalKHR still presents; the swapchain is recreated after the frame.
        index = mSwapchain.acquireNextImage(UINT64_MAX, *mImageReady, nullptr).second;
    } catch (const vk::OutOfDateKHRError&) {
        createSwapchain();
        return false;
    }
    if (preview && preview->width > 0) {
        const size_t bytes = preview->bytes.size();
        if (!mStaging || mStaging->size() < bytes)
            mStaging = std::make_unique<gpu::Buffer>(
                mCtx, bytes, vk::BufferUsageFlagBits::eTransferSrc, true, "inspector.preview");
        std::memcpy(mStaging->mapped(), preview->bytes.data(), bytes);
    }
    mCmd.reset();
    mCmd.begin(vk::CommandBufferBeginInfo{.flags = vk::CommandBufferUsageFlagBits::eOneTimeSubmit});
    recordFrame(mCmd, index, recordUi, preview, screenshot != nullptr);
    mCmd.end();
    vk::SemaphoreSubmitInfo wait{.semaphore = *mImageReady,
                                 .stageMask = vk::PipelineStageFlagBits2::eTransfer};
    vk::SemaphoreSubmitInfo signal{.semaphore = *mRenderDone[index],
                                   .stageMask = vk::PipelineStageFlagBits2::eAllCommands};
    vk::CommandBufferSubmitInfo cmdInfo{.commandBuffer = *mCmd};
    mCtx.submit(vk::SubmitInfo2{.waitSemaphoreInfoCount = 1,
                                .pWaitSemaphoreInfos = &wait,
                                .commandBufferInfoCount = 1,
                                .pCommandBufferInfos = &cmdInfo,
                                .signalSemaphoreInfoCount = 1,
                                .pSignalSemaphoreInfos = &signal},
                *mFence);
    vk::SwapchainKHR swapchain = *mSwapchain;
    vk::Semaphore renderDone = *mRenderDone[index];
    bool recreate = false;
    try {
        const vk::Result presented =
            mCtx.queue().presentKHR(vk::PresentInfoKHR{.waitSemaphoreCount = 1,
                                                       .pWaitSemaphores = &renderDone,
                                                       .swapchainCount = 1,
                                                       .pSwapchains = &swapchain,
                                                       .pImageIndices = &index});
        recreate = presented == vk::Result::eSuboptimalKHR;
    } catch (const vk::OutOfDateKHRError&) {
        recreate = true;
    }
    (void)mCtx.device().waitForFences(*mFence, VK_TRUE, UINT64_MAX);
    mCtx.device().resetFences(*mFence);
    if (screenshot) {
        const auto* bytes = static_cast<const uint8_t*>(mReadback->mapped());
        screenshot->width = mExtent.width;
        screenshot->height = mExtent.height;
        screenshot->pixels.resize(size_t(mExtent.width) * mExtent.height * 4);
        const bool swap = bgra();
        for (size_t p = 0; p < size_t(mExtent.width) * mExtent.height; ++p)
            for (int c = 0; c < 4; ++c) {
                const int from = (swap && c != 3) ? 2 - c : c;
                screenshot->pixels[p * 4 + size_t(c)] = float(bytes[p * 4 + size_t(from)]) / 255.0f;
            }
    }
    if (recreate) createSwapchain();
    return true;
}

}  // namespace fovea::editor
