// The Vulkan instance + device + queue fovea computes on, plus the few shared objects every pass
// needs (one-shot submits, samplers, the shader compiler, validation message capture).
#pragma once
#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <type_traits>
#include <vector>
#include <vulkan/vulkan_raii.hpp>

namespace fovea::gpu {

class ShaderCompiler;

struct ContextOptions {
    // "" = default (first discrete GPU, else integrated, else virtual, else CPU/lavapipe), an
    // index into listDevices() ("0"), or a case-insensitive substring of the device name.
    std::string device;
    // Khronos validation layer. Env FOVEA_VALIDATION=1 forces it on. Validation always includes
    // synchronization validation unless FOVEA_SYNC_VALIDATION=0.
    bool validation = false;
    // Forces validation (with synchronization validation) on; env FOVEA_SYNC_VALIDATION=1 too.
    bool syncValidation = false;
    // Presentation (the inspector's window): extra instance extensions (the surface extensions
    // the window system asks for) and VK_KHR_swapchain on the device. Empty/false for headless.
    std::vector<std::string> instanceExtensions{};
    bool swapchain = false;
    // Non-zero: limits().maxStorageBufferRange is at most this many bytes, as on a smaller
    // device (how the tests check that a scene too large for the device is a clear error).
    uint64_t storageBufferRangeCap = 0;
};

// Optional device features that were available and are enabled (shaders may rely on these only
// after checking; synchronization2 and push descriptors are always there).
struct DeviceFeatures {
    bool shaderFloat16 = false;
    bool shaderInt8 = false;
    bool shaderInt16 = false;
    bool shaderInt64 = false;
    bool shaderFloat64 = false;
    bool storage16Bit = false;  // storageBuffer16BitAccess
    bool storage8Bit = false;   // storageBuffer8BitAccess
    bool bufferDeviceAddress = false;
    bool scalarBlockLayout = false;
    bool storageImageReadWithoutFormat = false;
    bool storageImageWriteWithoutFormat = false;
};

class Context {
public:
    // Throws RuntimeError: no Vulkan loader, no suitable device, no device matches
    // options.device (the message lists the available devices).
    explicit Context(const ContextOptions& options = {});
    ~Context();
    // Not movable: the validation callback and every resource keep pointers into the context.
    Context(const Context&) = delete;
    Context& operator=(const Context&) = delete;

    // "0: llvmpipe (LLVM 15.0.6, 256 bits) [cpu]"; unsuitable devices carry a "(unsuitable: ...)"
    // suffix. Throws RuntimeError when there is no Vulkan loader.
    static std::vector<std::string> listDevices();

    const vk::raii::Instance& instance() const { return mInstance; }
    const vk::raii::Device& device() const { return mDevice; }
    const vk::raii::PhysicalDevice& physicalDevice() const { return mPhysicalDevice; }
    const vk::raii::Queue& queue() const { return mQueue; }
    uint32_t queueFamily() const { return mQueueFamily; }
    const vk::PhysicalDeviceProperties& properties() const { return mProperties; }
    const vk::PhysicalDeviceLimits& limits() const { return mProperties.limits; }
    // The largest single memory allocation (Vulkan 1.1 maxMemoryAllocationSize): the bound on a
    // buffer read through its device address.
    uint64_t maxAllocationBytes() const { return mMaxAllocationBytes; }
    const DeviceFeatures& features() const { return mFeatures; }

    std::string deviceName() const;
    std::string driverName() const { return mDriverName; }
    std::string driverInfo() const { return mDriverInfo; }
    std::string deviceTypeName() const;  // "cpu", "discrete", "integrated", "virtual", "other"
    double timestampPeriodNs() const { return mProperties.limits.timestampPeriod; }
    bool validationEnabled() const { return mValidation; }
    bool syncValidationEnabled() const { return mSyncValidation; }
    bool debugUtilsEnabled() const { return mDebugUtils; }

    // Validation WARNING and ERROR messages (general + validation types; performance hints are
    // not counted) since construction or the last clear. Each is also printed to stderr.
    size_t validationMessageCount() const;
    std::vector<std::string> validationMessages() const;
    void clearValidationMessages();

    // Records into a fresh primary command buffer from an internal pool, submits it and waits
    // on a fence. Thread-safe (serialised with submit()).
    void submitAndWait(const std::function<void(const vk::raii::CommandBuffer&)>& record) const;
    // Queue submission guarded by the same lock, for callers that record their own buffers.
    void submit(const vk::SubmitInfo2& info, vk::Fence fence) const;

