// One compute shader as a pipeline: set 0 via push descriptors, push constants by member name.
// Resources are staged by name (bind/set) and recorded with dispatch(); staged state persists
// across dispatches, so a pass only re-binds what changed.
#pragma once
#include <array>
#include <cstdint>
#include <glm/fwd.hpp>
#include <memory>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>
#include <vulkan/vulkan_raii.hpp>

#include "core/vk/ShaderCompiler.h"
#include "core/vk/ShaderReflection.h"

namespace fovea::gpu {

class Context;
class Image;
class Buffer;

// One resource a dispatch touches through a staged binding: what DispatchHazards compares to
// derive the barrier between two dispatches. `handle` is the VkImageView or VkBuffer (images and
// buffers apart: handles of different types may share a value).
struct ResourceAccess {
    uint64_t handle = 0;
    bool image = false;
    bool read = false, write = false;
};

class ComputePipeline {
public:
    // Compiles (through the context's cached compiler), reflects and creates the pipeline.
    // Throws RuntimeError on compile errors or when the shader uses a set other than 0,
    // descriptor arrays, or more bindings than the device can push.
    ComputePipeline(Context& context, const std::string& shaderPath,
                    const ShaderDefines& defines = {});
    ComputePipeline(const ComputePipeline&) = delete;
    ComputePipeline& operator=(const ComputePipeline&) = delete;

    // Another pipeline object on the same compiled Vulkan objects (no compile, no driver call),
    // with its own staged bindings and push constants: how RenderGraph reuses pipelines when a
    // parameter edit re-runs a pass's compile() with unchanged shaders and defines.
    std::unique_ptr<ComputePipeline> share() const;

private:
    struct ShareTag {};

public:
    ComputePipeline(const ComputePipeline& other, ShareTag);  // for share() only (private tag)

    const ShaderInterface& interface() const { return mInterface; }
    const std::string& shaderPath() const { return mShaderPath; }
    bool hasBinding(std::string_view name) const { return mInterface.findBinding(name) != nullptr; }
    bool hasPushConstant(std::string_view member) const {
        return mInterface.findPushConstant(member) != nullptr;
    }
    vk::Pipeline pipeline() const { return *mObjects->pipeline; }
    vk::PipelineLayout layout() const { return *mObjects->layout; }

    // Stage a resource for the next dispatch. Throws RuntimeError for an unknown name (with
    // did-you-mean), the wrong kind (Image vs Buffer), a missing usage flag, or a storage image
    // whose format differs from the shader's format qualifier. Sampled images use the context's
    // linear clamp sampler (nearest for formats without linear filtering); bindNearest forces
    // the nearest sampler. All images are expected in GENERAL layout.
    ComputePipeline& bind(std::string_view name, const Image& image);
    ComputePipeline& bindNearest(std::string_view name, const Image& image);
    ComputePipeline& bind(std::string_view name, const Buffer& buffer);

    // Push constant by member name. sizeof(T) must equal the member's size, and a float value
    // cannot go into an int member or vice versa (checked for arithmetic and glm types).
    // Members never set are zero.
    template <class T>
    ComputePipeline& set(std::string_view member, const T& value) {
        static_assert(std::is_trivially_copyable_v<T>, "push constants are copied bytewise");
        return setBytes(member, &value, sizeof(T), scalarClass<T>());
    }
    // Untyped variant: only the size is checked.
    ComputePipeline& setBytes(std::string_view member, const void* data, size_t size);

    // Records bind pipeline + push descriptors + push constants + dispatch of
    // ceil(threads / localSize) groups. Throws RuntimeError if any declared binding was never
    // bound. Records no barriers: ordering against other work is the caller's job.
    void dispatch(const vk::raii::CommandBuffer& cmd, uint32_t threadsX, uint32_t threadsY = 1,
                  uint32_t threadsZ = 1);
    // Same, with the group counts read by the GPU from `args` at `offset` (3 x uint32,
    // VkDispatchIndirectCommand); the buffer needs INDIRECT usage. A zero count records nothing
    // that runs: how a pass skips work the GPU decided is not needed (no read-back).
    void dispatchIndirect(const vk::raii::CommandBuffer& cmd, const Buffer& args,
                          vk::DeviceSize offset = 0);
    // The resources the next dispatch touches: sampled images and uniform buffers are read;
    // storage images and buffers are read unless `writeonly` and written unless `readonly` (the
    // shader's qualifiers, as reflected). Unbound bindings are left out (dispatch throws).
    std::vector<ResourceAccess> accesses() const;
    std::array<uint32_t, 3> groupCount(uint32_t threadsX, uint32_t threadsY = 1,
                                       uint32_t threadsZ = 1) const;

private:
    void recordState(const vk::raii::CommandBuffer& cmd);  // pipeline, descriptors, constants
    enum class ScalarClass { Float, Integer, Other };
    template <class T>
    struct ScalarOf {
        using type = T;
    };
    template <glm::length_t L, class U, glm::qualifier Q>
    struct ScalarOf<glm::vec<L, U, Q>> {
        using type = U;
    };
    template <glm::length_t C, glm::length_t R, class U, glm::qualifier Q>
    struct ScalarOf<glm::mat<C, R, U, Q>> {
        using type = U;
    };
    template <class T>
    static constexpr ScalarClass scalarClass() {
        using S = typename ScalarOf<T>::type;
        if constexpr (std::is_floating_point_v<S>) return ScalarClass::Float;
        if constexpr (std::is_integral_v<S>) return ScalarClass::Integer;
        return ScalarClass::Other;
    }

    struct Staged {
        bool bound = false;
        vk::DescriptorImageInfo image;
        vk::DescriptorBufferInfo buffer;
    };

    ComputePipeline& setBytes(std::string_view member, const void* data, size_t size,
                              ScalarClass valueClass);
    size_t bindingIndex(std::string_view name) const;
    ComputePipeline& bindImage(std::string_view name, const Image& image, bool nearest);
    std::string label() const { return "shader '" + mShaderPath + "'"; }

    struct Objects {  // immutable once created; shared by share()
        vk::raii::DescriptorSetLayout setLayout = nullptr;
        vk::raii::PipelineLayout layout = nullptr;
        vk::raii::Pipeline pipeline = nullptr;
    };
    const Context& mContext;
    std::string mShaderPath;
    ShaderInterface mInterface;
    std::shared_ptr<const Objects> mObjects;
    std::vector<Staged> mStaged;  // parallel to mInterface.bindings
    std::vector<uint8_t> mPushData;
};

}  // namespace fovea::gpu
