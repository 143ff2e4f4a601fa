#include "core/vk/Resources.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/packing.hpp>
#include <optional>
#include <utility>

#include "core/util/Error.h"
#include "core/vk/Barriers.h"
#include "core/vk/Context.h"
#include "core/vk/Formats.h"

namespace fovea::gpu {
namespace {

using Stage = vk::PipelineStageFlagBits2;
using Access = vk::AccessFlagBits2;
constexpr vk::AccessFlags2 kAnyAccess = Access::eMemoryRead | Access::eMemoryWrite;
constexpr vk::ImageSubresourceRange kColorRange{vk::ImageAspectFlagBits::eColor, 0, 1, 0, 1};

vk::ImageCreateInfo imageInfo(const ImageDesc& desc) {
    return vk::ImageCreateInfo{.imageType = vk::ImageType::e2D,
                               .format = desc.format,
                               .extent = vk::Extent3D{desc.width, desc.height, 1},
                               .mipLevels = 1,
                               .arrayLayers = 1,
                               .samples = vk::SampleCountFlagBits::e1,
                               .tiling = vk::ImageTiling::eOptimal,
                               .usage = desc.usage,
                               .sharingMode = vk::SharingMode::eExclusive,
                               .initialLayout = vk::ImageLayout::eUndefined};
}

std::string imageLabel(const ImageDesc& desc) {
    return "image '" + (desc.debugName.empty() ? std::string("<unnamed>") : desc.debugName) +
           "' (" + std::to_string(desc.width) + "x" + std::to_string(desc.height) + " " +
           formatName(desc.format) + ")";
}

// Fails early with a readable message instead of a validation error at vkCreateImage.
void checkImageSupport(const Context& context, const ImageDesc& desc) {
    if (desc.width == 0 || desc.height == 0)
        throw RuntimeError(imageLabel(desc) + ": width and height must be at least 1");
    auto features = context.physicalDevice().getFormatProperties(desc.format).optimalTilingFeatures;
    const std::pair<vk::ImageUsageFlagBits, vk::FormatFeatureFlagBits> needs[] = {
        {vk::ImageUsageFlagBits::eStorage, vk::FormatFeatureFlagBits::eStorageImage},
        {vk::ImageUsageFlagBits::eSampled, vk::FormatFeatureFlagBits::eSampledImage},
        {vk::ImageUsageFlagBits::eTransferSrc, vk::FormatFeatureFlagBits::eTransferSrc},
        {vk::ImageUsageFlagBits::eTransferDst, vk::FormatFeatureFlagBits::eTransferDst},
        {vk::ImageUsageFlagBits::eColorAttachment, vk::FormatFeatureFlagBits::eColorAttachment},
    };
    for (auto [usage, feature] : needs) {
        if ((desc.usage & usage) && !(features & feature))
            throw RuntimeError(imageLabel(desc) + ": format " + formatName(desc.format) +
                               " does not support " + vk::to_string(usage) + " usage on '" +
                               context.deviceName() + "'");
    }
    auto limit = context.limits().maxImageDimension2D;
    if (desc.width > limit || desc.height > limit)
        throw RuntimeError(imageLabel(desc) + ": larger than the device limit " +
                           std::to_string(limit));
    // The device's largest resource of this format and usage (maxResourceSize, at least 2^31):
    // checked here so that an oversized render gets this message, not a driver error.
    const vk::DeviceSize bytes =
        vk::DeviceSize(desc.width) * desc.height * formatBytesPerPixel(desc.format);
    vk::ImageFormatProperties props;
    try {
        props = context.physicalDevice().getImageFormatProperties(
            desc.format, vk::ImageType::e2D, vk::ImageTiling::eOptimal, desc.usage);
    } catch (const vk::SystemError& e) {
        throw RuntimeError(imageLabel(desc) + ": usage " + vk::to_string(desc.usage) +
                           " not supported on '" + context.deviceName() + "': " + e.what());
    }
    if (bytes > props.maxResourceSize)
        throw RuntimeError(imageLabel(desc) + ": " + std::to_string(bytes) + " bytes (" +
                           std::to_string(bytes >> 20) + " MiB) exceed the largest image '" +
                           context.deviceName() + "' allows for this format (" +
                           std::to_string(props.maxResourceSize >> 20) +
                           " MiB); render at a smaller --size");
}

// The heap behind `memoryType`: its index and size (nullopt for an index the device lacks).
std::optional<std::pair<uint32_t, vk::DeviceSize>> heapOfType(const Context& context,
                                                              uint32_t memoryType) {
    const auto props = context.physicalDevice().getMemoryProperties();
    if (memoryType >= props.memoryTypeCount) return std::nullopt;
    const uint32_t heap = props.memoryTypes[memoryType].heapIndex;
    return std::make_pair(heap, props.memoryHeaps[heap].size);
}

// "memory heap 0 of 2048 MiB on 'llvmpipe ...'": the budget a failed allocation or bind ran into.
std::string heapOf(const Context& context, uint32_t memoryType) {
    const auto heap = heapOfType(context, memoryType);
    if (!heap) return "'" + context.deviceName() + "'";
    return "memory heap " + std::to_string(heap->first) + " of " +
           std::to_string(heap->second >> 20) + " MiB on '" + context.deviceName() + "'";
}

// Binds `resource` (an image or buffer described by `label`, `bytes` of `memoryType`) and turns a
// driver's out-of-memory into a message that names it, its size and the device's budget (issue
// 33: "vk::Image::bindMemory: ErrorOutOfDeviceMemory" named nothing).
template <class Resource>
void bindMemory(const Context& context, const Resource& resource,
                const vk::raii::DeviceMemory& memory, vk::DeviceSize offset, vk::DeviceSize bytes,
                uint32_t memoryType, const std::string& label) {
    try {
        resource.bindMemory(*memory, offset);
    } catch (const vk::SystemError& e) {
        throw RuntimeError("cannot place " + label + ": " + std::to_string(bytes) + " bytes (" +
                           std::to_string(bytes >> 20) + " MiB) do not fit in " +
                           heapOf(context, memoryType) + " (" + e.what() +
                           "); render at a smaller --size");
    }
}

vk::raii::DeviceMemory allocate(const Context& context, vk::DeviceSize size, uint32_t typeBits,
                                vk::MemoryPropertyFlags props, const std::string& what,
                                const void* pNext = nullptr) {
    uint32_t type = context.findMemoryType(typeBits, props);
    // Larger than the whole heap: say so before the driver (and the validation layer) refuse.
    const auto heap = heapOfType(context, type);
    if (heap && size > heap->second)
        throw RuntimeError("cannot allocate " + std::to_string(size) + " bytes (" +
                           std::to_string(size >> 20) + " MiB) for " + what + ": larger than " +
                           heapOf(context, type) + "; render at a smaller --size");
    context.countAllocation();
    try {
        return vk::raii::DeviceMemory(
            context.device(), vk::MemoryAllocateInfo{
                                  .pNext = pNext, .allocationSize = size, .memoryTypeIndex = type});
    } catch (const vk::SystemError& e) {
        throw RuntimeError("cannot allocate " + std::to_string(size) + " bytes (" +
                           std::to_string(size >> 20) + " MiB) for " + what + " in " +
                           heapOf(context, type) + ": " + e.what());
    }
}

enum class Component { F32, F16, Unorm8, U32 };

Component componentOf(vk::Format format) {
    switch (format) {
        case vk::Format::eR16G16B16A16Sfloat:
        case vk::Format::eR16G16Sfloat:
        case vk::Format::eR16Sfloat:
            return Component::F16;
        case vk::Format::eR8G8B8A8Unorm:
        case vk::Format::eR8Unorm:
            return Component::Unorm8;
        case vk::Format::eR32Uint:
        case vk::Format::eR32G32Uint:
        case vk::Format::eR32G32B32A32Uint:
            return Component::U32;
        default:
            return Component::F32;
    }
}

float readComponent(const std::byte* p, Component c) {
    switch (c) {
        case Component::F32: {
            float v;
            std::memcpy(&v, p, 4);
            return v;
        }
        case Component::F16: {
            uint16_t v;
            std::memcpy(&v, p, 2);
            return glm::unpackHalf1x16(v);
        }
        case Component::Unorm8:
            return static_cast<float>(std::to_integer<uint8_t>(*p)) / 255.0f;
        case Component::U32: {
            uint32_t v;
            std::memcpy(&v, p, 4);
            return static_cast<float>(v);
        }
    }
    return 0.0f;
}

void writeComponent(std::byte* p, Component c, float value) {
    switch (c) {
        case Component::F32:
            std::memcpy(p, &value, 4);
            break;
        case Component::F16: {
            uint16_t v = glm::packHalf1x16(value);
            std::memcpy(p, &v, 2);
            break;
        }
        case Component::Unorm8: {
            float scaled = std::round(std::clamp(value, 0.0f, 1.0f) * 255.0f);
            *p = static_cast<std::byte>(static_cast<uint8_t>(scaled));
            break;
        }
        case Component::U32: {
            // NaN and negatives have no uint meaning; clamping keeps the conversion defined.
            float clamped = std::isnan(value) ? 0.0f : std::clamp(value, 0.0f, 4294967040.0f);
            auto v = static_cast<uint32_t>(clamped);
            std::memcpy(p, &v, 4);
            break;
        }
    }
}

}  // namespace

// --- MemoryBlock -----------------------------------------------------------------------------

MemoryBlock::MemoryBlock(const Context& context, vk::DeviceSize size, uint32_t memoryTypeBits,
                         vk::MemoryPropertyFlags props, const std::string& what)
    : mSize(size) {
    mMemoryType = context.findMemoryType(memoryTypeBits, props);
    mMemory = allocate(context, size, 1u << mMemoryType, props, what);
}

// --- Image -----------------------------------------------------------------------------------

vk::MemoryRequirements Image::memoryRequirements(const Context& context, const ImageDesc& desc) {
    vk::ImageCreateInfo info = imageInfo(desc);
    return context.device()
        .getImageMemoryRequirements(vk::DeviceImageMemoryRequirements{.pCreateInfo = &info})
        .memoryRequirements;
}

void Image::create(const Context& context) {
    checkImageSupport(context, mDesc);
    try {
        mImage = vk::raii::Image(context.device(), imageInfo(mDesc));
    } catch (const vk::SystemError& e) {
        throw RuntimeError("cannot create " + imageLabel(mDesc) + ": " + e.what());
    }
    context.setObjectName(*mImage, mDesc.debugName);
}

Image::Image(const Context& context, const ImageDesc& desc) : mDesc(desc) {
    create(context);
    vk::MemoryRequirements req = mImage.getMemoryRequirements();
    mAllocationSize = req.size;
    mMemory = allocate(context, req.size, req.memoryTypeBits,
                       vk::MemoryPropertyFlagBits::eDeviceLocal, imageLabel(mDesc));
    context.setObjectName(*mMemory, mDesc.debugName);
    bindMemory(context, mImage, mMemory, 0, req.size,
               context.findMemoryType(req.memoryTypeBits, vk::MemoryPropertyFlagBits::eDeviceLocal),
               imageLabel(mDesc));
    mView = vk::raii::ImageView(context.device(),
                                vk::ImageViewCreateInfo{.image = *mImage,
                                                        .viewType = vk::ImageViewType::e2D,
                                                        .format = mDesc.format,
                                                        .subresourceRange = kColorRange});
    context.setObjectName(*mView, mDesc.debugName);
    // Fresh images start defined (zero) so a pass reading before anyone wrote gets no garbage.
    context.submitAndWait([&](const vk::raii::CommandBuffer& cmd) {
        imageBarrier(cmd, *mImage, vk::ImageLayout::eUndefined, vk::ImageLayout::eGeneral,
                     Stage::eNone, {}, Stage::eClear, Access::eTransferWrite);
        recordClear(cmd, {0, 0, 0, 0});
        imageBarrier(cmd, *mImage, vk::ImageLayout::eGeneral, vk::ImageLayout::eGeneral,
                     Stage::eClear, Access::eTransferWrite, Stage::eAllCommands, kAnyAccess);
    });
}

Image::Image(const Context& context, const ImageDesc& desc, std::shared_ptr<MemoryBlock> block,
             vk::DeviceSize offset)
    : mDesc(desc), mBlock(std::move(block)) {
    if (!mBlock) throw RuntimeError(imageLabel(mDesc) + ": aliased image without a memory block");
    create(context);
    vk::MemoryRequirements req = mImage.getMemoryRequirements();
    mAllocationSize = req.size;
    if (!(req.memoryTypeBits & (1u << mBlock->memoryType())))
        throw RuntimeError(imageLabel(mDesc) + ": memory block type " +
                           std::to_string(mBlock->memoryType()) + " not allowed (type bits " +
                           std::to_string(req.memoryTypeBits) + ")");
    if (offset % req.alignment != 0 || offset + req.size > mBlock->size())
        throw RuntimeError(imageLabel(mDesc) + ": needs " + std::to_string(req.size) +
                           " bytes aligned to " + std::to_string(req.alignment) + " at offset " +
                           std::to_string(offset) + " of a " + std::to_string(mBlock->size()) +
                           "-byte block");
    bindMemory(context, mImage, mBlock->memory(), offset, req.size, mBlock->memoryType(),
               imageLabel(mDesc) + " (aliased, at offset " + std::to_string(offset) + " of a " +
                   std::to_string(mBlock->size() >> 20) + " MiB block)");
    mView = vk::raii::ImageView(context.device(),
                                vk::ImageViewCreateInfo{.image = *mImage,
                                                        .viewType = vk::ImageViewType::e2D,
                                                        .format = mDesc.format,
                                                        .subresourceRange = kColorRange});
    context.setObjectName(*mView, mDesc.debugName);
}

size_t Image::byteSize() const {
    return size_t(mDesc.width) * mDesc.height * formatBytesPerPixel(mDesc.format);
}

void Image::upload(const Context& context, const void* data, size_t bytes) {
    if (bytes != byteSize())
        throw RuntimeError(imageLabel(mDesc) + ": upload of " + std::to_string(bytes) +
                           " bytes, expected " + std::to_string(byteSize()));
    Buffer staging(context, bytes, vk::BufferUsageFlagBits::eTransferSrc, true, "upload staging");
    std::memcpy(staging.mapped(), data, bytes);
    context.submitAndWait([&](const vk::raii::CommandBuffer& cmd) {
        imageBarrier(cmd, *mImage, vk::ImageLayout::eGeneral, vk::ImageLayout::eGeneral,
                     Stage::eAllCommands, kAnyAccess, Stage::eCopy, Access::eTransferWrite);
        vk::BufferImageCopy region{.imageSubresource = {vk::ImageAspectFlagBits::eColor, 0, 0, 1},
                                   .imageExtent = vk::Extent3D{mDesc.width, mDesc.height, 1}};
        cmd.copyBufferToImage(staging.buffer(), *mImage, vk::ImageLayout::eGeneral, region);
        imageBarrier(cmd, *mImage, vk::ImageLayout::eGeneral, vk::ImageLayout::eGeneral,
                     Stage::eCopy, Access::eTransferWrite, Stage::eAllCommands, kAnyAccess);
    });
}

std::vector<std::byte> Image::download(const Context& context) const {
    const size_t bytes = byteSize();
    Buffer staging(context, bytes, vk::BufferUsageFlagBits::eTransferDst, true, "download staging");
    context.submitAndWait([&](const vk::raii::CommandBuffer& cmd) {
        imageBarrier(cmd, *mImage, vk::ImageLayout::eGeneral, vk::ImageLayout::eGeneral,
                     Stage::eAllCommands, Access::eMemoryWrite, Stage::eCopy,
                     Access::eTransferRead);
        vk::BufferImageCopy region{.imageSubresource = {vk::ImageAspectFlagBits::eColor, 0, 0, 1},
                                   .imageExtent = vk::Extent3D{mDesc.width, mDesc.height, 1}};
        cmd.copyImageToBuffer(*mImage, vk::ImageLayout::eGeneral, staging.buffer(), region);
        // Later writes to the image must wait for the read (WAR), and the host reads the copy.
        imageBarrier(cmd, *mImage, vk::ImageLayout::eGeneral, vk::ImageLayout::eGeneral,
                     Stage::eCopy, {}, Stage::eAllCommands, {});
        memoryBarrier(cmd, Stage::eCopy, Access::eTransferWrite, Stage::eHost, Access::eHostRead);
    });
    std::vector<std::byte> out(bytes);
    std::memcpy(out.data(), staging.mapped(), bytes);
    return out;
}

std::vector<float> Image::downloadRGBA32F(const Context& context) const {
    std::vector<std::byte> raw = download(context);
    const uint32_t channels = formatChannels(mDesc.format);
    const Component component = componentOf(mDesc.format);
    const uint32_t componentBytes = formatBytesPerPixel(mDesc.format) / channels;
    const size_t pixels = size_t(mDesc.width) * mDesc.height;
    std::vector<float> out(pixels * 4);
    for (size_t i = 0; i < pixels; ++i) {
        const std::byte* src = raw.data() + i * channels * componentBytes;
        for (uint32_t c = 0; c < 4; ++c) {
            out[i * 4 + c] = c < channels ? readComponent(src + c * componentBytes, component)
                                          : (c == 3 ? 1.0f : 0.0f);
        }
    }
    return out;
}

void Image::uploadRGBA32F(const Context& context, const std::vector<float>& rgba) {
    const size_t pixels = size_t(mDesc.width) * mDesc.height;
    if (rgba.size() != pixels * 4)
        throw RuntimeError(imageLabel(mDesc) + ": uploadRGBA32F got " +
                           std::to_string(rgba.size()) + " floats, expected " +
                           std::to_string(pixels * 4));
    const uint32_t channels = formatChannels(mDesc.format);
    const Component component = componentOf(mDesc.format);
    const uint32_t componentBytes = formatBytesPerPixel(mDesc.format) / channels;
    std::vector<std::byte> raw(byteSize());
    for (size_t i = 0; i < pixels; ++i) {
        std::byte* dst = raw.data() + i * channels * componentBytes;
        for (uint32_t c = 0; c < channels; ++c)
            writeComponent(dst + c * componentBytes, component, rgba[i * 4 + c]);
    }
    upload(context, raw.data(), raw.size());
}

void Image::recordClear(const vk::raii::CommandBuffer& cmd, std::array<float, 4> value) const {
    std::array<uint32_t, 4> asUint{};
    for (size_t i = 0; i < 4; ++i) asUint[i] = static_cast<uint32_t>(std::max(value[i], 0.0f));
    const vk::ClearColorValue color = formatIsUint(mDesc.format)
                                          ? vk::ClearColorValue{.uint32 = asUint}
                                          : vk::ClearColorValue{.float32 = value};
    cmd.clearColorImage(*mImage, vk::ImageLayout::eGeneral, color, kColorRange);
}

void Image::recordTransition(const vk::raii::CommandBuffer& cmd, vk::ImageLayout from,
                             vk::ImageLayout to) const {
    imageBarrier(cmd, *mImage, from, to, Stage::eAllCommands, kAnyAccess, Stage::eAllCommands,
                 kAnyAccess);
}

// --- Buffer ----------------------------------------------------------------------------------

Buffer::Buffer(const Context& context, vk::DeviceSize size, vk::BufferUsageFlags usage,
               bool hostVisible, std::string debugName)
    : mSize(size), mUsage(usage), mDebugName(std::move(debugName)) {
    const std::string label = "buffer '" + (mDebugName.empty() ? "<unnamed>" : mDebugName) + "'";
    if (size == 0) throw RuntimeError(label + ": size must be at least 1 byte");
    try {
        mBuffer = vk::raii::Buffer(
            context.device(),
            vk::BufferCreateInfo{
                .size = size, .usage = usage, .sharingMode = vk::SharingMode::eExclusive});
    } catch (const vk::SystemError& e) {
        throw RuntimeError("cannot create " + label + ": " + e.what());
    }
    context.setObjectName(*mBuffer, mDebugName);
    vk::MemoryRequirements req = mBuffer.getMemoryRequirements();
    const bool wantAddress = (usage & vk::BufferUsageFlagBits::eShaderDeviceAddress) &&
                             context.features().bufferDeviceAddress;
    vk::MemoryAllocateFlagsInfo flags{.flags = vk::MemoryAllocateFlagBits::eDeviceAddress};
    vk::MemoryPropertyFlags props = hostVisible ? vk::MemoryPropertyFlagBits::eHostVisible |
                                                      vk::MemoryPropertyFlagBits::eHostCoherent
                                                : vk::MemoryPropertyFlagBits::eDeviceLocal;
    mMemory = allocate(context, req.size, req.memoryTypeBits, props, label,
                       wantAddress ? &flags : nullptr);
    context.setObjectName(*mMemory, mDebugName);
    bindMemory(context, mBuffer, mMemory, 0, req.size,
               context.findMemoryType(req.memoryTypeBits, props), label);
    if (hostVisible) mMapped = mMemory.mapMemory(0, VK_WHOLE_SIZE);
    if (wantAddress)
        mAddress =
            context.device().getBufferAddress(vk::BufferDeviceAddressInfo{.buffer = *mBuffer});
}

void Buffer::upload(const Context& context, const void* data, size_t bytes, vk::DeviceSize offset) {
    if (offset + bytes > mSize)
        throw RuntimeError("buffer '" + mDebugName + "': upload of " + std::to_string(bytes) +
                           " bytes at offset " + std::to_string(offset) + " exceeds its " +
                           std::to_string(mSize) + " bytes");
    if (bytes == 0) return;
    if (mMapped) {
        std::memcpy(static_cast<std::byte*>(mMapped) + offset, data, bytes);
        return;
    }
    if (!(mUsage & vk::BufferUsageFlagBits::eTransferDst))
        throw RuntimeError("buffer '" + mDebugName + "': upload needs eTransferDst usage");
    Buffer staging(context, bytes, vk::BufferUsageFlagBits::eTransferSrc, true, "upload staging");
    std::memcpy(staging.mapped(), data, bytes);
    context.submitAndWait([&](const vk::raii::CommandBuffer& cmd) {
        memoryBarrier(cmd, Stage::eAllCommands, kAnyAccess, Stage::eCopy, Access::eTransferWrite);
        cmd.copyBuffer(staging.buffer(), *mBuffer,
                       vk::BufferCopy{.srcOffset = 0, .dstOffset = offset, .size = bytes});
        memoryBarrier(cmd, Stage::eCopy, Access::eTransferWrite, Stage::eAllCommands, kAnyAccess);
    });
}

std::vector<std::byte> Buffer::download(const Context& context) const {
    std::vector<std::byte> out(mSize);
    if (mMapped) {
        // Still one tiny submit: it waits for earlier GPU writes and makes them host-visible.
        context.submitAndWait([&](const vk::raii::CommandBuffer& cmd) {
            memoryBarrier(cmd, Stage::eAllCommands, Access::eMemoryWrite, Stage::eHost,
                          Access::eHostRead);
        });
        std::memcpy(out.data(), mMapped, mSize);
        return out;
    }
    if (!(mUsage & vk::BufferUsageFlagBits::eTransferSrc))
        throw RuntimeError("buffer '" + mDebugName + "': download needs eTransferSrc usage");
    Buffer staging(context, mSize, vk::BufferUsageFlagBits::eTransferDst, true, "download staging");
    context.submitAndWait([&](const vk::raii::CommandBuffer& cmd) {
        memoryBarrier(cmd, Stage::eAllCommands, Access::eMemoryWrite, Stage::eCopy,
                      Access::eTransferRead);
        cmd.copyBuffer(*mBuffer, staging.buffer(), vk::BufferCopy{.size = mSize});
        memoryBarrier(cmd, Stage::eCopy, Access::eTransferWrite, Stage::eHost, Access::eHostRead);
    });
    std::memcpy(out.data(), staging.mapped(), mSize);
    return out;
}

}  // namespace fovea::gpu
