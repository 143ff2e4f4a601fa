#include "core/vk/Context.h"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <optional>

#include "core/util/Error.h"
#include "core/util/InstallPaths.h"
#include "core/vk/ShaderCompiler.h"

namespace fovea::gpu {
namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";
constexpr uint32_t kApiVersion = VK_API_VERSION_1_3;

// Env switches: unset -> nullopt; "0", "false" or "" -> false; anything else -> true.
std::optional<bool> envSwitch(const char* name) {
    const char* value = std::getenv(name);
    if (!value) return std::nullopt;
    const std::string v = value;
    return !(v.empty() || v == "0" || v == "false");
}

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return s;
}

std::string typeName(vk::PhysicalDeviceType type) {
    switch (type) {
        case vk::PhysicalDeviceType::eCpu:
            return "cpu";
        case vk::PhysicalDeviceType::eDiscreteGpu:
            return "discrete";
        case vk::PhysicalDeviceType::eIntegratedGpu:
            return "integrated";
        case vk::PhysicalDeviceType::eVirtualGpu:
            return "virtual";
        default:
            return "other";
    }
}

// Lower is preferred by the default device choice.
int typeRank(vk::PhysicalDeviceType type) {
    switch (type) {
        case vk::PhysicalDeviceType::eDiscreteGpu:
            return 0;
        case vk::PhysicalDeviceType::eIntegratedGpu:
            return 1;
        case vk::PhysicalDeviceType::eVirtualGpu:
            return 2;
        case vk::PhysicalDeviceType::eCpu:
            return 3;
        default:
            return 4;
    }
}

bool hasExtension(const std::vector<vk::ExtensionProperties>& list, const char* name) {
    return std::any_of(list.begin(), list.end(), [&](const vk::ExtensionProperties& e) {
        return std::string_view(e.extensionName.data()) == name;
    });
}

vk::raii::Context makeLoaderContext() {
    try {
        return vk::raii::Context();
    } catch (const std::exception& e) {
        throw RuntimeError(std::string("cannot load the Vulkan loader (libvulkan.so.1): ") +
                           e.what() + "; install libvulkan1 and a Vulkan driver");
    }
}

// The queue family fovea submits to: compute with timestamps, preferring a universal family
// (graphics+compute) because those are the most robust on every vendor.
std::optional<uint32_t> pickQueueFamily(const vk::raii::PhysicalDevice& pd) {
    auto families = pd.getQueueFamilyProperties();
    std::optional<uint32_t> best;
    int bestScore = -1;
    for (uint32_t i = 0; i < families.size(); ++i) {
        const auto& f = families[i];
        if (!(f.queueFlags & vk::QueueFlagBits::eCompute)) continue;
        int score = (f.timestampValidBits > 0 ? 2 : 0) +
                    ((f.queueFlags & vk::QueueFlagBits::eGraphics) ? 1 : 0);
        if (score > bestScore) {
            best = i;
            bestScore = score;
        }
    }
    return best;
}

// Why a device cannot run fovea, or "" if it can.
std::string unsuitableReason(const vk::raii::PhysicalDevice& pd) {
    auto props = pd.getProperties();
    if (props.apiVersion < kApiVersion) return "needs Vulkan 1.3";
    if (!hasExtension(pd.enumerateDeviceExtensionProperties(),
                      VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME))
        return "no VK_KHR_push_descriptor";
    if (!pickQueueFamily(pd)) return "no compute queue";
    auto features =
        pd.getFeatures2<vk::PhysicalDeviceFeatures2, vk::PhysicalDeviceVulkan13Features>();
    const auto& f13 = features.get<vk::PhysicalDeviceVulkan13Features>();
    if (!f13.synchronization2) return "no synchronization2";
    if (!f13.maintenance4) return "no maintenance4";
    return "";
}

std::string describe(size_t index, const vk::raii::PhysicalDevice& pd) {
    auto props = pd.getProperties();
    std::string line = std::to_string(index) + ": " + std::string(props.deviceName.data()) + " [" +
                       typeName(props.deviceType) + "]";
    std::string reason = unsuitableReason(pd);
    if (!reason.empty()) line += " (unsuitable: " + reason + ")";
    return line;
}

