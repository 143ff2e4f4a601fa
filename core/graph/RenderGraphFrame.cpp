// Frame execution of a RenderGraph: barriers, bypass, caching, timestamps.
#include <algorithm>
#include <chrono>
#include <cstring>
#include <map>

#include "core/graph/GraphContexts.h"
#include "core/graph/RenderGraph.h"
#include "core/graph/RuntimeResource.h"
#include "core/scene/CameraGpu.h"
#include "core/util/Error.h"
#include "core/vk/Context.h"
#include "core/vk/Resources.h"
#include "core/vk/Timestamps.h"

namespace fovea::graph {

namespace {
using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t).count();
}

// Everything the graph does is compute, transfer or an indirect dispatch's argument read (a
// buffer field declared indirect()); one access mask covers every direction.
constexpr vk::PipelineStageFlags2 kStages = vk::PipelineStageFlagBits2::eComputeShader |
                                            vk::PipelineStageFlagBits2::eTransfer |
                                            vk::PipelineStageFlagBits2::eDrawIndirect;
constexpr vk::AccessFlags2 kAccess =
    vk::AccessFlagBits2::eShaderRead | vk::AccessFlagBits2::eShaderWrite |
    vk::AccessFlagBits2::eTransferRead | vk::AccessFlagBits2::eTransferWrite |
    vk::AccessFlagBits2::eIndirectCommandRead;

uint64_t mix(uint64_t h, uint64_t v) {  // FNV-1a style combine
    h ^= v + 0x9e3779b97f4a7c15ull + (h << 6) + (h >> 2);
    return h * 1099511628211ull;
}
}  // namespace

void RenderGraph::recordBarrier(const vk::raii::CommandBuffer& cmd, const BarrierPlan* plan) const {
    vk::MemoryBarrier2 memory{.srcStageMask = kStages,
                              .srcAccessMask = kAccess,
                              .dstStageMask = kStages,
                              .dstAccessMask = kAccess};
    std::vector<vk::ImageMemoryBarrier2> images;
    if (plan)
        for (size_t r : plan->initialize)
            for (const auto& img : mResources[r]->ring)
                images.push_back(vk::ImageMemoryBarrier2{
                    .srcStageMask = kStages,
                    .srcAccessMask = kAccess,
                    .dstStageMask = kStages,
                    .dstAccessMask = kAccess,
                    .oldLayout = vk::ImageLayout::eUndefined,
                    .newLayout = vk::ImageLayout::eGeneral,
                    .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                    .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                    .image = img->image(),
                    .subresourceRange = {vk::ImageAspectFlagBits::eColor, 0, 1, 0, 1}});
    cmd.pipelineBarrier2(vk::DependencyInfo{.memoryBarrierCount = 1,
                                            .pMemoryBarriers = &memory,
                                            .imageMemoryBarrierCount = uint32_t(images.size()),
                                            .pImageMemoryBarriers = images.data()});
}

uint64_t RenderGraph::cacheKey(size_t node) const {
    const PassNode& n = mPlan.nodes[node];
    uint64_t h = 1469598103934665603ull;
    for (char c : saveParams(*n.pass, false).dump()) h = mix(h, uint8_t(c));
    h = mix(h, mFrame.seed);  // passes see it (ImageSource noise); size changes reset anyway
    if (n.pass->sceneNeeds() != 0 || n.pass->usesCamera()) {
        // A pass that reads the scene sees the camera too: a moved camera is a changed input.
        const auto info = scene::layout::packCamera(*mCamera, 0, 0);
        const auto* bytes = reinterpret_cast<const uint8_t*>(&info);
        for (size_t i = 0; i < sizeof(info); ++i) h = mix(h, bytes[i]);
        h = mix(h, reinterpret_cast<uintptr_t>(mScene));
    }
    for (const auto& [key, src] : mPlan.inputs) {
        if (key.first != node) continue;
        h = mix(h, mResources[src.resource]->version);
        h = mix(h, src.delay);
    }
    return h == 0 ? 1 : h;  // 0 means "never ran"
}

void RenderGraph::carryRings(const vk::raii::CommandBuffer& cmd, size_t n, bool all) const {
    // An output read through a delayed edge lives in a ring and each frame writes the next slot.
    // A persistent one (read-modify-write, e.g. a running mean) and any output of a skipped pass
    // must still start from the previous frame's content: copy it into this frame's slot.
    const PassNode& node = mPlan.nodes[n];
    bool copied = false;
    for (const auto& f : node.reflection.fields()) {
        if (f.kind == FieldKind::Input || !(all || f.persistent)) continue;
        size_t index = mPlan.resourceOf.at({n, f.name});
        const RuntimeResource& r = *mResources[index];
        if (mPlan.resources[index].lifetime != Lifetime::History || r.ring.size() < 2) continue;
        const gpu::Image& src = *r.ring[slotOf(r, 1)];
        const gpu::Image& dst = *r.ring[slotOf(r, 0)];
        vk::ImageCopy region{.srcSubresource = {vk::ImageAspectFlagBits::eColor, 0, 0, 1},
                             .dstSubresource = {vk::ImageAspectFlagBits::eColor, 0, 0, 1},
                             .extent = {dst.width(), dst.height(), 1}};
        cmd.copyImage(src.image(), vk::ImageLayout::eGeneral, dst.image(),
                      vk::ImageLayout::eGeneral, region);
        copied = true;
    }
    if (copied) recordBarrier(cmd, nullptr);
}

