// The compile driver (compileGraphPlan runs the stages in order) and the plan's lookups and
// memory figures.
#include "core/graph/CompilerStages.h"
#include "core/vk/Formats.h"

namespace fovea::graph {

size_t CompiledPlan::findNode(const std::string& name) const {
    for (size_t i = 0; i < nodes.size(); ++i)
        if (nodes[i].name == name) return i;
    return kNone;
}

int CompiledPlan::positionOf(size_t node) const {
    for (size_t i = 0; i < order.size(); ++i)
        if (order[i] == node) return static_cast<int>(i);
    return -1;
}

const char* lifetimeName(Lifetime l) {
    switch (l) {
        case Lifetime::Transient:
            return "transient";
        case Lifetime::Output:
            return "output";
        case Lifetime::History:
            return "history";
        case Lifetime::Persistent:
            return "persistent";
    }
    return "?";
}

uint64_t ResourcePlan::bytes() const {
    if (!isImage) return bufferBytes;
    return uint64_t(width) * height * gpu::formatBytesPerPixel(format);
}

uint64_t CompiledPlan::historyBytes() const {
    uint64_t total = 0;
    for (const auto& r : resources)
        if (r.lifetime == Lifetime::History) total += r.bytes() * (r.ringSize - 1);
    return total;
}

uint64_t CompiledPlan::transientBytes() const {
    uint64_t total = 0;
    for (const auto& g : aliasGroups) total += g.bytes;
    for (const auto& r : resources)
        if (r.lifetime == Lifetime::Transient && r.aliasGroup < 0) total += r.bytes();
    return total;
}

uint64_t CompiledPlan::transientBytesWithoutAliasing() const {
    uint64_t total = 0;
    for (const auto& r : resources)
        if (r.lifetime == Lifetime::Transient) total += r.bytes();
    return total;
}

uint64_t CompiledPlan::persistentBytes() const {
    uint64_t total = 0;
    for (const auto& r : resources)
        if (r.lifetime != Lifetime::Transient) total += r.bytes() * r.ringSize;
    return total;
}

CompiledPlan compileGraphPlan(const GraphDesc& desc, const PassRegistry& registry,
                              const CompileOptions& options) {
    CompiledPlan plan;
    plan.options = options;
    instantiatePasses(desc, registry, plan);
    reflectPasses(plan);
    checkEdges(desc, plan);
    cullPasses(plan);
    validatePasses(plan);
    orderPasses(plan);
    resolveResources(plan);
    aliasResources(plan);
    planBarriers(plan);
    return plan;
}

}  // namespace fovea::graph
