// What a compiled compute shader expects: descriptors, push-constant members, workgroup size.
// Read from SPIR-V with spirv-cross, so pass code never repeats binding numbers by hand.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>
#include <vulkan/vulkan.hpp>

namespace fovea::gpu {

enum class DescriptorKind {
    StorageImage,
    SampledImage,  // combined image sampler
    StorageBuffer,
    UniformBuffer,
};

// "storage image", "sampled image", "storage buffer", "uniform buffer".
std::string descriptorKindName(DescriptorKind kind);
vk::DescriptorType descriptorType(DescriptorKind kind);

struct ShaderBinding {
    // Buffers: the block instance name if it has one, else the block type name. Images: the
    // variable name.
    std::string name;
    uint32_t set = 0, binding = 0;
    DescriptorKind kind = DescriptorKind::StorageImage;
    // Storage images: the layout format qualifier; eUndefined when the shader declares none.
    vk::Format imageFormat = vk::Format::eUndefined;
    bool readonly = false, writeonly = false;
    uint32_t arraySize = 1;  // descriptor array length (1 = not an array)
};

struct PushConstantMember {
    std::string name;
    uint32_t offset = 0, size = 0;
    // GLSL spelling: "float", "int", "uint", "vec2", "ivec2", "uvec2", "vec3", "vec4", "mat4",
    // "mat3x4", "float16_t", "bool", "float[4]", or the struct name.
    std::string typeName;
};

struct ShaderInterface {
    std::vector<ShaderBinding> bindings;  // sorted by (set, binding)
    std::vector<PushConstantMember> pushConstants;
    uint32_t pushConstantSize = 0;  // bytes up to the end of the last member
    std::array<uint32_t, 3> localSize{1, 1, 1};

    const ShaderBinding* findBinding(std::string_view name) const;
    const PushConstantMember* findPushConstant(std::string_view name) const;
    std::vector<std::string> bindingNames() const;
    std::vector<std::string> pushConstantNames() const;
};

// Throws RuntimeError for invalid SPIR-V or resources fovea cannot bind (separate samplers or
// images, texel buffers, acceleration structures).
ShaderInterface reflectShader(const std::vector<uint32_t>& spirv);

// SPIR-V image format -> Vulkan format (eUndefined for Unknown).
vk::Format formatFromSpirv(uint32_t spvImageFormat);

}  // namespace fovea::gpu
