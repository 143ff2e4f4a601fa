// GPU memory objects: Buffer, Image (2D, one mip, one layer) and the MemoryBlock that aliased
// images share. Layout convention: every image fovea touches lives in VK_IMAGE_LAYOUT_GENERAL;
// the only other layout is UNDEFINED, before an aliased image's first transition.
#pragma once
#include <array>
#include <cstddef>
#include <cstring>
#include <memory>
#include <string>
#include <vector>
#include <vulkan/vulkan_raii.hpp>

namespace fovea::gpu {

class Context;

// One VkDeviceMemory shared by aliased images (the graph compiler decides the aliasing).
class MemoryBlock {
public:
    // Throws RuntimeError when no memory type in memoryTypeBits has `props`, or allocation fails.
    // `what` names the block's users in errors (e.g. the images of an alias group).
    MemoryBlock(const Context& context, vk::DeviceSize size, uint32_t memoryTypeBits,
                vk::MemoryPropertyFlags props = vk::MemoryPropertyFlagBits::eDeviceLocal,
                const std::string& what = "an aliased memory block");
    const vk::raii::DeviceMemory& memory() const { return mMemory; }
    vk::DeviceSize size() const { return mSize; }
    uint32_t memoryType() const { return mMemoryType; }

private:
    vk::raii::DeviceMemory mMemory = nullptr;
    vk::DeviceSize mSize = 0;
    uint32_t mMemoryType = 0;
};

struct ImageDesc {
    uint32_t width = 1, height = 1;
    vk::Format format = vk::Format::eR32G32B32A32Sfloat;
    vk::ImageUsageFlags usage =
        vk::ImageUsageFlagBits::eStorage | vk::ImageUsageFlagBits::eSampled |
        vk::ImageUsageFlagBits::eTransferSrc | vk::ImageUsageFlagBits::eTransferDst;
    std::string debugName;
};

class Image {
public:
    // Owns a dedicated allocation; the image is in GENERAL layout and cleared to zero on return
    // (one submitAndWait). Throws RuntimeError when the format cannot be used with desc.usage.
    Image(const Context& context, const ImageDesc& desc);
    // Aliased: bound to `block` at `offset`; records nothing, so the layout is UNDEFINED until
    // the caller transitions it (e.g. recordTransition). Throws RuntimeError when the block's
    // memory type, size or the offset's alignment does not fit.
    Image(const Context& context, const ImageDesc& desc, std::shared_ptr<MemoryBlock> block,
          vk::DeviceSize offset);

    // Without creating an image (vkGetDeviceImageMemoryRequirements).
    static vk::MemoryRequirements memoryRequirements(const Context& context, const ImageDesc& desc);

    vk::Image image() const { return *mImage; }
    vk::ImageView view() const { return *mView; }
    const ImageDesc& desc() const { return mDesc; }
    uint32_t width() const { return mDesc.width; }
    uint32_t height() const { return mDesc.height; }
    vk::Format format() const { return mDesc.format; }
    vk::DeviceSize allocationSize() const { return mAllocationSize; }
    bool aliased() const { return mBlock != nullptr; }
    // width * height * bytes per pixel: what upload() expects and download() returns.
    size_t byteSize() const;

    // Host transfers: each is one submitAndWait. The image must be in GENERAL and stays there;
    // full barriers on both sides order the copy after and before any other GPU work.
    void upload(const Context& context, const void* data, size_t bytes);
    std::vector<std::byte> download(const Context& context) const;
    // Any fovea format as 4 floats per pixel: missing channels 0, missing alpha 1, unorm /255,
    // half -> float, uint as its float value.
    std::vector<float> downloadRGBA32F(const Context& context) const;
    // Inverse of downloadRGBA32F (extra channels dropped, unorm clamped and rounded). Throws
    // RuntimeError unless rgba.size() == width * height * 4.
    void uploadRGBA32F(const Context& context, const std::vector<float>& rgba);

    // vkCmdClearColorImage in GENERAL (uint formats get the values converted to uint). Records
    // no barriers: it is a CLEAR-stage TRANSFER_WRITE the caller must order.
    void recordClear(const vk::raii::CommandBuffer& cmd, std::array<float, 4> value) const;
    // Layout transition with a full memory barrier (all commands, all memory access) on both
    // sides; from = eUndefined discards the contents (first use of an aliased image).
    void recordTransition(const vk::raii::CommandBuffer& cmd, vk::ImageLayout from,
                          vk::ImageLayout to) const;

private:
    void create(const Context& context);

    ImageDesc mDesc;
    // Declared first so it outlives the image bound to it.
    std::shared_ptr<MemoryBlock> mBlock;
    vk::raii::DeviceMemory mMemory = nullptr;  // only for dedicated allocations
    vk::raii::Image mImage = nullptr;
    vk::raii::ImageView mView = nullptr;
    vk::DeviceSize mAllocationSize = 0;
};

class Buffer {
public:
    // hostVisible buffers live in HOST_VISIBLE|HOST_COHERENT memory and stay mapped (mapped());
    // others are DEVICE_LOCAL and go through a staging buffer. eShaderDeviceAddress usage gets
    // a device-address allocation. Throws RuntimeError for size 0 or allocation failure.
    Buffer(const Context& context, vk::DeviceSize size,
           vk::BufferUsageFlags usage = vk::BufferUsageFlagBits::eStorageBuffer |
                                        vk::BufferUsageFlagBits::eTransferSrc |
                                        vk::BufferUsageFlagBits::eTransferDst,
           bool hostVisible = false, std::string debugName = "");

    vk::Buffer buffer() const { return *mBuffer; }
    vk::DeviceSize size() const { return mSize; }
    vk::BufferUsageFlags usage() const { return mUsage; }
    bool hostVisible() const { return mMapped != nullptr; }
    const std::string& debugName() const { return mDebugName; }
    // Persistent mapping of a hostVisible buffer, else nullptr.
    void* mapped() const { return mMapped; }
    // 0 unless created with eShaderDeviceAddress on a device with bufferDeviceAddress.
    vk::DeviceAddress deviceAddress() const { return mAddress; }

    // Host-visible: memcpy (the caller makes sure the GPU is not using the range). Otherwise via
    // staging in one submitAndWait with full barriers. Throws RuntimeError when out of range.
    void upload(const Context& context, const void* data, size_t bytes, vk::DeviceSize offset = 0);
    // Whole buffer; waits for and makes visible all earlier GPU writes.
    std::vector<std::byte> download(const Context& context) const;
    template <class T>
    std::vector<T> downloadAs(const Context& context) const {
        std::vector<std::byte> bytes = download(context);
        std::vector<T> out(bytes.size() / sizeof(T));
        std::memcpy(out.data(), bytes.data(), out.size() * sizeof(T));
        return out;
    }

private:
    vk::raii::DeviceMemory mMemory = nullptr;
    vk::raii::Buffer mBuffer = nullptr;
    vk::DeviceSize mSize = 0;
    vk::BufferUsageFlags mUsage;
    std::string mDebugName;
    void* mMapped = nullptr;
    vk::DeviceAddress mAddress = 0;
};

}  // namespace fovea::gpu
