// Barriers recorded outside the graph's plan: a pass between its own dispatches (the graph orders
// passes; a pass with several dependent dispatches orders them itself), image uploads and
// read-backs, the inspector's swapchain images.
#pragma once
#include <vulkan/vulkan_raii.hpp>

namespace fovea::gpu {

// One global memory barrier (synchronization2).
void memoryBarrier(const vk::raii::CommandBuffer& cmd, vk::PipelineStageFlags2 srcStage,
                   vk::AccessFlags2 srcAccess, vk::PipelineStageFlags2 dstStage,
                   vk::AccessFlags2 dstAccess);

// Storage reads and writes of earlier dispatches complete and are visible before the next
// dispatch reads (as storage or through a sampler) or writes (ping-pong levels, producer/consumer
// kernels of one pass).
void computeToComputeBarrier(const vk::raii::CommandBuffer& cmd);

// A dispatch wrote indirect arguments (and storage data) that the next dispatch consumes, either
// as its indirect command or as storage.
void computeToIndirectBarrier(const vk::raii::CommandBuffer& cmd);

// A layout transition of a whole single-mip, single-layer colour image, with its dependency.
void imageBarrier(const vk::raii::CommandBuffer& cmd, vk::Image image, vk::ImageLayout from,
                  vk::ImageLayout to, vk::PipelineStageFlags2 srcStage, vk::AccessFlags2 srcAccess,
                  vk::PipelineStageFlags2 dstStage, vk::AccessFlags2 dstAccess);

}  // namespace fovea::gpu
