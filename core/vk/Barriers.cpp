#include "core/vk/Barriers.h"

namespace fovea::gpu {

void memoryBarrier(const vk::raii::CommandBuffer& cmd, vk::PipelineStageFlags2 srcStage,
                   vk::AccessFlags2 srcAccess, vk::PipelineStageFlags2 dstStage,
                   vk::AccessFlags2 dstAccess) {
    vk::MemoryBarrier2 barrier{.srcStageMask = srcStage,
                               .srcAccessMask = srcAccess,
                               .dstStageMask = dstStage,
                               .dstAccessMask = dstAccess};
    cmd.pipelineBarrier2(vk::DependencyInfo{.memoryBarrierCount = 1, .pMemoryBarriers = &barrier});
}

void computeToComputeBarrier(const vk::raii::CommandBuffer& cmd) {
    constexpr auto kStorage =
        vk::AccessFlagBits2::eShaderStorageRead | vk::AccessFlagBits2::eShaderStorageWrite;
    // Sampled reads too: a later dispatch may read through a sampler what an earlier one stored.
    memoryBarrier(cmd, vk::PipelineStageFlagBits2::eComputeShader, kStorage,
                  vk::PipelineStageFlagBits2::eComputeShader,
                  kStorage | vk::AccessFlagBits2::eShaderSampledRead);
}

void computeToIndirectBarrier(const vk::raii::CommandBuffer& cmd) {
    constexpr auto kStorage =
        vk::AccessFlagBits2::eShaderStorageRead | vk::AccessFlagBits2::eShaderStorageWrite;
    memoryBarrier(
        cmd, vk::PipelineStageFlagBits2::eComputeShader | vk::PipelineStageFlagBits2::eDrawIndirect,
        kStorage | vk::AccessFlagBits2::eIndirectCommandRead,
        vk::PipelineStageFlagBits2::eDrawIndirect | vk::PipelineStageFlagBits2::eComputeShader,
        kStorage | vk::AccessFlagBits2::eIndirectCommandRead);
}

void imageBarrier(const vk::raii::CommandBuffer& cmd, vk::Image image, vk::ImageLayout from,
                  vk::ImageLayout to, vk::PipelineStageFlags2 srcStage, vk::AccessFlags2 srcAccess,
                  vk::PipelineStageFlags2 dstStage, vk::AccessFlags2 dstAccess) {
    vk::ImageMemoryBarrier2 barrier{
        .srcStageMask = srcStage,
        .srcAccessMask = srcAccess,
        .dstStageMask = dstStage,
        .dstAccessMask = dstAccess,
        .oldLayout = from,
        .newLayout = to,
        .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
        .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
        .image = image,
        .subresourceRange = {vk::ImageAspectFlagBits::eColor, 0, 1, 0, 1}};
    cmd.pipelineBarrier2(
        vk::DependencyInfo{.imageMemoryBarrierCount = 1, .pImageMemoryBarriers = &barrier});
}

}  // namespace fovea::gpu