void RenderGraph::recordBufferInit(const vk::raii::CommandBuffer& cmd) const {
    // FieldDesc::init: zeros on a buffer's first frame, and for ZeroOnReset on every frame that
    // starts a history, so no pass clears its own counters (and no pass records the barrier).
    for (size_t i = 0; i < mPlan.resources.size(); ++i) {
        const ResourcePlan& r = mPlan.resources[i];
        const RuntimeResource& res = *mResources[i];
        if (!res.buffer) continue;
        const bool fresh = res.createdAt == mFrame.index;
        if ((r.init == BufferInit::Zero && fresh) ||
            (r.init == BufferInit::ZeroOnReset && (fresh || mFrame.framesSinceReset == 0)))
            cmd.fillBuffer(res.buffer->buffer(), 0, VK_WHOLE_SIZE, 0u);
    }
}

void RenderGraph::recordPass(const vk::raii::CommandBuffer& cmd, size_t n, double& passCpuMs) {
    PassNode& node = mPlan.nodes[n];
    PassRecord& record = mRecords[n];
    auto bumpOutputs = [&] {
        for (const auto& f : node.reflection.fields())
            if (f.kind != FieldKind::Input) ++mResources[mPlan.resourceOf.at({n, f.name})]->version;
    };
    if (!node.pass->isActive(mFrame)) {
        auto pairs = node.pass->bypass();
        if (pairs.empty()) {
            carryRings(cmd, n, true);
            record.status = PassStatus::Skipped;
            record.reason = "inactive this frame; outputs keep their previous content";
            return;
        }
        for (const auto& [input, output] : pairs) {
            const gpu::Image& dst = imageFor(n, output);
            if (mPlan.inputs.count({n, input})) {
                const gpu::Image& src = imageFor(n, input);
                vk::ImageCopy region{.srcSubresource = {vk::ImageAspectFlagBits::eColor, 0, 0, 1},
                                     .dstSubresource = {vk::ImageAspectFlagBits::eColor, 0, 0, 1},
                                     .extent = {dst.width(), dst.height(), 1}};
                cmd.copyImage(src.image(), vk::ImageLayout::eGeneral, dst.image(),
                              vk::ImageLayout::eGeneral, region);
            } else {
                dst.recordClear(cmd, {0, 0, 0, 0});
            }
        }
        bumpOutputs();
        record.status = PassStatus::Bypassed;
        record.reason = "inactive this frame; bypass copies its input";
        return;
    }
    bool hasHistoryOutput = false;
    for (const auto& f : node.reflection.fields())
        if (f.kind != FieldKind::Input &&
            mPlan.resources[mPlan.resourceOf.at({n, f.name})].lifetime == Lifetime::History)
            hasHistoryOutput = true;
    if (node.pass->cacheable() && !hasHistoryOutput) {
        uint64_t key = cacheKey(n);
        if (key == mLastCacheKey[n]) {
            record.status = PassStatus::Cached;
            record.reason = "inputs and parameters unchanged since its last run";
            return;
        }
        mLastCacheKey[n] = key;
    }
    carryRings(cmd, n, false);
    GraphExecuteContext ctx(*this, mPlan, n, cmd, mFrame);
    auto t0 = Clock::now();
    attributeAllocations(n, [&] { node.pass->execute(ctx); });
    passCpuMs += msSince(t0);
    record.dispatches += ctx.hazards().dispatches();
    record.barriersInPass += ctx.hazards().barriers();
    bumpOutputs();
    record.status = PassStatus::Executed;
    record.reason.clear();
    ++record.executions;
}

