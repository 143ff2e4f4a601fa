// Compile stage 7: transient images whose lifetimes do not overlap share memory (greedy interval
// colouring).
#include <algorithm>

#include "core/graph/CompilerStages.h"

namespace fovea::graph {

void aliasResources(CompiledPlan& plan) {
    plan.aliasGroups.clear();
    for (auto& r : plan.resources) r.aliasGroup = -1;
    if (!plan.options.aliasing) return;
    std::vector<size_t> transient;
    for (size_t i = 0; i < plan.resources.size(); ++i)
        if (plan.resources[i].lifetime == Lifetime::Transient && plan.resources[i].isImage)
            transient.push_back(i);
    // Greedy interval colouring: by first use; join the free group whose size is closest.
    std::stable_sort(transient.begin(), transient.end(), [&](size_t a, size_t b) {
        return plan.resources[a].firstUse < plan.resources[b].firstUse;
    });
    std::vector<int> groupLastUse;
    for (size_t i : transient) {
        ResourcePlan& r = plan.resources[i];
        int best = -1;
        uint64_t bestCost = ~0ull;
        for (size_t g = 0; g < plan.aliasGroups.size(); ++g) {
            if (groupLastUse[g] >= r.firstUse) continue;  // still in use: lifetimes overlap
            uint64_t gb = plan.aliasGroups[g].bytes, rb = r.bytes();
            uint64_t cost = gb > rb ? gb - rb : rb - gb;
            if (cost < bestCost) {
                bestCost = cost;
                best = int(g);
            }
        }
        if (best < 0) {
            best = int(plan.aliasGroups.size());
            plan.aliasGroups.emplace_back();
            groupLastUse.push_back(-1);
        }
        AliasGroup& g = plan.aliasGroups[best];
        g.members.push_back(i);
        g.bytes = std::max(g.bytes, r.bytes());
        groupLastUse[best] = r.lastUse;
        r.aliasGroup = best;
    }
}

}  // namespace fovea::graph
