#include "core/vk/ComputePipeline.h"

#include <cstring>

#include "core/util/DidYouMean.h"
#include "core/util/Error.h"
#include "core/vk/Context.h"
#include "core/vk/Formats.h"
#include "core/vk/Resources.h"

namespace fovea::gpu {
namespace {

std::string imageName(const Image& image) {
    return image.desc().debugName.empty() ? std::string("<unnamed>") : image.desc().debugName;
}

// The scalar class of a push-constant member from its GLSL type name; arrays of scalars count,
// structs do not (no check for them).
bool startsWithAny(const std::string& s, std::initializer_list<const char*> prefixes) {
    for (const char* p : prefixes)
        if (s.rfind(p, 0) == 0) return true;
    return false;
}

}  // namespace

ComputePipeline::ComputePipeline(Context& context, const std::string& shaderPath,
                                 const ShaderDefines& defines)
    : mContext(context), mShaderPath(shaderPath) {
    std::vector<uint32_t> spirv = context.shaderCompiler().compile(shaderPath, defines);
    try {
        mInterface = reflectShader(spirv);
    } catch (const RuntimeError& e) {
        throw RuntimeError(label() + ": " + e.what());
    }

    auto pushProps = context.physicalDevice()
                         .getProperties2<vk::PhysicalDeviceProperties2,
                                         vk::PhysicalDevicePushDescriptorPropertiesKHR>()
                         .get<vk::PhysicalDevicePushDescriptorPropertiesKHR>();
    if (mInterface.bindings.size() > pushProps.maxPushDescriptors)
        throw RuntimeError(label() + " declares " + std::to_string(mInterface.bindings.size()) +
                           " resources but '" + context.deviceName() + "' can push at most " +
                           std::to_string(pushProps.maxPushDescriptors));
    if (mInterface.pushConstantSize > context.limits().maxPushConstantsSize)
        throw RuntimeError(label() + " has " + std::to_string(mInterface.pushConstantSize) +
                           " bytes of push constants; the device allows " +
                           std::to_string(context.limits().maxPushConstantsSize));

    std::vector<vk::DescriptorSetLayoutBinding> layoutBindings;
    for (const auto& b : mInterface.bindings) {
        // One pushed set keeps binding simple; passes never need more than set 0.
        if (b.set != 0)
            throw RuntimeError(label() + ": resource '" + b.name + "' uses set " +
                               std::to_string(b.set) + "; fovea compute shaders use set 0 only");
        if (b.arraySize != 1)
            throw RuntimeError(label() + ": resource '" + b.name +
                               "' is a descriptor array, which fovea cannot bind");
        layoutBindings.push_back(
            vk::DescriptorSetLayoutBinding{.binding = b.binding,
                                           .descriptorType = descriptorType(b.kind),
                                           .descriptorCount = 1,
                                           .stageFlags = vk::ShaderStageFlagBits::eCompute});
    }
    const auto& device = context.device();
    auto objects = std::make_shared<Objects>();
    objects->setLayout = vk::raii::DescriptorSetLayout(
        device, vk::DescriptorSetLayoutCreateInfo{
                    .flags = vk::DescriptorSetLayoutCreateFlagBits::ePushDescriptorKHR,
                    .bindingCount = static_cast<uint32_t>(layoutBindings.size()),
                    .pBindings = layoutBindings.data()});
    vk::PushConstantRange range{.stageFlags = vk::ShaderStageFlagBits::eCompute,
                                .offset = 0,
                                .size = mInterface.pushConstantSize};
    vk::DescriptorSetLayout setLayout = *objects->setLayout;
    objects->layout = vk::raii::PipelineLayout(
        device, vk::PipelineLayoutCreateInfo{
                    .setLayoutCount = 1,
                    .pSetLayouts = &setLayout,
                    .pushConstantRangeCount = mInterface.pushConstantSize > 0 ? 1u : 0u,
                    .pPushConstantRanges = &range});
    vk::raii::ShaderModule module(
        device, vk::ShaderModuleCreateInfo{.codeSize = spirv.size() * sizeof(uint32_t),
                                           .pCode = spirv.data()});
    try {
        objects->pipeline = vk::raii::Pipeline(
            device, nullptr,
            vk::ComputePipelineCreateInfo{
                .stage =
                    vk::PipelineShaderStageCreateInfo{.stage = vk::ShaderStageFlagBits::eCompute,
                                                      .module = *module,
                                                      .pName = "main"},
                .layout = *objects->layout});
    } catch (const vk::SystemError& e) {
        throw RuntimeError(label() + ": pipeline creation failed: " + e.what());
    }
    context.setObjectName(*objects->pipeline, mShaderPath);
    context.setObjectName(*objects->layout, mShaderPath);
    mObjects = std::move(objects);
    mStaged.resize(mInterface.bindings.size());
    mPushData.assign(mInterface.pushConstantSize, 0);
}

ComputePipeline::ComputePipeline(const ComputePipeline& other, ShareTag)
    : mContext(other.mContext),
      mShaderPath(other.mShaderPath),
      mInterface(other.mInterface),
      mObjects(other.mObjects),
      mStaged(other.mInterface.bindings.size()),
      mPushData(other.mInterface.pushConstantSize, 0) {}

std::unique_ptr<ComputePipeline> ComputePipeline::share() const {
    return std::make_unique<ComputePipeline>(*this, ShareTag{});
}

size_t ComputePipeline::bindingIndex(std::string_view name) const {
    for (size_t i = 0; i < mInterface.bindings.size(); ++i)
        if (mInterface.bindings[i].name == name) return i;
    throw RuntimeError(label() + " has no resource '" + std::string(name) + "'" +
                       didYouMean(name, mInterface.bindingNames()));
}

ComputePipeline& ComputePipeline::bind(std::string_view name, const Image& image) {
    return bindImage(name, image, false);
}

ComputePipeline& ComputePipeline::bindNearest(std::string_view name, const Image& image) {
    return bindImage(name, image, true);
}

ComputePipeline& ComputePipeline::bindImage(std::string_view name, const Image& image,
                                            bool nearest) {
    const size_t index = bindingIndex(name);
    const ShaderBinding& b = mInterface.bindings[index];
    const std::string where = label() + " resource '" + b.name + "'";
    if (b.kind != DescriptorKind::StorageImage && b.kind != DescriptorKind::SampledImage)
        throw RuntimeError(where + " is a " + descriptorKindName(b.kind) +
                           "; bind a Buffer, not image '" + imageName(image) + "'");
    vk::Sampler sampler = nullptr;
    if (b.kind == DescriptorKind::StorageImage) {
        if (nearest)
            throw RuntimeError(where + " is a storage image; bindNearest is for sampled images");
        if (!(image.desc().usage & vk::ImageUsageFlagBits::eStorage))
            throw RuntimeError(where + ": image '" + imageName(image) + "' lacks storage usage");
        if (b.imageFormat != vk::Format::eUndefined && b.imageFormat != image.format())
            throw RuntimeError(where + " is declared " + formatName(b.imageFormat) +
                               " but image '" + imageName(image) + "' is " +
                               formatName(image.format()));
    } else {
        if (!(image.desc().usage & vk::ImageUsageFlagBits::eSampled))
            throw RuntimeError(where + ": image '" + imageName(image) + "' lacks sampled usage");
        // Linear filtering of a format that does not support it is invalid (e.g. uint formats).
        auto features =
            mContext.physicalDevice().getFormatProperties(image.format()).optimalTilingFeatures;
        bool linearOk = bool(features & vk::FormatFeatureFlagBits::eSampledImageFilterLinear);
        sampler = (nearest || !linearOk) ? *mContext.nearestClampSampler()
                                         : *mContext.linearClampSampler();
    }
    Staged& s = mStaged[index];
    s.bound = true;
    s.image = vk::DescriptorImageInfo{
        .sampler = sampler, .imageView = image.view(), .imageLayout = vk::ImageLayout::eGeneral};
    return *this;
}

ComputePipeline& ComputePipeline::bind(std::string_view name, const Buffer& buffer) {
    const size_t index = bindingIndex(name);
    const ShaderBinding& b = mInterface.bindings[index];
    const std::string where = label() + " resource '" + b.name + "'";
    const std::string bufferName = buffer.debugName().empty() ? "<unnamed>" : buffer.debugName();
    if (b.kind != DescriptorKind::StorageBuffer && b.kind != DescriptorKind::UniformBuffer)
        throw RuntimeError(where + " is a " + descriptorKindName(b.kind) +
                           "; bind an Image, not buffer '" + bufferName + "'");
    auto needed = b.kind == DescriptorKind::StorageBuffer ? vk::BufferUsageFlagBits::eStorageBuffer
                                                          : vk::BufferUsageFlagBits::eUniformBuffer;
    if (!(buffer.usage() & needed))
        throw RuntimeError(where + ": buffer '" + bufferName + "' lacks " + vk::to_string(needed) +
                           " usage");
    Staged& s = mStaged[index];
    s.bound = true;
    s.buffer =
        vk::DescriptorBufferInfo{.buffer = buffer.buffer(), .offset = 0, .range = VK_WHOLE_SIZE};
    return *this;
}

ComputePipeline& ComputePipeline::setBytes(std::string_view member, const void* data, size_t size) {
    return setBytes(member, data, size, ScalarClass::Other);
}

ComputePipeline& ComputePipeline::setBytes(std::string_view member, const void* data, size_t size,
                                           ScalarClass valueClass) {
    const PushConstantMember* m = mInterface.findPushConstant(member);
    if (!m)
        throw RuntimeError(label() + " has no push constant '" + std::string(member) + "'" +
                           didYouMean(member, mInterface.pushConstantNames()));
    const std::string where = label() + " push constant '" + m->name + "' (" + m->typeName + ", " +
                              std::to_string(m->size) + " bytes)";
    if (size != m->size)
        throw RuntimeError(where + " was set with a " + std::to_string(size) + "-byte value");
    const bool memberFloat =
        startsWithAny(m->typeName, {"float", "vec", "mat", "f16", "double", "dvec", "dmat"});
    const bool memberInteger = startsWithAny(
        m->typeName,
        {"int", "uint", "ivec", "uvec", "bool", "bvec", "i8", "u8", "i16", "u16", "i64", "u64"});
    if ((valueClass == ScalarClass::Float && memberInteger) ||
        (valueClass == ScalarClass::Integer && memberFloat))
        throw RuntimeError(where + " was set with " +
                           (valueClass == ScalarClass::Float ? "a floating-point" : "an integer") +
                           " value");
    std::memcpy(mPushData.data() + m->offset, data, size);
    return *this;
}

std::array<uint32_t, 3> ComputePipeline::groupCount(uint32_t threadsX, uint32_t threadsY,
                                                    uint32_t threadsZ) const {
    const auto& local = mInterface.localSize;
    return {(threadsX + local[0] - 1) / local[0], (threadsY + local[1] - 1) / local[1],
            (threadsZ + local[2] - 1) / local[2]};
}

void ComputePipeline::recordState(const vk::raii::CommandBuffer& cmd) {
    std::vector<vk::WriteDescriptorSet> writes;
    writes.reserve(mStaged.size());
    for (size_t i = 0; i < mStaged.size(); ++i) {
        const ShaderBinding& b = mInterface.bindings[i];
        if (!mStaged[i].bound)
            throw RuntimeError(label() + " expects resource '" + b.name + "' but none was bound");
        const bool isImage =
            b.kind == DescriptorKind::StorageImage || b.kind == DescriptorKind::SampledImage;
        writes.push_back(
            vk::WriteDescriptorSet{.dstBinding = b.binding,
                                   .descriptorCount = 1,
                                   .descriptorType = descriptorType(b.kind),
                                   .pImageInfo = isImage ? &mStaged[i].image : nullptr,
                                   .pBufferInfo = isImage ? nullptr : &mStaged[i].buffer});
    }
    cmd.bindPipeline(vk::PipelineBindPoint::eCompute, *mObjects->pipeline);
    if (!writes.empty())
        cmd.pushDescriptorSetKHR(vk::PipelineBindPoint::eCompute, *mObjects->layout, 0, writes);
    if (!mPushData.empty())
        cmd.pushConstants<uint8_t>(*mObjects->layout, vk::ShaderStageFlagBits::eCompute, 0,
                                   mPushData);
}

std::vector<ResourceAccess> ComputePipeline::accesses() const {
    std::vector<ResourceAccess> out;
    out.reserve(mStaged.size());
    for (size_t i = 0; i < mStaged.size(); ++i) {
        if (!mStaged[i].bound) continue;
        const ShaderBinding& b = mInterface.bindings[i];
        ResourceAccess a;
        a.image = b.kind == DescriptorKind::StorageImage || b.kind == DescriptorKind::SampledImage;
        a.handle = a.image ? uint64_t(VkImageView(mStaged[i].image.imageView))
                           : uint64_t(VkBuffer(mStaged[i].buffer.buffer));
        const bool storage =
            b.kind == DescriptorKind::StorageImage || b.kind == DescriptorKind::StorageBuffer;
        a.read = !storage || !b.writeonly;
        a.write = storage && !b.readonly;
        out.push_back(a);
    }
    return out;
}

void ComputePipeline::dispatch(const vk::raii::CommandBuffer& cmd, uint32_t threadsX,
                               uint32_t threadsY, uint32_t threadsZ) {
    const auto groups = groupCount(threadsX, threadsY, threadsZ);
    const auto& maxGroups = mContext.limits().maxComputeWorkGroupCount;
    for (int i = 0; i < 3; ++i)
        if (groups[i] > maxGroups[i])
            throw RuntimeError(label() + ": dispatch of " + std::to_string(groups[i]) +
                               " groups exceeds the device limit " + std::to_string(maxGroups[i]));
    recordState(cmd);
    cmd.dispatch(groups[0], groups[1], groups[2]);
}

void ComputePipeline::dispatchIndirect(const vk::raii::CommandBuffer& cmd, const Buffer& args,
                                       vk::DeviceSize offset) {
    if (!(args.usage() & vk::BufferUsageFlagBits::eIndirectBuffer))
        throw RuntimeError(label() + ": indirect dispatch from a buffer without INDIRECT usage");
    if (offset % 4 != 0 || offset + 3 * sizeof(uint32_t) > args.size())
        throw RuntimeError(label() + ": indirect arguments at offset " + std::to_string(offset) +
                           " do not fit the buffer");
    recordState(cmd);
    cmd.dispatchIndirect(args.buffer(), offset);
}

}  // namespace fovea::gpu
