#include "core/graph/RenderGraph.h"

#include <chrono>

#include "core/graph/GraphContexts.h"
#include "core/graph/RuntimeResource.h"
#include "core/scene/Camera.h"
#include "core/scene/CameraGpu.h"
#include "core/util/Error.h"
#include "core/vk/ComputePipeline.h"
#include "core/vk/Context.h"
#include "core/vk/Formats.h"
#include "core/vk/Resources.h"
#include "core/vk/Timestamps.h"

namespace fovea::graph {

namespace {
std::string historyKey(const ResourcePlan& r) {
    return r.name + "|" + std::to_string(r.width) + "x" + std::to_string(r.height) + "|" +
           gpu::formatName(r.format) + "|" + std::to_string(r.ringSize);
}
gpu::ImageDesc imageDesc(const ResourcePlan& r) {
    gpu::ImageDesc d;
    d.width = r.width;
    d.height = r.height;
    d.format = r.format;
    d.debugName = r.name;
    return d;
}
vk::BufferUsageFlags bufferUsage(const ResourcePlan& r) {
    vk::BufferUsageFlags usage = vk::BufferUsageFlagBits::eStorageBuffer |
                                 vk::BufferUsageFlagBits::eTransferSrc |
                                 vk::BufferUsageFlagBits::eTransferDst;
    if (r.indirect) usage |= vk::BufferUsageFlagBits::eIndirectBuffer;
    return usage;
}
}  // namespace

const char* passStatusName(PassStatus s) {
    switch (s) {
        case PassStatus::Executed:
            return "executed";
        case PassStatus::Culled:
            return "culled";
        case PassStatus::Skipped:
            return "skipped";
        case PassStatus::Cached:
            return "cached";
        case PassStatus::Bypassed:
            return "bypassed";
    }
    return "?";
}

RenderGraph::RenderGraph(gpu::Context& gpu, const PassRegistry& registry)
    : mGpu(gpu), mRegistry(registry), mCamera(std::make_unique<scene::FrameCamera>()) {
    const auto& device = mGpu.device();
    mCameraBuffer =
        std::make_unique<gpu::Buffer>(mGpu, sizeof(scene::layout::CameraInfo),
                                      vk::BufferUsageFlagBits::eUniformBuffer, true, "camera_info");
    mCommandPool = std::make_unique<vk::raii::CommandPool>(
        device,
        vk::CommandPoolCreateInfo{.flags = vk::CommandPoolCreateFlagBits::eResetCommandBuffer,
                                  .queueFamilyIndex = mGpu.queueFamily()});
    vk::raii::CommandBuffers buffers(
        device, vk::CommandBufferAllocateInfo{.commandPool = **mCommandPool,
                                              .level = vk::CommandBufferLevel::ePrimary,
                                              .commandBufferCount = 1});
    mCommandBuffer = std::make_unique<vk::raii::CommandBuffer>(std::move(buffers[0]));
    mFence = std::make_unique<vk::raii::Fence>(device, vk::FenceCreateInfo{});
}

RenderGraph::~RenderGraph() = default;

void RenderGraph::build(const GraphDesc& desc, const CompileOptions& options) {
    // A graph that does not compile throws here and leaves the running graph as it was.
    CompiledPlan plan = compileGraphPlan(desc, mRegistry, options);
    mPipelineCache.clear();  // every pipeline from source again (a shader may have changed)
    buildPlan(desc, std::move(plan), options);
}

void RenderGraph::buildPlan(const GraphDesc& desc, CompiledPlan plan,
                            const CompileOptions& options) {
    // Past this point the old graph is being replaced: a failure (allocation, a pass's compile)
    // leaves no half-built graph behind, but an unbuilt one that runFrame() refuses to run.
    mBuilt = false;
    try {
        install(desc, std::move(plan), options);
    } catch (const std::exception& e) {
        discardBuild(e.what());
        throw;
    } catch (...) {
        discardBuild("unknown error");
        throw;
    }
    mBuilt = true;
    mBuildError.clear();
}

void RenderGraph::discardBuild(const std::string& error) {
    mBuildError = error;
    mResources.clear();
    mKeptHistory.clear();
    mBlocks.clear();
    mPlan = CompiledPlan{};
    mRecords.clear();
    mLastCacheKey.clear();
    mTimestamps.reset();
    mFrame.framesSinceReset = 0;  // whatever is built next starts without history
}

void RenderGraph::install(const GraphDesc& desc, CompiledPlan plan, const CompileOptions& options) {
    bool sizeChanged = options.width != mFrame.width || options.height != mFrame.height;
    // Keep history rings of the previous build for reuse by identical resources.
    for (size_t i = 0; i < mResources.size(); ++i)
        if (mPlan.resources[i].lifetime == Lifetime::History)
            mKeptHistory[mResources[i]->key] = std::move(mResources[i]);
    mResources.clear();
    mBlocks.clear();
    mDesc = desc;
    mPlan = std::move(plan);
    mFrame.width = options.width;
    mFrame.height = options.height;
    mRecords.assign(mPlan.nodes.size(), PassRecord{});
    for (size_t n = 0; n < mPlan.nodes.size(); ++n)
        if (!mPlan.nodes[n].alive) {
            mRecords[n].status = PassStatus::Culled;
            mRecords[n].reason = mPlan.nodes[n].cullReason;
        }
    mLastCacheKey.assign(mPlan.nodes.size(), 0);
    allocate();
    mKeptHistory.clear();
    compilePasses();
    mTimestamps = std::make_unique<gpu::TimestampPool>(
        mGpu, uint32_t(std::max<size_t>(2, 2 * mPlan.order.size())));
    if (sizeChanged) reset();
}

void RenderGraph::resize(uint32_t width, uint32_t height) {
    CompileOptions options = mPlan.options;
    options.width = width;
    options.height = height;
    build(mDesc, options);
    reset();
}

void RenderGraph::setCamera(const scene::FrameCamera& camera) {
    *mCamera = camera;
    if (camera.cut) reset();
    mFrame.cameraCut = camera.cut;
}

void RenderGraph::reset() {
    mFrame.framesSinceReset = 0;
    std::fill(mLastCacheKey.begin(), mLastCacheKey.end(), 0);
    for (size_t n : mPlan.order) mPlan.nodes[n].pass->onReset();
}

void RenderGraph::allocate() {
    mAllocatedTransient = mAllocatedPersistent = 0;
    mResources.resize(mPlan.resources.size());
    // Alias groups: one memory block per group, sized for its largest member.
    std::vector<std::shared_ptr<gpu::MemoryBlock>> groupBlocks(mPlan.aliasGroups.size());
    for (size_t g = 0; g < mPlan.aliasGroups.size(); ++g) {
        vk::DeviceSize size = 0;
        uint32_t typeBits = ~0u;
        for (size_t m : mPlan.aliasGroups[g].members) {
            auto req = gpu::Image::memoryRequirements(mGpu, imageDesc(mPlan.resources[m]));
            size = std::max(size, req.size);
            typeBits &= req.memoryTypeBits;
        }
        if (typeBits == 0)
            throw RuntimeError("alias group " + std::to_string(g) +
                               ": members need incompatible memory types");
        // Errors name the images that share the block (the largest decides its size).
        std::string users = "the memory shared by";
        for (size_t m : mPlan.aliasGroups[g].members) {
            const ResourcePlan& r = mPlan.resources[m];
            users += (m == mPlan.aliasGroups[g].members.front() ? " '" : ", '") + r.name + "' (" +
                     std::to_string(r.width) + "x" + std::to_string(r.height) + ")";
        }
        groupBlocks[g] = std::make_shared<gpu::MemoryBlock>(
            mGpu, size, typeBits, vk::MemoryPropertyFlagBits::eDeviceLocal, users);
        mBlocks.push_back(groupBlocks[g]);
        mAllocatedTransient += size;
    }
    for (size_t i = 0; i < mPlan.resources.size(); ++i) {
        const ResourcePlan& r = mPlan.resources[i];
        std::string key = historyKey(r);
        if (r.lifetime == Lifetime::History) {
            auto kept = mKeptHistory.find(key);
            if (kept != mKeptHistory.end()) {
                mResources[i] = std::move(kept->second);
                mKeptHistory.erase(kept);
                for (const auto& img : mResources[i]->ring)
                    mAllocatedPersistent += img->allocationSize();
                continue;
            }
        }
        auto res = std::make_unique<RuntimeResource>();
        res->key = key;
        res->createdAt = mFrame.index;
        if (!r.isImage) {
            res->buffer = std::make_unique<gpu::Buffer>(mGpu, r.bufferBytes, bufferUsage(r),
                                                        r.hostVisible, r.name);
            if (r.init == BufferInit::Contents)  // constant data, checked to fit by reflectPasses
                res->buffer->upload(mGpu, r.contents, r.bufferBytes);
            (r.lifetime == Lifetime::Transient ? mAllocatedTransient : mAllocatedPersistent) +=
                r.bufferBytes;
        } else if (r.aliasGroup >= 0) {
            res->ring.push_back(
                std::make_unique<gpu::Image>(mGpu, imageDesc(r), groupBlocks[r.aliasGroup], 0));
        } else {
            for (uint32_t s = 0; s < r.ringSize; ++s) {
                res->ring.push_back(std::make_unique<gpu::Image>(mGpu, imageDesc(r)));
                (r.lifetime == Lifetime::Transient ? mAllocatedTransient : mAllocatedPersistent) +=
                    res->ring.back()->allocationSize();
            }
        }
        mResources[i] = std::move(res);
    }
}

void RenderGraph::compilePasses() {
    for (size_t n : mPlan.order) {
        PassNode& node = mPlan.nodes[n];
        GraphCompileContext ctx(*this, mPlan, n);
        attributeAllocations(n, [&] { node.pass->compile(ctx); });
        // Bypass pairs were checked for equal size and format by the compile stages.
    }
}

size_t RenderGraph::slotOf(const RuntimeResource& r, uint32_t delay) const {
    const uint64_t ring = r.ring.size();
    return size_t(((mFrame.index % ring) + ring - (delay % ring)) % ring);
}

const gpu::Image& RenderGraph::imageFor(size_t node, const std::string& field) const {
    auto own = mPlan.resourceOf.find({node, field});
    if (own != mPlan.resourceOf.end()) {
        const RuntimeResource& r = *mResources[own->second];
        return *r.ring[slotOf(r, 0)];
    }
    auto in = mPlan.inputs.find({node, field});
    if (in == mPlan.inputs.end())
        throw RuntimeError("pass '" + mPlan.nodes[node].name + "' asked for unconnected field '" +
                           field + "'");
    const RuntimeResource& r = *mResources[in->second.resource];
    if (r.ring.empty())
        throw RuntimeError("field '" + field + "' of pass '" + mPlan.nodes[node].name +
                           "' is a buffer, not an image");
    return *r.ring[slotOf(r, in->second.delay)];
}

std::optional<uint64_t> RenderGraph::inputVersionFor(size_t node, const std::string& input) const {
    auto in = mPlan.inputs.find({node, input});
    // A delayed input reads another ring slot every frame: no single version describes it.
    if (in == mPlan.inputs.end() || in->second.delay != 0) return std::nullopt;
    return mResources[in->second.resource]->version;
}

nlohmann::json RenderGraph::passStatistics(size_t node) const {
    if (node >= mPlan.nodes.size() || !mPlan.nodes[node].alive || !mPlan.nodes[node].pass)
        return nullptr;
    StatisticsContext ctx{mGpu, [this, node](const std::string& field) -> const gpu::Buffer& {
                              return bufferFor(node, field);
                          }};
    return mPlan.nodes[node].pass->statistics(ctx);
}

const gpu::Buffer& RenderGraph::bufferFor(size_t node, const std::string& field) const {
    auto own = mPlan.resourceOf.find({node, field});
    size_t index;
    if (own != mPlan.resourceOf.end()) {
        index = own->second;
    } else {
        auto in = mPlan.inputs.find({node, field});
        if (in == mPlan.inputs.end())
            throw RuntimeError("pass '" + mPlan.nodes[node].name +
                               "' asked for unconnected field '" + field + "'");
        index = in->second.resource;
    }
    if (!mResources[index]->buffer)
        throw RuntimeError("field '" + field + "' of pass '" + mPlan.nodes[node].name +
                           "' is an image, not a buffer");
    return *mResources[index]->buffer;
}

bool RenderGraph::historyValidFor(size_t node, const std::string& field,
                                  uint32_t framesBack) const {
    size_t resource = kNone;
    uint64_t delay = framesBack;
    if (auto own = mPlan.resourceOf.find({node, field}); own != mPlan.resourceOf.end()) {
        // Pass-declared history: valid for the frames the ring has held since the last reset.
        if (framesBack == 0 || framesBack > mPlan.resources[own->second].declaredHistory)
            return false;
        resource = own->second;
    } else if (auto in = mPlan.inputs.find({node, field}); in != mPlan.inputs.end()) {
        resource = in->second.resource;
        delay = in->second.delay;
    } else {
        return false;
    }
    return mFrame.framesSinceReset >= delay &&
           mFrame.index - mResources[resource]->createdAt >= delay;
}

const gpu::Image& RenderGraph::previousFor(size_t node, const std::string& field,
                                           uint32_t framesBack) const {
    auto own = mPlan.resourceOf.find({node, field});
    if (own == mPlan.resourceOf.end() || mPlan.resources[own->second].declaredHistory == 0)
        throw RuntimeError("pass '" + mPlan.nodes[node].name +
                           "' asked for the previous frame of '" + field +
                           "', which is not an output/internal with declared history");
    const ResourcePlan& plan = mPlan.resources[own->second];
    if (framesBack == 0 || framesBack > plan.declaredHistory)
        throw RuntimeError("pass '" + mPlan.nodes[node].name + "' asked for '" + field + "' " +
                           std::to_string(framesBack) + " frames back; it declares " +
                           std::to_string(plan.declaredHistory));
    const RuntimeResource& r = *mResources[own->second];
    return *r.ring[slotOf(r, framesBack)];
}

void RenderGraph::attributeAllocations(size_t node, const std::function<void()>& call) {
    const uint64_t before = mGpu.allocationCount(), graphBefore = mGraphAllocations;
    call();
    const uint64_t made = (mGpu.allocationCount() - before) - (mGraphAllocations - graphBefore);
    if (node < mRecords.size()) mRecords[node].allocationsOutsidePlan += made;
}

const gpu::Image& RenderGraph::dummyImage(vk::Format format) {
    if (format == vk::Format::eUndefined) format = vk::Format::eR32G32B32A32Sfloat;
    auto& slot = mDummies[format];
    if (!slot) {
        const uint64_t before = mGpu.allocationCount();
        slot = std::make_unique<gpu::Image>(
            mGpu, gpu::ImageDesc{.width = 1, .height = 1, .format = format, .debugName = "dummy"});
        mGraphAllocations += mGpu.allocationCount() - before;
    }
    return *slot;
}

const gpu::Buffer& RenderGraph::dummyBuffer() {
    if (!mDummyBuffer) {
        const uint64_t before = mGpu.allocationCount();
        // Zero-filled, so a shader that reads an unconnected optional buffer sees count 0.
        mDummyBuffer = std::make_unique<gpu::Buffer>(
            mGpu, kDummyBufferBytes,
            vk::BufferUsageFlagBits::eStorageBuffer | vk::BufferUsageFlagBits::eUniformBuffer |
                vk::BufferUsageFlagBits::eTransferDst | vk::BufferUsageFlagBits::eTransferSrc,
            false, "dummy");
        std::vector<std::byte> zeros(kDummyBufferBytes);
        mDummyBuffer->upload(mGpu, zeros.data(), zeros.size());
        mGraphAllocations += mGpu.allocationCount() - before;
    }
    return *mDummyBuffer;
}

const gpu::Image& RenderGraph::image(const std::string& resourceName) const {
    // The frame index already advanced past the frame that wrote it.
    auto lastFrame = [&](size_t resource, uint32_t delay) -> const gpu::Image& {
        const RuntimeResource& r = *mResources[resource];
        const uint64_t ring = r.ring.size();
        return *r.ring[size_t((mFrame.index + ring - 1 - (delay % ring)) % ring)];
    };
    for (size_t i = 0; i < mPlan.resources.size(); ++i)
        if (mPlan.resources[i].name == resourceName && mPlan.resources[i].isImage)
            return lastFrame(i, 0);
    // An input: what it read in the last frame (an edge's content, its delay included).
    if (auto endpoint = parseEndpoint(resourceName)) {
        const size_t node = mPlan.findNode(endpoint->pass);
        auto in = mPlan.inputs.find({node, endpoint->field});
        if (node != kNone && in != mPlan.inputs.end() && in->second.resource != kNone &&
            mPlan.resources[in->second.resource].isImage)
            return lastFrame(in->second.resource, in->second.delay);
    }
    throw RuntimeError("no live image resource or connected image input '" + resourceName + "'");
}

const gpu::Buffer& RenderGraph::buffer(const std::string& resourceName) const {
    for (size_t i = 0; i < mPlan.resources.size(); ++i)
        if (mPlan.resources[i].name == resourceName && mResources.size() > i &&
            mResources[i]->buffer)
            return *mResources[i]->buffer;
    throw RuntimeError("no live buffer resource '" + resourceName + "'");
}

void RenderGraph::setFirstFrameIndex(uint64_t index) {
    // History rings and "created at" frames are counted from the index at build.
    if (mBuilt) throw RuntimeError("setFirstFrameIndex: call it before build()");
    mFrame.index = index;
}

}  // namespace fovea::graph