bool allDigits(const std::string& s) {
    return !s.empty() &&
           std::all_of(s.begin(), s.end(), [](unsigned char c) { return std::isdigit(c); });
}

std::string joinLines(const std::vector<std::string>& lines) {
    std::string out;
    for (const auto& l : lines) out += "\n  " + l;
    return out;
}

// Picks the physical device named by `spec` (see ContextOptions::device).
vk::raii::PhysicalDevice selectDevice(const vk::raii::Instance& instance, const std::string& spec) {
    vk::raii::PhysicalDevices devices(instance);
    std::vector<std::string> listing;
    for (size_t i = 0; i < devices.size(); ++i) listing.push_back(describe(i, devices[i]));
    if (devices.empty())
        throw RuntimeError("no Vulkan devices found (is a Vulkan driver installed?)");

    auto fail = [&](const std::string& why) -> RuntimeError {
        return RuntimeError(why + "; available devices:" + joinLines(listing));
    };
    if (spec.empty()) {
        std::optional<size_t> best;
        for (size_t i = 0; i < devices.size(); ++i) {
            if (!unsuitableReason(devices[i]).empty()) continue;
            if (!best || typeRank(devices[i].getProperties().deviceType) <
                             typeRank(devices[*best].getProperties().deviceType))
                best = i;
        }
        if (!best) throw fail("no Vulkan device supports what fovea needs");
        return std::move(devices[*best]);
    }
    if (allDigits(spec)) {
        size_t index = std::stoul(spec);
        if (index >= devices.size()) throw fail("no Vulkan device with index " + spec);
        std::string reason = unsuitableReason(devices[index]);
        if (!reason.empty()) throw fail("Vulkan device " + spec + " is unsuitable: " + reason);
        return std::move(devices[index]);
    }
    std::string reason;
    for (size_t i = 0; i < devices.size(); ++i) {
        std::string name = devices[i].getProperties().deviceName.data();
        if (lower(name).find(lower(spec)) == std::string::npos) continue;
        reason = unsuitableReason(devices[i]);
        if (reason.empty()) return std::move(devices[i]);
    }
    if (!reason.empty())
        throw fail("Vulkan device matching '" + spec + "' is unsuitable: " + reason);
    throw fail("no Vulkan device matches '" + spec + "'");
}

std::filesystem::path defaultShaderCacheDir() {
    if (const char* dir = std::getenv("FOVEA_SHADER_CACHE")) return dir;  // "" disables it
    if (const char* home = std::getenv("HOME"); home && *home)
        return std::filesystem::path(home) / ".cache" / "fovea" / "shaders";
    return {};
}

vk::raii::Sampler makeSampler(const vk::raii::Device& device, vk::Filter filter) {
    vk::SamplerMipmapMode mip = filter == vk::Filter::eLinear ? vk::SamplerMipmapMode::eLinear
                                                              : vk::SamplerMipmapMode::eNearest;
    return vk::raii::Sampler(device, vk::SamplerCreateInfo{
                                         .magFilter = filter,
                                         .minFilter = filter,
                                         .mipmapMode = mip,
                                         .addressModeU = vk::SamplerAddressMode::eClampToEdge,
                                         .addressModeV = vk::SamplerAddressMode::eClampToEdge,
                                         .addressModeW = vk::SamplerAddressMode::eClampToEdge,
                                         .maxLod = VK_LOD_CLAMP_NONE,
                                     });
}

// The device create info with every feature struct fovea enables chained behind it.
using DeviceCreateChain =
    vk::StructureChain<vk::DeviceCreateInfo, vk::PhysicalDeviceFeatures2,
                       vk::PhysicalDeviceVulkan11Features, vk::PhysicalDeviceVulkan12Features,
                       vk::PhysicalDeviceVulkan13Features>;