    // Throws RuntimeError when no memory type matches.
    uint32_t findMemoryType(uint32_t typeBits, vk::MemoryPropertyFlags props) const;

    ShaderCompiler& shaderCompiler() { return *mShaderCompiler; }

    const vk::raii::Sampler& linearClampSampler() const { return mLinearClamp; }
    const vk::raii::Sampler& nearestClampSampler() const { return mNearestClamp; }

    // Debug-utils object names (visible in validation messages and RenderDoc). No-op when the
    // extension is off or the name is empty.
    void setObjectName(vk::ObjectType type, uint64_t handle, const std::string& name) const;
    template <class Handle>
    void setObjectName(Handle handle, const std::string& name) const {
        using CType = typename Handle::CType;
        auto raw = static_cast<CType>(handle);
        uint64_t bits;
        if constexpr (std::is_pointer_v<CType>) {
            bits = reinterpret_cast<uint64_t>(raw);
        } else {
            bits = static_cast<uint64_t>(raw);
        }
        setObjectName(Handle::objectType, bits, name);
    }

    // How many device memory allocations (vkAllocateMemory) this context has made so far,
    // counted by core/vk/Resources.cpp. The render graph compares it around each pass's compile
    // and execute to find memory a pass allocates outside the plan (report.json).
    uint64_t allocationCount() const { return mAllocations.load(std::memory_order_relaxed); }
    void countAllocation() const { mAllocations.fetch_add(1, std::memory_order_relaxed); }

private:
    struct MessageSink {
        mutable std::mutex mutex;
        std::vector<std::string> messages;
    };
    // The layers and extensions the instance is created with. The names point at constants or
    // into ContextOptions::instanceExtensions, both of which outlive instance creation.
    struct InstanceLayersAndExtensions {
        std::vector<const char*> layers;
        std::vector<const char*> extensions;
    };
    static VKAPI_ATTR VkBool32 VKAPI_CALL onDebugMessage(
        VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT types,
        const VkDebugUtilsMessengerCallbackDataEXT* data, void* userData);

    // Construction stages, in the order the constructor runs them. Each fills the members it
    // names; later stages rely on the members earlier ones set.
    // Sets mValidation/mSyncValidation from the options and the FOVEA_*VALIDATION env switches.
    void resolveValidationSwitches(const ContextOptions& options);
    // Also sets mDebugUtils.
    InstanceLayersAndExtensions chooseInstanceLayersAndExtensions(const ContextOptions& options);
    // Turns validation off when the layer (or debug utils) is missing, and sync validation off
    // when the layer lacks VK_EXT_validation_features.
    void addValidationLayer(InstanceLayersAndExtensions& enabled);
    // Creates mInstance and, with validation, mMessenger.
    void createInstance(const InstanceLayersAndExtensions& enabled);
    // Sets mPhysicalDevice, mProperties, the driver strings and mQueueFamily.
    void pickPhysicalDevice(const std::string& spec);
    std::vector<const char*> chooseDeviceExtensions(bool swapchain) const;
    // Creates mDevice with the supported optional features (recorded in mFeatures) and mQueue.
    void createDevice(const ContextOptions& options);
    // The command pool, samplers and shader compiler every pass shares.
    void createSharedObjects();

    // Declaration order is destruction order (reverse): the loader context outlives everything.
    std::unique_ptr<MessageSink> mSink;
    vk::raii::Context mVkContext;
    vk::raii::Instance mInstance = nullptr;
    vk::raii::DebugUtilsMessengerEXT mMessenger = nullptr;
    vk::raii::PhysicalDevice mPhysicalDevice = nullptr;
    vk::raii::Device mDevice = nullptr;
    vk::raii::Queue mQueue = nullptr;
    vk::raii::CommandPool mCommandPool = nullptr;
    vk::raii::Sampler mLinearClamp = nullptr;
    vk::raii::Sampler mNearestClamp = nullptr;
    std::unique_ptr<ShaderCompiler> mShaderCompiler;
    mutable std::recursive_mutex mSubmitMutex;  // guards the queue and the command pool
    uint32_t mQueueFamily = 0;
    vk::PhysicalDeviceProperties mProperties;
    uint64_t mMaxAllocationBytes = 0;
    std::string mDriverName;
    std::string mDriverInfo;
    DeviceFeatures mFeatures;
    bool mValidation = false;
    bool mSyncValidation = false;
    bool mDebugUtils = false;
    mutable std::atomic<uint64_t> mAllocations{0};
};

}  // namespace fovea::gpu
