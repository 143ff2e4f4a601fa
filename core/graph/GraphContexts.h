// The CompileContext / ExecuteContext a RenderGraph hands to one pass.
#pragma once
#include "core/graph/GraphPlan.h"
#include "core/graph/Pass.h"
#include "core/vk/DispatchHazards.h"
#include "core/vk/ShaderReflection.h"

namespace fovea::graph {

class RenderGraph;

class GraphCompileContext : public CompileContext {
public:
    GraphCompileContext(RenderGraph& graph, const CompiledPlan& plan, size_t node)
        : mGraph(graph), mPlan(plan), mNode(node) {}
    gpu::Context& gpu() override;
    const FrameInfo& renderSize() const override { return mSize; }
    ResourceExtent extent(const std::string& field) const override;
    bool connected(const std::string& input) const override;
    std::unique_ptr<gpu::ComputePipeline> createPipeline(
        const std::string& shaderPath,
        const std::vector<std::pair<std::string, std::string>>& defines,
        const std::vector<std::string>& extraResources) override;
    const scene::SceneGpu* scene() const override;
    std::string resolvePath(const std::string& path) const override;

private:
    RenderGraph& mGraph;
    const CompiledPlan& mPlan;
    size_t mNode;
    FrameInfo mSize{0, 0, 0, mPlan.options.width, mPlan.options.height};
};

class GraphExecuteContext : public ExecuteContext {
public:
    GraphExecuteContext(RenderGraph& graph, const CompiledPlan& plan, size_t node,
                        const vk::raii::CommandBuffer& cmd, const FrameInfo& frame)
        : mGraph(graph), mPlan(plan), mNode(node), mCmd(cmd), mFrame(frame) {}
    gpu::Context& gpu() override;
    const vk::raii::CommandBuffer& cmd() override { return mCmd; }
    const FrameInfo& frame() const override { return mFrame; }
    bool connected(const std::string& input) const override;
    const gpu::Image& image(const std::string& field) override;
    const gpu::Buffer& buffer(const std::string& field) override;
    bool historyValid(const std::string& field, uint32_t framesBack) const override;
    const gpu::Image& previous(const std::string& field, uint32_t framesBack) override;
    std::optional<uint64_t> inputVersion(const std::string& input) const override;
    void bindFields(gpu::ComputePipeline& pipeline) override;
    void bindField(gpu::ComputePipeline& pipeline, const std::string& binding,
                   const std::string& field) override;
    const scene::SceneGpu* scene() const override;
    const scene::FrameCamera& camera() const override;
    void dispatch(gpu::ComputePipeline& pipeline, uint32_t threadsX, uint32_t threadsY,
                  uint32_t threadsZ) override;
    void dispatchIndirect(gpu::ComputePipeline& pipeline, const gpu::Buffer& args,
                          vk::DeviceSize offset) override;
    // What this execution dispatched and the barriers derived between its dispatches.
    const gpu::DispatchHazards& hazards() const { return mHazards; }

private:
    void bindResource(gpu::ComputePipeline& pipeline, const gpu::ShaderBinding& binding,
                      const FieldDesc& field);
    RenderGraph& mGraph;
    const CompiledPlan& mPlan;
    size_t mNode;
    const vk::raii::CommandBuffer& mCmd;
    const FrameInfo& mFrame;
    gpu::DispatchHazards mHazards;
};

}  // namespace fovea::graph