// Only features that are both useful to passes and supported; sync2 and maintenance4 are
// required by device selection.
void enableSupportedFeatures(const vk::raii::PhysicalDevice& pd, DeviceCreateChain& chain) {
    auto supported =
        pd.getFeatures2<vk::PhysicalDeviceFeatures2, vk::PhysicalDeviceVulkan11Features,
                        vk::PhysicalDeviceVulkan12Features, vk::PhysicalDeviceVulkan13Features>();
    const auto& s10 = supported.get<vk::PhysicalDeviceFeatures2>().features;
    const auto& s11 = supported.get<vk::PhysicalDeviceVulkan11Features>();
    const auto& s12 = supported.get<vk::PhysicalDeviceVulkan12Features>();

    auto& f10 = chain.get<vk::PhysicalDeviceFeatures2>().features;
    f10.shaderInt16 = s10.shaderInt16;
    f10.shaderInt64 = s10.shaderInt64;
    f10.shaderFloat64 = s10.shaderFloat64;
    f10.shaderStorageImageExtendedFormats = s10.shaderStorageImageExtendedFormats;
    f10.shaderStorageImageReadWithoutFormat = s10.shaderStorageImageReadWithoutFormat;
    f10.shaderStorageImageWriteWithoutFormat = s10.shaderStorageImageWriteWithoutFormat;
    auto& f11 = chain.get<vk::PhysicalDeviceVulkan11Features>();
    f11.storageBuffer16BitAccess = s11.storageBuffer16BitAccess;
    f11.uniformAndStorageBuffer16BitAccess = s11.uniformAndStorageBuffer16BitAccess;
    auto& f12 = chain.get<vk::PhysicalDeviceVulkan12Features>();
    f12.shaderFloat16 = s12.shaderFloat16;
    f12.shaderInt8 = s12.shaderInt8;
    f12.storageBuffer8BitAccess = s12.storageBuffer8BitAccess;
    f12.uniformAndStorageBuffer8BitAccess = s12.uniformAndStorageBuffer8BitAccess;
    f12.bufferDeviceAddress = s12.bufferDeviceAddress;
    f12.scalarBlockLayout = s12.scalarBlockLayout;
    f12.hostQueryReset = s12.hostQueryReset;
    f12.timelineSemaphore = s12.timelineSemaphore;
    auto& f13 = chain.get<vk::PhysicalDeviceVulkan13Features>();
    f13.synchronization2 = VK_TRUE;
    // glslang's SPIR-V 1.6 output declares the workgroup size with LocalSizeId, which needs
    // maintenance4 (mandatory in Vulkan 1.3; device selection checks it).
    f13.maintenance4 = VK_TRUE;
}

// What Context::features() reports: the optional features enabled in `chain`.
DeviceFeatures enabledFeatures(const DeviceCreateChain& chain) {
    const auto& f10 = chain.get<vk::PhysicalDeviceFeatures2>().features;
    const auto& f11 = chain.get<vk::PhysicalDeviceVulkan11Features>();
    const auto& f12 = chain.get<vk::PhysicalDeviceVulkan12Features>();
    return DeviceFeatures{
        .shaderFloat16 = bool(f12.shaderFloat16),
        .shaderInt8 = bool(f12.shaderInt8),
        .shaderInt16 = bool(f10.shaderInt16),
        .shaderInt64 = bool(f10.shaderInt64),
        .shaderFloat64 = bool(f10.shaderFloat64),
        .storage16Bit = bool(f11.storageBuffer16BitAccess),
        .storage8Bit = bool(f12.storageBuffer8BitAccess),
        .bufferDeviceAddress = bool(f12.bufferDeviceAddress),
        .scalarBlockLayout = bool(f12.scalarBlockLayout),
        .storageImageReadWithoutFormat = bool(f10.shaderStorageImageReadWithoutFormat),
        .storageImageWriteWithoutFormat = bool(f10.shaderStorageImageWriteWithoutFormat),
    };
}

}  // namespace

Context::Context(const ContextOptions& options)
    : mSink(std::make_unique<MessageSink>()), mVkContext(makeLoaderContext()) {
    resolveValidationSwitches(options);
    createInstance(chooseInstanceLayersAndExtensions(options));
    pickPhysicalDevice(options.device);
    if (options.storageBufferRangeCap != 0)
        mProperties.limits.maxStorageBufferRange = uint32_t(std::min<uint64_t>(
            mProperties.limits.maxStorageBufferRange, options.storageBufferRangeCap));
    createDevice(options);
    createSharedObjects();
}

