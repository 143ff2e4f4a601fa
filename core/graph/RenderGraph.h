// The runtime side of a graph: allocates what a CompiledPlan describes (aliased transients in
// shared memory blocks, history rings kept across rebuilds), compiles every live pass, and
// executes frames: barriers from the plan, bypass of inactive passes, skipping of cached passes,
// GPU timestamps around every pass.
#pragma once
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/graph/CompilerStages.h"

namespace fovea::gpu {
class Context;
class Image;
class Buffer;
class MemoryBlock;
class TimestampPool;
class ComputePipeline;
}  // namespace fovea::gpu

namespace fovea::scene {
class SceneGpu;
struct FrameCamera;
}  // namespace fovea::scene

namespace fovea::graph {

enum class PassStatus { Executed, Culled, Skipped, Cached, Bypassed };
const char* passStatusName(PassStatus s);

struct PassRecord {
    PassStatus status = PassStatus::Executed;  // in the last frame
    std::string reason;
    std::vector<double> gpuMs;  // one entry per frame the pass ran (executed or bypassed)
    uint64_t executions = 0;
    // Device memory allocations the pass made itself in compile() and execute() since the graph
    // was built: memory the plan, `validate --dump` and the memory totals cannot see. The pass
    // contract says 0 (declare a buffer field instead); report.json lists it per pass.
    uint64_t allocationsOutsidePlan = 0;
    // Since the graph was built: dispatches the pass recorded through ExecuteContext::dispatch,
    // and the barriers the graph derived between them (gpu::DispatchHazards).
    uint64_t dispatches = 0;
    uint64_t barriersInPass = 0;
    // With dispatch profiling (RenderGraph::setDispatchProfiling): the GPU time of each dispatch,
    // keyed by shader and by its occurrence among that shader's dispatches in the pass's frame
    // (ATrousNH's levels are atrous_nh.comp #0, #1, ...), one entry per frame it ran, in the
    // order first seen. Empty without profiling.
    struct DispatchTimes {
        std::string shader;
        uint32_t occurrence = 0;
        std::vector<double> ms;
    };
    std::vector<DispatchTimes> dispatchMs;
};

struct FrameTiming {
    double gpuMs = 0;         // first to last timestamp of the frame
    double recordCpuMs = 0;   // CPU time recording the command buffer (all passes)
    double passCpuMs = 0;     // of which inside Pass::execute
    double submitWaitMs = 0;  // submit + wait for the fence
};

struct RuntimeResource;  // defined in RenderGraph.cpp

class RenderGraph {
public:
    RenderGraph(gpu::Context& gpu, const PassRegistry& registry);
    ~RenderGraph();

    // Compiles `desc` with `options`, allocates and compiles every live pass. History rings whose
    // producer, size, format and ring length are unchanged survive a rebuild (and stay valid,
    // unless the size changed).
    void build(const GraphDesc& desc, const CompileOptions& options);
    void resize(uint32_t width, uint32_t height);  // rebuild at a new size; history invalid
    void reset();  // history invalid (reset / camera cut); caches dropped

    // A parameter edit without a full rebuild (RenderGraphUpdate.cpp). `desc` is compiled (every
    // check); when its plan has the same shape as the running one (live passes, order, inputs,
    // resources with sizes/formats/lifetimes, alias groups, barriers), every resource keeps its
    // memory and content, every pass whose parameters did not change keeps its instance (and its
    // pipelines, CPU state and cache key), and only changed passes are created and compiled
    // again, their pipelines taken from the graph's pipeline cache when shader and defines are
    // unchanged (a parameter that only reaches push constants creates no pipeline). A compile
    // error of a changed pass leaves the running graph untouched. Any other change: build().
    struct UpdateResult {
        bool inPlace = false;
        std::vector<std::string> recompiled;  // passes whose compile() ran (in place)
        uint32_t pipelinesCreated = 0;        // driver pipeline creations during the update
        uint32_t pipelinesReused = 0;         // pipelines shared from the cache
    };
    UpdateResult update(const GraphDesc& desc);
    // Used by GraphCompileContext: a pipeline for shader + defines, shared from the cache when
    // update() compiles a pass (build() starts with an empty cache, so edited shaders reload).
    std::unique_ptr<gpu::ComputePipeline> pipeline(
        const std::string& shaderPath,
        const std::vector<std::pair<std::string, std::string>>& defines);

    // The scene passes see (not owned; must outlive the graph's use of it; null = none) and the
    // camera of the next frame. A camera with `cut` set resets history before the frame runs.
    void setScene(const scene::SceneGpu* scene) { mScene = scene; }
    void setCamera(const scene::FrameCamera& camera);
    const scene::SceneGpu* scene() const { return mScene; }
    const scene::FrameCamera& camera() const { return *mCamera; }
    // The `camera_info` uniform buffer (shaders/common/camera.glsl), refreshed before each frame.
    const gpu::Buffer& cameraBuffer() const { return *mCameraBuffer; }

    // Throws RuntimeError when the graph is not built (no build() yet, or the last one failed).
    FrameTiming runFrame();
    bool built() const { return mBuilt; }

    const CompiledPlan& plan() const { return mPlan; }
    const GraphDesc& desc() const { return mDesc; }
    const std::vector<PassRecord>& records() const { return mRecords; }  // per plan node
    uint64_t frameIndex() const { return mFrame.index; }
    uint64_t framesSinceReset() const { return mFrame.framesSinceReset; }
    void setSeed(uint64_t seed) { mFrame.seed = seed; }
    // The index the next frame gets (FrameInfo::index: the path tracer's sample streams and the
    // camera jitter follow it). Before build only: a shard of a reference continues where the
    // frames of the shard before it end (eval/reference/ReferenceShards.h).
    void setFirstFrameIndex(uint64_t index);

