// Compile stages 4-5: culling with reasons, deterministic execution order.
#include <queue>
#include <set>

#include "core/graph/CompilerStages.h"
#include "core/util/Error.h"

namespace fovea::graph {

void cullPasses(CompiledPlan& plan) {
    // Scene needs: a pass that needs features the scene lacks is culled, not run on missing data.
    for (auto& node : plan.nodes) {
        if (!node.alive) continue;
        uint32_t missing = node.pass->sceneNeeds() & ~plan.options.sceneFeatures;
        if (missing) {
            std::string list;
            for (const auto& f : sceneFeatureNames(missing)) list += (list.empty() ? "" : ", ") + f;
            node.alive = false;
            node.cullReason = "the scene lacks " + list;
        }
    }
    // Propagate: a required input fed by a culled pass culls its consumer. Optional inputs are
    // simply disconnected. Iterate to a fixed point (graphs are small).
    for (bool changed = true; changed;) {
        changed = false;
        for (size_t n = 0; n < plan.nodes.size(); ++n) {
            PassNode& node = plan.nodes[n];
            if (!node.alive) continue;
            for (const FieldDesc& f : node.reflection.fields()) {
                if (f.kind != FieldKind::Input) continue;
                auto it = plan.inputs.find({n, f.name});
                if (it == plan.inputs.end() || plan.nodes[it->second.node].alive) continue;
                if (f.optional) {
                    plan.inputs.erase(it);
                    continue;
                }
                node.alive = false;
                node.cullReason = "input '" + f.name + "' comes from culled pass '" +
                                  plan.nodes[it->second.node].name + "'";
                changed = true;
                break;
            }
        }
    }
    // Reachability backwards from the marked outputs, over all data edges (delayed ones too: a
    // history feeds the output). Order-only edges carry no data and keep nothing alive.
    std::vector<bool> needed(plan.nodes.size(), false);
    std::vector<size_t> work;
    for (const auto& [n, field] : plan.outputs)
        if (plan.nodes[n].alive && !needed[n]) {
            needed[n] = true;
            work.push_back(n);
        }
    while (!work.empty()) {
        size_t n = work.back();
        work.pop_back();
        for (const auto& [key, src] : plan.inputs)
            if (key.first == n && plan.nodes[src.node].alive && !needed[src.node]) {
                needed[src.node] = true;
                work.push_back(src.node);
            }
    }
    for (size_t n = 0; n < plan.nodes.size(); ++n)
        if (plan.nodes[n].alive && !needed[n]) {
            plan.nodes[n].alive = false;
            plan.nodes[n].cullReason = "reaches no marked output";
        }
    // Drop the edges of culled consumers so later stages see only live data flow.
    for (auto it = plan.inputs.begin(); it != plan.inputs.end();)
        it = plan.nodes[it->first.first].alive ? std::next(it) : plan.inputs.erase(it);

    bool anyOutput = false;
    for (const auto& [n, field] : plan.outputs) anyOutput |= plan.nodes[n].alive;
    if (!anyOutput) {
        std::string why;
        for (const auto& [n, field] : plan.outputs)
            why += (why.empty() ? "" : "; ") + plan.nodes[n].name + ": " + plan.nodes[n].cullReason;
        throw InputError(plan.file, "/outputs", "every marked output was culled (" + why + ")");
    }
}

void orderPasses(CompiledPlan& plan) {
    // Kahn's algorithm over undelayed data edges and order edges; the ready set is a min-heap of
    // graph-file indices so the order is deterministic and follows the file where free.
    const size_t count = plan.nodes.size();
    std::vector<std::set<size_t>> next(count);
    std::vector<size_t> indegree(count, 0);
    auto link = [&](size_t a, size_t b) {
        if (a == b || !plan.nodes[a].alive || !plan.nodes[b].alive) return;
        if (next[a].insert(b).second) ++indegree[b];
    };
    for (const auto& [key, src] : plan.inputs)
        if (src.delay == 0) link(src.node, key.first);
    for (const auto& [a, b] : plan.orderEdges) link(a, b);
    std::priority_queue<size_t, std::vector<size_t>, std::greater<>> ready;
    for (size_t n = 0; n < count; ++n)
        if (plan.nodes[n].alive && indegree[n] == 0) ready.push(n);
    plan.order.clear();
    while (!ready.empty()) {
        size_t n = ready.top();
        ready.pop();
        plan.order.push_back(n);
        for (size_t m : next[n])
            if (--indegree[m] == 0) ready.push(m);
    }
    // checkEdges rejected cycles already; this guards the invariant for hand-built plans.
    size_t alive = 0;
    for (const auto& node : plan.nodes) alive += node.alive;
    if (plan.order.size() != alive)
        throw InputError(plan.file, "/edges", "cycle without delay among the passes");
}

}  // namespace fovea::graph