void Context::resolveValidationSwitches(const ContextOptions& options) {
    const std::optional<bool> envValidation = envSwitch("FOVEA_VALIDATION");
    const std::optional<bool> envSync = envSwitch("FOVEA_SYNC_VALIDATION");
    mValidation = options.validation || options.syncValidation || envValidation.value_or(false) ||
                  envSync.value_or(false);
    mSyncValidation = mValidation && envSync.value_or(true);
}

Context::InstanceLayersAndExtensions Context::chooseInstanceLayersAndExtensions(
    const ContextOptions& options) {
    InstanceLayersAndExtensions enabled;
    auto instanceExtensions = mVkContext.enumerateInstanceExtensionProperties();
    mDebugUtils = hasExtension(instanceExtensions, VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    if (mDebugUtils) enabled.extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    for (const std::string& name : options.instanceExtensions) {
        if (!hasExtension(instanceExtensions, name.c_str()))
            throw RuntimeError("the Vulkan instance lacks extension " + name +
                               " (needed to present to a window)");
        enabled.extensions.push_back(name.c_str());
    }
    if (mValidation) addValidationLayer(enabled);
    return enabled;
}

void Context::addValidationLayer(InstanceLayersAndExtensions& enabled) {
    auto available = mVkContext.enumerateInstanceLayerProperties();
    bool found = std::any_of(available.begin(), available.end(), [](const vk::LayerProperties& l) {
        return std::string_view(l.layerName.data()) == kValidationLayer;
    });
    if (!found || !mDebugUtils) {
        // A missing layer should not stop a render; tests notice via validationEnabled().
        std::cerr << "fovea: warning: validation requested but " << kValidationLayer
                  << " is not installed (apt install vulkan-validationlayers); continuing "
                     "without validation\n";
        mValidation = mSyncValidation = false;
        return;
    }
    enabled.layers.push_back(kValidationLayer);
    auto layerExtensions =
        mVkContext.enumerateInstanceExtensionProperties(std::string(kValidationLayer));
    if (mSyncValidation && hasExtension(layerExtensions, VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME))
        enabled.extensions.push_back(VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME);
    else
        mSyncValidation = false;
}

void Context::createInstance(const InstanceLayersAndExtensions& enabled) {
    vk::ApplicationInfo appInfo{.pApplicationName = "fovea",
                                .applicationVersion = VK_MAKE_API_VERSION(0, 0, 1, 0),
                                .pEngineName = "fovea",
                                .engineVersion = VK_MAKE_API_VERSION(0, 0, 1, 0),
                                .apiVersion = kApiVersion};
    vk::DebugUtilsMessengerCreateInfoEXT messengerInfo{
        .messageSeverity = vk::DebugUtilsMessageSeverityFlagBitsEXT::eWarning |
                           vk::DebugUtilsMessageSeverityFlagBitsEXT::eError,
        .messageType = vk::DebugUtilsMessageTypeFlagBitsEXT::eGeneral |
                       vk::DebugUtilsMessageTypeFlagBitsEXT::eValidation,
        .pfnUserCallback = &Context::onDebugMessage,
        .pUserData = mSink.get()};
    vk::ValidationFeatureEnableEXT syncFeature =
        vk::ValidationFeatureEnableEXT::eSynchronizationValidation;
    vk::ValidationFeaturesEXT validationFeatures{.enabledValidationFeatureCount = 1,
                                                 .pEnabledValidationFeatures = &syncFeature};
    vk::InstanceCreateInfo instanceInfo{
        .pApplicationInfo = &appInfo,
        .enabledLayerCount = static_cast<uint32_t>(enabled.layers.size()),
        .ppEnabledLayerNames = enabled.layers.data(),
        .enabledExtensionCount = static_cast<uint32_t>(enabled.extensions.size()),
        .ppEnabledExtensionNames = enabled.extensions.data()};
    if (mValidation) {
        // Chained into instance creation too, so messages from vkCreate/DestroyInstance count.
        // The messenger info goes last: it is reused below, where its pNext must be null.
        instanceInfo.pNext = &messengerInfo;
        if (mSyncValidation) {
            instanceInfo.pNext = &validationFeatures;
            validationFeatures.pNext = &messengerInfo;
        }
    }
    try {
        mInstance = vk::raii::Instance(mVkContext, instanceInfo);
    } catch (const vk::SystemError& e) {
        throw RuntimeError(std::string("cannot create a Vulkan 1.3 instance: ") + e.what());
    }
    if (mValidation) mMessenger = vk::raii::DebugUtilsMessengerEXT(mInstance, messengerInfo);
}

void Context::pickPhysicalDevice(const std::string& spec) {
    mPhysicalDevice = selectDevice(mInstance, spec);
    mProperties = mPhysicalDevice.getProperties();
    auto props2 =
        mPhysicalDevice
            .getProperties2<vk::PhysicalDeviceProperties2, vk::PhysicalDeviceDriverProperties,
                            vk::PhysicalDeviceMaintenance3Properties>();
    const auto& driver = props2.get<vk::PhysicalDeviceDriverProperties>();
    mMaxAllocationBytes =
        props2.get<vk::PhysicalDeviceMaintenance3Properties>().maxMemoryAllocationSize;
    mDriverName = driver.driverName.data();
    mDriverInfo = driver.driverInfo.data();
    mQueueFamily = *pickQueueFamily(mPhysicalDevice);
}

std::vector<const char*> Context::chooseDeviceExtensions(bool swapchain) const {
    std::vector<const char*> deviceExtensions{VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME};
    if (swapchain) {
        if (!hasExtension(mPhysicalDevice.enumerateDeviceExtensionProperties(),
                          VK_KHR_SWAPCHAIN_EXTENSION_NAME))
            throw RuntimeError("Vulkan device '" + deviceName() +
                               "' cannot present to a window (no VK_KHR_swapchain)");
        deviceExtensions.push_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);
    }
    return deviceExtensions;
}

