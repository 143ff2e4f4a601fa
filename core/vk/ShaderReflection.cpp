#include "core/vk/ShaderReflection.h"

#include <spirv_cross/spirv_cross_c.h>

#include <algorithm>
#include <memory>
#include <tuple>

#include "core/util/Error.h"

namespace fovea::gpu {
namespace {

using ContextPtr = std::unique_ptr<spvc_context_s, decltype(&spvc_context_destroy)>;

std::string vectorName(const char* scalar, const char* vectorPrefix, uint32_t n) {
    return n == 1 ? std::string(scalar) : std::string(vectorPrefix) + "vec" + std::to_string(n);
}

// GLSL spelling of a (push-constant member) type.
std::string glslTypeName(spvc_compiler compiler, spvc_type_id typeId) {
    spvc_type type = spvc_compiler_get_type_handle(compiler, typeId);
    const uint32_t n = spvc_type_get_vector_size(type);
    const uint32_t columns = spvc_type_get_columns(type);
    std::string name;
    switch (spvc_type_get_basetype(type)) {
        case SPVC_BASETYPE_FP32:
            if (columns > 1)
                name = columns == n ? "mat" + std::to_string(columns)
                                    : "mat" + std::to_string(columns) + "x" + std::to_string(n);
            else
                name = vectorName("float", "", n);
            break;
        case SPVC_BASETYPE_FP16:
            name = vectorName("float16_t", "f16", n);
            break;
        case SPVC_BASETYPE_FP64:
            name = columns > 1 ? "dmat" + std::to_string(columns) : vectorName("double", "d", n);
            break;
        case SPVC_BASETYPE_INT32:
            name = vectorName("int", "i", n);
            break;
        case SPVC_BASETYPE_UINT32:
            name = vectorName("uint", "u", n);
            break;
        case SPVC_BASETYPE_INT16:
            name = vectorName("int16_t", "i16", n);
            break;
        case SPVC_BASETYPE_UINT16:
            name = vectorName("uint16_t", "u16", n);
            break;
        case SPVC_BASETYPE_INT8:
            name = vectorName("int8_t", "i8", n);
            break;
        case SPVC_BASETYPE_UINT8:
            name = vectorName("uint8_t", "u8", n);
            break;
        case SPVC_BASETYPE_INT64:
            name = vectorName("int64_t", "i64", n);
            break;
        case SPVC_BASETYPE_UINT64:
            name = vectorName("uint64_t", "u64", n);
            break;
        case SPVC_BASETYPE_BOOLEAN:
            name = vectorName("bool", "b", n);
            break;
        case SPVC_BASETYPE_STRUCT: {
            const char* s = spvc_compiler_get_name(compiler, spvc_type_get_base_type_id(type));
            name = s && *s ? s : "struct";
            break;
        }
        default:
            name = "unknown";
            break;
    }
    const uint32_t dims = spvc_type_get_num_array_dimensions(type);
    // SPIR-V lists the outermost dimension last; GLSL writes it first.
    for (uint32_t d = dims; d-- > 0;) {
        if (spvc_type_array_dimension_is_literal(type, d))
            name += "[" + std::to_string(spvc_type_get_array_dimension(type, d)) + "]";
        else
            name += "[]";
    }
    return name;
}

uint32_t arrayLength(spvc_compiler compiler, spvc_type_id typeId) {
    spvc_type type = spvc_compiler_get_type_handle(compiler, typeId);
    uint32_t length = 1;
    for (uint32_t d = 0; d < spvc_type_get_num_array_dimensions(type); ++d) {
        // Runtime-sized / spec-constant arrays: 0 tells ComputePipeline it cannot bind them.
        if (!spvc_type_array_dimension_is_literal(type, d)) return 0;
        length *= spvc_type_get_array_dimension(type, d);
    }
    return length;
}

const spvc_reflected_resource* resourceList(spvc_resources resources, spvc_resource_type type,
                                            size_t& count) {
    const spvc_reflected_resource* list = nullptr;
    count = 0;
    spvc_resources_get_resource_list_for_type(resources, type, &list, &count);
    return list;
}

}  // namespace

std::string descriptorKindName(DescriptorKind kind) {
    switch (kind) {
        case DescriptorKind::StorageImage:
            return "storage image";
        case DescriptorKind::SampledImage:
            return "sampled image";
        case DescriptorKind::StorageBuffer:
            return "storage buffer";
        case DescriptorKind::UniformBuffer:
            return "uniform buffer";
    }
    return "?";
}

vk::DescriptorType descriptorType(DescriptorKind kind) {
    switch (kind) {
        case DescriptorKind::StorageImage:
            return vk::DescriptorType::eStorageImage;
        case DescriptorKind::SampledImage:
            return vk::DescriptorType::eCombinedImageSampler;
        case DescriptorKind::StorageBuffer:
            return vk::DescriptorType::eStorageBuffer;
        case DescriptorKind::UniformBuffer:
            return vk::DescriptorType::eUniformBuffer;
    }
    return vk::DescriptorType::eStorageImage;
}

vk::Format formatFromSpirv(uint32_t f) {
    switch (static_cast<SpvImageFormat>(f)) {
        case SpvImageFormatRgba32f:
            return vk::Format::eR32G32B32A32Sfloat;
        case SpvImageFormatRgba16f:
            return vk::Format::eR16G16B16A16Sfloat;
        case SpvImageFormatR32f:
            return vk::Format::eR32Sfloat;
        case SpvImageFormatRgba8:
            return vk::Format::eR8G8B8A8Unorm;
        case SpvImageFormatRgba8Snorm:
            return vk::Format::eR8G8B8A8Snorm;
        case SpvImageFormatRg32f:
            return vk::Format::eR32G32Sfloat;
        case SpvImageFormatRg16f:
            return vk::Format::eR16G16Sfloat;
        case SpvImageFormatR11fG11fB10f:
            return vk::Format::eB10G11R11UfloatPack32;
        case SpvImageFormatR16f:
            return vk::Format::eR16Sfloat;
        case SpvImageFormatRgba16:
            return vk::Format::eR16G16B16A16Unorm;
        case SpvImageFormatRgb10A2:
            return vk::Format::eA2B10G10R10UnormPack32;
        case SpvImageFormatRg16:
            return vk::Format::eR16G16Unorm;
        case SpvImageFormatRg8:
            return vk::Format::eR8G8Unorm;
        case SpvImageFormatR16:
            return vk::Format::eR16Unorm;
        case SpvImageFormatR8:
            return vk::Format::eR8Unorm;
        case SpvImageFormatRgba16Snorm:
            return vk::Format::eR16G16B16A16Snorm;
        case SpvImageFormatRg16Snorm:
            return vk::Format::eR16G16Snorm;
        case SpvImageFormatRg8Snorm:
            return vk::Format::eR8G8Snorm;
        case SpvImageFormatR16Snorm:
            return vk::Format::eR16Snorm;
        case SpvImageFormatR8Snorm:
            return vk::Format::eR8Snorm;
        case SpvImageFormatRgba32i:
            return vk::Format::eR32G32B32A32Sint;
        case SpvImageFormatRgba16i:
            return vk::Format::eR16G16B16A16Sint;
        case SpvImageFormatRgba8i:
            return vk::Format::eR8G8B8A8Sint;
        case SpvImageFormatR32i:
            return vk::Format::eR32Sint;
        case SpvImageFormatRg32i:
            return vk::Format::eR32G32Sint;
        case SpvImageFormatRg16i:
            return vk::Format::eR16G16Sint;
        case SpvImageFormatRg8i:
            return vk::Format::eR8G8Sint;
        case SpvImageFormatR16i:
            return vk::Format::eR16Sint;
        case SpvImageFormatR8i:
            return vk::Format::eR8Sint;
        case SpvImageFormatRgba32ui:
            return vk::Format::eR32G32B32A32Uint;
        case SpvImageFormatRgba16ui:
            return vk::Format::eR16G16B16A16Uint;
        case SpvImageFormatRgba8ui:
            return vk::Format::eR8G8B8A8Uint;
        case SpvImageFormatR32ui:
            return vk::Format::eR32Uint;
        case SpvImageFormatRgb10a2ui:
            return vk::Format::eA2B10G10R10UintPack32;
        case SpvImageFormatRg32ui:
            return vk::Format::eR32G32Uint;
        case SpvImageFormatRg16ui:
            return vk::Format::eR16G16Uint;
        case SpvImageFormatRg8ui:
            return vk::Format::eR8G8Uint;
        case SpvImageFormatR16ui:
            return vk::Format::eR16Uint;
        case SpvImageFormatR8ui:
            return vk::Format::eR8Uint;
        case SpvImageFormatR64ui:
            return vk::Format::eR64Uint;
        case SpvImageFormatR64i:
            return vk::Format::eR64Sint;
        default:
            return vk::Format::eUndefined;
    }
}

const ShaderBinding* ShaderInterface::findBinding(std::string_view name) const {
    for (const auto& b : bindings)
        if (b.name == name) return &b;
    return nullptr;
}

const PushConstantMember* ShaderInterface::findPushConstant(std::string_view name) const {
    for (const auto& m : pushConstants)
        if (m.name == name) return &m;
    return nullptr;
}

std::vector<std::string> ShaderInterface::bindingNames() const {
    std::vector<std::string> names;
    for (const auto& b : bindings) names.push_back(b.name);
    return names;
}

std::vector<std::string> ShaderInterface::pushConstantNames() const {
    std::vector<std::string> names;
    for (const auto& m : pushConstants) names.push_back(m.name);
    return names;
}

namespace {

// One descriptor: set, binding, array size, name, access and (storage images) format.
ShaderBinding reflectBinding(spvc_compiler compiler, const spvc_reflected_resource& res,
                             DescriptorKind kind) {
    ShaderBinding b;
    b.kind = kind;
    b.set = spvc_compiler_get_decoration(compiler, res.id, SpvDecorationDescriptorSet);
    b.binding = spvc_compiler_get_decoration(compiler, res.id, SpvDecorationBinding);
    b.arraySize = arrayLength(compiler, res.type_id);
    const char* instance = spvc_compiler_get_name(compiler, res.id);
    b.name = instance && *instance ? instance : (res.name ? res.name : "");
    const bool isBuffer =
        kind == DescriptorKind::StorageBuffer || kind == DescriptorKind::UniformBuffer;
    if (isBuffer) {
        if (b.name.empty()) {
            const char* block = spvc_compiler_get_name(compiler, res.base_type_id);
            b.name = block ? block : "";
        }
        const SpvDecoration* decorations = nullptr;
        size_t numDecorations = 0;
        spvc_compiler_get_buffer_block_decorations(compiler, res.id, &decorations, &numDecorations);
        for (size_t d = 0; d < numDecorations; ++d) {
            if (decorations[d] == SpvDecorationNonWritable) b.readonly = true;
            if (decorations[d] == SpvDecorationNonReadable) b.writeonly = true;
        }
        b.readonly = b.readonly || kind == DescriptorKind::UniformBuffer;
        return b;
    }
    b.readonly = spvc_compiler_has_decoration(compiler, res.id, SpvDecorationNonWritable) ||
                 kind == DescriptorKind::SampledImage;
    b.writeonly = spvc_compiler_has_decoration(compiler, res.id, SpvDecorationNonReadable);
    spvc_type type = spvc_compiler_get_type_handle(compiler, res.base_type_id);
    if (spvc_type_get_image_dimension(type) == SpvDimBuffer)
        throw RuntimeError("shader reflection: '" + b.name +
                           "' is a texel buffer, which fovea cannot bind");
    if (kind == DescriptorKind::StorageImage)
        b.imageFormat = formatFromSpirv(spvc_type_get_image_storage_format(type));
    return b;
}

// Every descriptor fovea binds, sorted by (set, binding); a kind it cannot bind is an error.
std::vector<ShaderBinding> reflectBindings(spvc_compiler compiler, spvc_resources resources) {
    std::vector<ShaderBinding> bindings;
    const std::pair<spvc_resource_type, DescriptorKind> kinds[] = {
        {SPVC_RESOURCE_TYPE_STORAGE_IMAGE, DescriptorKind::StorageImage},
        {SPVC_RESOURCE_TYPE_SAMPLED_IMAGE, DescriptorKind::SampledImage},
        {SPVC_RESOURCE_TYPE_STORAGE_BUFFER, DescriptorKind::StorageBuffer},
        {SPVC_RESOURCE_TYPE_UNIFORM_BUFFER, DescriptorKind::UniformBuffer},
    };
    for (auto [type, kind] : kinds) {
        size_t count = 0;
        const spvc_reflected_resource* list = resourceList(resources, type, count);
        for (size_t r = 0; r < count; ++r)
            bindings.push_back(reflectBinding(compiler, list[r], kind));
    }
    const std::pair<spvc_resource_type, const char*> unsupported[] = {
        {SPVC_RESOURCE_TYPE_SEPARATE_IMAGE, "separate texture (use a combined sampler2D)"},
        {SPVC_RESOURCE_TYPE_SEPARATE_SAMPLERS, "separate sampler (use a combined sampler2D)"},
        {SPVC_RESOURCE_TYPE_ACCELERATION_STRUCTURE, "acceleration structure"},
        {SPVC_RESOURCE_TYPE_ATOMIC_COUNTER, "atomic counter"},
    };
    for (auto [type, what] : unsupported) {
        size_t count = 0;
        const spvc_reflected_resource* list = resourceList(resources, type, count);
        if (count > 0)
            throw RuntimeError("shader reflection: '" +
                               std::string(list[0].name ? list[0].name : "") + "' is a " + what +
                               ", which fovea cannot bind");
    }
    std::sort(bindings.begin(), bindings.end(), [](const auto& a, const auto& b) {
        return std::tie(a.set, a.binding) < std::tie(b.set, b.binding);
    });
    return bindings;
}

// The push-constant block's size and members (name, offset, size, GLSL type), if any.
void reflectPushConstants(spvc_compiler compiler, spvc_resources resources, ShaderInterface& out) {
    size_t pushCount = 0;
    const spvc_reflected_resource* push =
        resourceList(resources, SPVC_RESOURCE_TYPE_PUSH_CONSTANT, pushCount);
    if (pushCount == 0) return;
    spvc_type block = spvc_compiler_get_type_handle(compiler, push[0].base_type_id);
    size_t blockSize = 0;
    spvc_compiler_get_declared_struct_size(compiler, block, &blockSize);
    out.pushConstantSize = static_cast<uint32_t>(blockSize);
    for (uint32_t m = 0; m < spvc_type_get_num_member_types(block); ++m) {
        PushConstantMember member;
        const char* name = spvc_compiler_get_member_name(compiler, push[0].base_type_id, m);
        member.name = name ? name : "";
        unsigned offset = 0;
        spvc_compiler_type_struct_member_offset(compiler, block, m, &offset);
        size_t size = 0;
        spvc_compiler_get_declared_struct_member_size(compiler, block, m, &size);
        member.offset = offset;
        member.size = static_cast<uint32_t>(size);
        member.typeName = glslTypeName(compiler, spvc_type_get_member_type(block, m));
        out.pushConstants.push_back(std::move(member));
    }
}

}  // namespace

ShaderInterface reflectShader(const std::vector<uint32_t>& spirv) {
    spvc_context rawContext = nullptr;
    if (spvc_context_create(&rawContext) != SPVC_SUCCESS)
        throw RuntimeError("spirv-cross: cannot create a context");
    ContextPtr context(rawContext, &spvc_context_destroy);
    auto fail = [&](const std::string& what) {
        return RuntimeError("shader reflection: " + what + ": " +
                            spvc_context_get_last_error_string(context.get()));
    };
    spvc_parsed_ir ir = nullptr;
    if (spvc_context_parse_spirv(context.get(), spirv.data(), spirv.size(), &ir) != SPVC_SUCCESS)
        throw fail("invalid SPIR-V");
    spvc_compiler compiler = nullptr;
    if (spvc_context_create_compiler(context.get(), SPVC_BACKEND_NONE, ir,
                                     SPVC_CAPTURE_MODE_TAKE_OWNERSHIP, &compiler) != SPVC_SUCCESS)
        throw fail("cannot create a compiler");
    spvc_resources resources = nullptr;
    if (spvc_compiler_create_shader_resources(compiler, &resources) != SPVC_SUCCESS)
        throw fail("cannot list resources");

    ShaderInterface out;
    for (uint32_t i = 0; i < 3; ++i)
        out.localSize[i] = std::max(1u, spvc_compiler_get_execution_mode_argument_by_index(
                                            compiler, SpvExecutionModeLocalSize, i));
    out.bindings = reflectBindings(compiler, resources);
    reflectPushConstants(compiler, resources, out);
    return out;
}

}  // namespace fovea::gpu
