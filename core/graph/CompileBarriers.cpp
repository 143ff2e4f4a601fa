// Compile stage 8: barriers between passes (read-after-write and aliasing hand-overs, with
// reasons).
#include <algorithm>

#include "core/graph/CompilerStages.h"

namespace fovea::graph {

void planBarriers(CompiledPlan& plan) {
    plan.barriers.clear();
    // One global memory barrier covers every write before it, so a read only needs a barrier
    // when its writer ran after the last one. Aliased images get a layout initialization at
    // their first write (the previous member's content is garbage by then).
    int lastBarrier = -1;
    for (int pos = 0; pos < int(plan.order.size()); ++pos) {
        size_t n = plan.order[pos];
        BarrierPlan b;
        b.position = pos;
        for (const auto& [key, src] : plan.inputs) {
            if (key.first != n || src.delay > 0) continue;
            int writer = plan.positionOf(src.node);
            // A barrier at position p sits before pass p, so it covers writers at positions < p.
            if (writer >= lastBarrier && writer < pos)
                b.hazards.push_back("RAW " + plan.nodes[n].name + "." + key.second + " <- " +
                                    plan.resources[src.resource].name);
        }
        for (size_t i = 0; i < plan.resources.size(); ++i) {
            const ResourcePlan& r = plan.resources[i];
            if (r.aliasGroup < 0 || r.firstUse != pos) continue;
            b.initialize.push_back(i);
            const auto& members = plan.aliasGroups[r.aliasGroup].members;
            auto it = std::find(members.begin(), members.end(), i);
            if (it != members.begin())
                b.hazards.push_back("WAR alias " + r.name + " reuses the memory of " +
                                    plan.resources[*(it - 1)].name);
        }
        if (!b.hazards.empty() || !b.initialize.empty()) {
            plan.barriers.push_back(b);
            lastBarrier = pos;
        }
    }
}

}  // namespace fovea::graph