void Context::createDevice(const ContextOptions& options) {
    DeviceCreateChain chain;
    enableSupportedFeatures(mPhysicalDevice, chain);
    mFeatures = enabledFeatures(chain);

    float priority = 1.0f;
    vk::DeviceQueueCreateInfo queueInfo{
        .queueFamilyIndex = mQueueFamily, .queueCount = 1, .pQueuePriorities = &priority};
    std::vector<const char*> deviceExtensions = chooseDeviceExtensions(options.swapchain);
    auto& deviceInfo = chain.get<vk::DeviceCreateInfo>();
    deviceInfo.queueCreateInfoCount = 1;
    deviceInfo.pQueueCreateInfos = &queueInfo;
    deviceInfo.enabledExtensionCount = static_cast<uint32_t>(deviceExtensions.size());
    deviceInfo.ppEnabledExtensionNames = deviceExtensions.data();
    try {
        mDevice = vk::raii::Device(mPhysicalDevice, deviceInfo);
    } catch (const vk::SystemError& e) {
        throw RuntimeError("cannot create a Vulkan device on '" + deviceName() + "': " + e.what());
    }
    mQueue = vk::raii::Queue(mDevice, mQueueFamily, 0);
}

void Context::createSharedObjects() {
    mCommandPool = vk::raii::CommandPool(
        mDevice,
        vk::CommandPoolCreateInfo{.flags = vk::CommandPoolCreateFlagBits::eTransient |
                                           vk::CommandPoolCreateFlagBits::eResetCommandBuffer,
                                  .queueFamilyIndex = mQueueFamily});
    mLinearClamp = makeSampler(mDevice, vk::Filter::eLinear);
    mNearestClamp = makeSampler(mDevice, vk::Filter::eNearest);
    setObjectName(*mLinearClamp, "linearClampSampler");
    setObjectName(*mNearestClamp, "nearestClampSampler");
    mShaderCompiler = std::make_unique<ShaderCompiler>(shaderRoot(), defaultShaderCacheDir());
}

Context::~Context() {
    // Resources owned by others are gone by now; this only guards against in-flight one-shots.
    try {
        if (*mDevice) mDevice.waitIdle();
    } catch (const vk::SystemError&) {
        // Device lost at shutdown: nothing left to protect, and destructors must not throw.
    }
}