FrameTiming RenderGraph::runFrame() {
    if (!mBuilt) {
        if (mBuildError.empty())
            throw RuntimeError("runFrame: the render graph is not built (call build() first)");
        throw RuntimeError("runFrame: the render graph is not built: the last build() failed (" +
                           mBuildError + "); build it again");
    }
    FrameTiming timing;
    const auto& cmd = *mCommandBuffer;
    auto t0 = Clock::now();
    // The previous frame finished (runFrame waits on its fence), so the mapped camera buffer is
    // free to overwrite.
    const auto cameraInfo =
        scene::layout::packCamera(*mCamera, mFrame.index, mFrame.framesSinceReset);
    std::memcpy(mCameraBuffer->mapped(), &cameraInfo, sizeof(cameraInfo));
    cmd.reset();
    cmd.begin(vk::CommandBufferBeginInfo{.flags = vk::CommandBufferUsageFlagBits::eOneTimeSubmit});
    mTimestamps->reset(cmd);
    mFrameDispatches.clear();
    if (mProfileDispatches) {
        if (!mDispatchTimestamps)
            mDispatchTimestamps =
                std::make_unique<gpu::TimestampPool>(mGpu, 2 * kMaxProfiledDispatches);
        mDispatchTimestamps->reset(cmd);
    }
    recordBufferInit(cmd);
    // The previous frame (and any upload or buffer clear) is ordered before this one by a full
    // barrier.
    recordBarrier(cmd, nullptr);
    size_t nextBarrier = 0;
    for (size_t pos = 0; pos < mPlan.order.size(); ++pos) {
        if (nextBarrier < mPlan.barriers.size() && mPlan.barriers[nextBarrier].position == int(pos))
            recordBarrier(cmd, &mPlan.barriers[nextBarrier++]);
        mTimestamps->write(cmd, uint32_t(2 * pos));
        recordPass(cmd, mPlan.order[pos], timing.passCpuMs);
        mTimestamps->write(cmd, uint32_t(2 * pos + 1));
    }
    // Make the frame's writes visible to whatever reads them next (readback, next frame).
    recordBarrier(cmd, nullptr);
    cmd.end();
    timing.recordCpuMs = msSince(t0);

    auto t1 = Clock::now();
    // Through the context's submit: it holds the queue lock every other submit takes.
    vk::CommandBufferSubmitInfo cmdInfo{.commandBuffer = *cmd};
    mGpu.submit(vk::SubmitInfo2{.commandBufferInfoCount = 1, .pCommandBufferInfos = &cmdInfo},
                **mFence);
    if (mGpu.device().waitForFences(**mFence, VK_TRUE, UINT64_MAX) != vk::Result::eSuccess)
        throw RuntimeError("waiting for the frame's fence failed");
    mGpu.device().resetFences(**mFence);
    timing.submitWaitMs = msSince(t1);

    if (!mPlan.order.empty()) {
        auto ticks = mTimestamps->readTicks(uint32_t(2 * mPlan.order.size()));
        timing.gpuMs = mTimestamps->ticksToMs(ticks.back() - ticks.front());
        for (size_t pos = 0; pos < mPlan.order.size(); ++pos) {
            PassRecord& r = mRecords[mPlan.order[pos]];
            if (r.status == PassStatus::Executed || r.status == PassStatus::Bypassed)
                r.gpuMs.push_back(mTimestamps->ticksToMs(ticks[2 * pos + 1] - ticks[2 * pos]));
        }
    }
    collectDispatchTimes();
    ++mFrame.index;
    ++mFrame.framesSinceReset;
    mFrame.cameraCut = false;
    return timing;
}

void RenderGraph::beginDispatchTiming(const vk::raii::CommandBuffer& cmd, size_t node,
                                      const std::string& shader) {
    mDispatchOpen = false;
    if (!mProfileDispatches || !mDispatchTimestamps ||
        mFrameDispatches.size() >= kMaxProfiledDispatches)
        return;
    mDispatchTimestamps->write(cmd, uint32_t(2 * mFrameDispatches.size()));
    mFrameDispatches.push_back({node, shader});
    mDispatchOpen = true;
}

void RenderGraph::endDispatchTiming(const vk::raii::CommandBuffer& cmd) {
    if (!mDispatchOpen) return;
    mDispatchTimestamps->write(cmd, uint32_t(2 * mFrameDispatches.size() - 1));
    mDispatchOpen = false;
}

void RenderGraph::collectDispatchTimes() {
    if (mFrameDispatches.empty()) return;
    const auto ticks = mDispatchTimestamps->readTicks(uint32_t(2 * mFrameDispatches.size()));
    // Occurrence = how many dispatches of the same shader the pass recorded before this one in
    // this frame, so a pass's levels line up across frames even when some frames add dispatches
    // of another shader (e.g. ATrousNH's tile lists, rebuilt only when the mask changes).
    std::map<std::pair<size_t, std::string>, uint32_t> seen;
    for (size_t i = 0; i < mFrameDispatches.size(); ++i) {
        // Not a structured binding: clang 14 (the sanitizer build) lets no lambda capture one.
        const size_t node = mFrameDispatches[i].node;
        const std::string& shader = mFrameDispatches[i].shader;
        const uint32_t occurrence = seen[{node, shader}]++;
        auto& times = mRecords[node].dispatchMs;
        auto it = std::find_if(times.begin(), times.end(), [&](const auto& t) {
            return t.shader == shader && t.occurrence == occurrence;
        });
        if (it == times.end()) it = times.insert(times.end(), {shader, occurrence, {}});
        it->ms.push_back(mDispatchTimestamps->ticksToMs(ticks[2 * i + 1] - ticks[2 * i]));
    }
    mFrameDispatches.clear();
}

}  // namespace fovea::graph
