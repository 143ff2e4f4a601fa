// RenderGraph::update: a parameter edit recompiles only the passes whose parameters changed, and
// re-creates only the pipelines whose shader or defines changed (docs/architecture.md, "Executor").
#include "core/graph/GraphContexts.h"
#include "core/graph/RenderGraph.h"
#include "core/vk/ComputePipeline.h"

namespace fovea::graph {

namespace {

bool sameResource(const ResourcePlan& a, const ResourcePlan& b) {
    return a.name == b.name && a.producer == b.producer && a.field == b.field &&
           a.isImage == b.isImage && a.width == b.width && a.height == b.height &&
           a.format == b.format && a.bufferBytes == b.bufferBytes && a.lifetime == b.lifetime &&
           a.ringSize == b.ringSize && a.declaredHistory == b.declaredHistory &&
           a.firstUse == b.firstUse && a.lastUse == b.lastUse && a.aliasGroup == b.aliasGroup &&
           a.indirect == b.indirect && a.hostVisible == b.hostVisible && a.init == b.init &&
           a.contents == b.contents;
}

// Same shape: everything allocate(), the barrier plan and the executor depend on is equal, so
// the running graph's resources, timestamps and barriers serve the new plan unchanged.
bool samePlanShape(const CompiledPlan& a, const CompiledPlan& b) {
    if (a.nodes.size() != b.nodes.size() || a.order != b.order || a.orderEdges != b.orderEdges ||
        a.outputs != b.outputs || a.resourceOf != b.resourceOf ||
        a.resources.size() != b.resources.size() || a.inputs.size() != b.inputs.size() ||
        a.aliasGroups.size() != b.aliasGroups.size() || a.barriers.size() != b.barriers.size())
        return false;
    for (size_t i = 0; i < a.nodes.size(); ++i)
        if (a.nodes[i].name != b.nodes[i].name || a.nodes[i].type != b.nodes[i].type ||
            a.nodes[i].alive != b.nodes[i].alive)
            return false;
    for (size_t i = 0; i < a.resources.size(); ++i)
        if (!sameResource(a.resources[i], b.resources[i])) return false;
    for (auto ia = a.inputs.begin(), ib = b.inputs.begin(); ia != a.inputs.end(); ++ia, ++ib)
        if (ia->first != ib->first || ia->second.node != ib->second.node ||
            ia->second.field != ib->second.field || ia->second.delay != ib->second.delay ||
            ia->second.resource != ib->second.resource)
            return false;
    for (size_t i = 0; i < a.aliasGroups.size(); ++i)
        if (a.aliasGroups[i].members != b.aliasGroups[i].members) return false;
    for (size_t i = 0; i < a.barriers.size(); ++i)
        if (a.barriers[i].position != b.barriers[i].position ||
            a.barriers[i].initialize != b.barriers[i].initialize)
            return false;
    return true;
}

std::string pipelineKey(const std::string& shaderPath,
                        const std::vector<std::pair<std::string, std::string>>& defines) {
    std::string key = shaderPath;
    for (const auto& [name, value] : defines) key += "\n" + name + "=" + value;
    return key;
}

}  // namespace

std::unique_ptr<gpu::ComputePipeline> RenderGraph::pipeline(
    const std::string& shaderPath,
    const std::vector<std::pair<std::string, std::string>>& defines) {
    auto& slot = mPipelineCache[pipelineKey(shaderPath, defines)];
    if (slot) {
        ++mPipelinesReused;
        return slot->share();
    }
    slot = std::make_unique<gpu::ComputePipeline>(mGpu, shaderPath, defines);
    ++mPipelinesCreated;
    return slot->share();
}

RenderGraph::UpdateResult RenderGraph::update(const GraphDesc& desc) {
    UpdateResult result;
    const uint32_t created = mPipelinesCreated, reused = mPipelinesReused;
    CompiledPlan plan = compileGraphPlan(desc, mRegistry, mPlan.options);  // throws: unchanged
    if (!mBuilt || !samePlanShape(mPlan, plan)) {
        buildPlan(desc, std::move(plan), mPlan.options);
        result.pipelinesCreated = mPipelinesCreated - created;
        result.pipelinesReused = mPipelinesReused - reused;
        return result;
    }
    // Compile the passes whose parameters changed first: an exception here leaves the running
    // graph as it was (the new instances live only in `plan`).
    std::vector<bool> keep(plan.nodes.size(), false);
    for (size_t n : plan.order) {
        keep[n] = saveParams(*mPlan.nodes[n].pass, false) == saveParams(*plan.nodes[n].pass, false);
        if (keep[n]) continue;
        GraphCompileContext ctx(*this, plan, n);
        attributeAllocations(n, [&] { plan.nodes[n].pass->compile(ctx); });
        result.recompiled.push_back(plan.nodes[n].name);
    }
    for (size_t n : plan.order)
        if (keep[n]) plan.nodes[n].pass = std::move(mPlan.nodes[n].pass);
    for (size_t n = 0; n < plan.nodes.size(); ++n)
        if (!keep[n]) mLastCacheKey[n] = 0;  // a new instance: its cached output is stale
    mPlan = std::move(plan);
    mDesc = desc;
    result.inPlace = true;
    result.pipelinesCreated = mPipelinesCreated - created;
    result.pipelinesReused = mPipelinesReused - reused;
    return result;
}

}  // namespace fovea::graph