    // The current content of an alive resource ("pass.field"), e.g. a marked output; for a
    // connected input ("pass.input") the image that input read in the last frame (delay included).
    const gpu::Image& image(const std::string& resourceName) const;
    // A live buffer resource ("pass.field"), e.g. a pass's counters for a test or a tool.
    const gpu::Buffer& buffer(const std::string& resourceName) const;
    // Bytes actually allocated on the device (after alignment), by lifetime class.
    uint64_t allocatedTransientBytes() const { return mAllocatedTransient; }
    uint64_t allocatedPersistentBytes() const { return mAllocatedPersistent; }
    gpu::Context& gpu() { return mGpu; }

    // Pass::statistics of node `node` (null for culled passes or passes without counters).
    nlohmann::json passStatistics(size_t node) const;

    // Opt-in profiling (fovea run --profile-dispatches): a GPU timestamp before and after every
    // dispatch a pass records through its ExecuteContext, so PassRecord::dispatchMs splits the
    // pass's time by dispatch (the first kMaxProfiledDispatches of a frame). Each timestamp waits
    // for the commands before it, so profiled frames can be slower than plain ones.
    void setDispatchProfiling(bool on) { mProfileDispatches = on; }
    static constexpr uint32_t kMaxProfiledDispatches = 1024;
    // Used by GraphExecuteContext around each dispatch (no-ops without profiling).
    void beginDispatchTiming(const vk::raii::CommandBuffer& cmd, size_t node,
                             const std::string& shader);
    void endDispatchTiming(const vk::raii::CommandBuffer& cmd);

    // Used by the contexts handed to passes.
    const gpu::Image& imageFor(size_t node, const std::string& field) const;
    const gpu::Buffer& bufferFor(size_t node, const std::string& field) const;
    bool historyValidFor(size_t node, const std::string& field, uint32_t framesBack) const;
    const gpu::Image& previousFor(size_t node, const std::string& field, uint32_t framesBack) const;
    std::optional<uint64_t> inputVersionFor(size_t node, const std::string& input) const;
    const gpu::Image& dummyImage(vk::Format format);
    const gpu::Buffer& dummyBuffer();  // kDummyBufferBytes of zeros

private:
    // build() after the plan compiled, keeping the pipeline cache (update() falls back to it).
    void buildPlan(const GraphDesc& desc, CompiledPlan plan, const CompileOptions& options);
    // The part of build() after the plan compiled; on failure build() calls discardBuild().
    void install(const GraphDesc& desc, CompiledPlan plan, const CompileOptions& options);
    void discardBuild(const std::string& error);
    void allocate();
    void compilePasses();
    void recordPass(const vk::raii::CommandBuffer& cmd, size_t node, double& passCpuMs);
    void carryRings(const vk::raii::CommandBuffer& cmd, size_t node, bool allOutputs) const;
    void recordBarrier(const vk::raii::CommandBuffer& cmd, const BarrierPlan* plan) const;
    void recordBufferInit(const vk::raii::CommandBuffer& cmd) const;
    // Runs a pass's compile or execute and adds the device allocations it made to
    // PassRecord::allocationsOutsidePlan (the graph's own, e.g. a lazily made dummy, excluded).
    void attributeAllocations(size_t node, const std::function<void()>& call);
    uint64_t cacheKey(size_t node) const;
    size_t slotOf(const RuntimeResource& r, uint32_t delay) const;

    gpu::Context& mGpu;
    const PassRegistry& mRegistry;
    GraphDesc mDesc;
    CompiledPlan mPlan;
    std::vector<PassRecord> mRecords;
    uint64_t mGraphAllocations = 0;  // allocations of dummyImage/dummyBuffer
    std::vector<std::unique_ptr<RuntimeResource>> mResources;  // parallel to mPlan.resources
    std::map<std::string, std::unique_ptr<RuntimeResource>> mKeptHistory;  // across rebuilds
    std::vector<std::shared_ptr<gpu::MemoryBlock>> mBlocks;
    std::map<vk::Format, std::unique_ptr<gpu::Image>> mDummies;
    static constexpr size_t kDummyBufferBytes = 256;
    std::unique_ptr<gpu::Buffer> mDummyBuffer;
    std::vector<uint64_t> mLastCacheKey;  // per node; 0 = never ran
    std::unique_ptr<gpu::TimestampPool> mTimestamps;
    // Dispatch profiling: the pool (made on the first profiled frame) and this frame's dispatches.
    void collectDispatchTimes();
    struct ProfiledDispatch {
        size_t node;
        std::string shader;
    };
    bool mProfileDispatches = false;
    bool mDispatchOpen = false;  // a begin was written whose end is due
    std::unique_ptr<gpu::TimestampPool> mDispatchTimestamps;
    std::vector<ProfiledDispatch> mFrameDispatches;
    std::unique_ptr<vk::raii::CommandPool> mCommandPool;
    std::unique_ptr<vk::raii::CommandBuffer> mCommandBuffer;
    std::unique_ptr<vk::raii::Fence> mFence;
    FrameInfo mFrame;
    const scene::SceneGpu* mScene = nullptr;
    std::unique_ptr<scene::FrameCamera> mCamera;
    std::unique_ptr<gpu::Buffer> mCameraBuffer;  // host-visible; frames run one at a time
    uint64_t mAllocatedTransient = 0, mAllocatedPersistent = 0;
    std::map<std::string, std::unique_ptr<gpu::ComputePipeline>> mPipelineCache;
    uint32_t mPipelinesCreated = 0, mPipelinesReused = 0;
    bool mBuilt = false;
    std::string mBuildError;  // what the last failed build() threw
};

}  // namespace fovea::graph