std::vector<std::string> Context::listDevices() {
    vk::raii::Context loader = makeLoaderContext();
    vk::ApplicationInfo appInfo{.pApplicationName = "fovea", .apiVersion = kApiVersion};
    vk::raii::Instance instance(loader, vk::InstanceCreateInfo{.pApplicationInfo = &appInfo});
    vk::raii::PhysicalDevices devices(instance);
    std::vector<std::string> out;
    for (size_t i = 0; i < devices.size(); ++i) out.push_back(describe(i, devices[i]));
    return out;
}

std::string Context::deviceName() const {
    return mProperties.deviceName.data();
}

std::string Context::deviceTypeName() const {
    return typeName(mProperties.deviceType);
}

VKAPI_ATTR VkBool32 VKAPI_CALL Context::onDebugMessage(
    VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT /*types*/,
    const VkDebugUtilsMessengerCallbackDataEXT* data, void* userData) {
    auto* sink = static_cast<MessageSink*>(userData);
    std::string text =
        (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) ? "ERROR" : "WARNING";
    text += ": ";
    if (data->pMessageIdName) text += std::string(data->pMessageIdName) + ": ";
    if (data->pMessage) text += data->pMessage;
    std::cerr << "fovea: validation " << text << "\n";
    std::lock_guard lock(sink->mutex);
    sink->messages.push_back(std::move(text));
    return VK_FALSE;  // never abort the call: the message count is what fails tests
}

size_t Context::validationMessageCount() const {
    std::lock_guard lock(mSink->mutex);
    return mSink->messages.size();
}

std::vector<std::string> Context::validationMessages() const {
    std::lock_guard lock(mSink->mutex);
    return mSink->messages;
}

void Context::clearValidationMessages() {
    std::lock_guard lock(mSink->mutex);
    mSink->messages.clear();
}

void Context::submitAndWait(
    const std::function<void(const vk::raii::CommandBuffer&)>& record) const {
    std::lock_guard lock(mSubmitMutex);
    vk::raii::CommandBuffers buffers(
        mDevice, vk::CommandBufferAllocateInfo{.commandPool = *mCommandPool,
                                               .level = vk::CommandBufferLevel::ePrimary,
                                               .commandBufferCount = 1});
    const vk::raii::CommandBuffer& cmd = buffers.front();
    cmd.begin(vk::CommandBufferBeginInfo{.flags = vk::CommandBufferUsageFlagBits::eOneTimeSubmit});
    record(cmd);
    cmd.end();
    vk::raii::Fence fence(mDevice, vk::FenceCreateInfo{});
    vk::CommandBufferSubmitInfo cmdInfo{.commandBuffer = *cmd};
    submit(vk::SubmitInfo2{.commandBufferInfoCount = 1, .pCommandBufferInfos = &cmdInfo}, *fence);
    try {
        (void)mDevice.waitForFences(*fence, VK_TRUE, UINT64_MAX);
    } catch (const vk::SystemError& e) {
        throw RuntimeError(std::string("GPU work failed on '") + deviceName() + "': " + e.what());
    }
}

void Context::submit(const vk::SubmitInfo2& info, vk::Fence fence) const {
    std::lock_guard lock(mSubmitMutex);
    try {
        mQueue.submit2(info, fence);
    } catch (const vk::SystemError& e) {
        throw RuntimeError(std::string("vkQueueSubmit2 failed on '") + deviceName() +
                           "': " + e.what());
    }
}

uint32_t Context::findMemoryType(uint32_t typeBits, vk::MemoryPropertyFlags props) const {
    auto memory = mPhysicalDevice.getMemoryProperties();
    for (uint32_t i = 0; i < memory.memoryTypeCount; ++i) {
        if ((typeBits & (1u << i)) && (memory.memoryTypes[i].propertyFlags & props) == props)
            return i;
    }
    throw RuntimeError("no Vulkan memory type with " + vk::to_string(props) + " among type bits " +
                       std::to_string(typeBits) + " on '" + deviceName() + "'");
}

void Context::setObjectName(vk::ObjectType type, uint64_t handle, const std::string& name) const {
    if (!mDebugUtils || name.empty() || handle == 0) return;
    mDevice.setDebugUtilsObjectNameEXT(vk::DebugUtilsObjectNameInfoEXT{
        .objectType = type, .objectHandle = handle, .pObjectName = name.c_str()});
}

}  // namespace fovea::gpu
