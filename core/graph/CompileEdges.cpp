// Compile stage 3: edges (fields exist, direction, formats, required inputs, outputs, cycles).
#include <algorithm>
#include <functional>
#include <set>
#include <stdexcept>

#include "core/graph/CompilerStages.h"
#include "core/util/DidYouMean.h"
#include "core/util/Error.h"
#include "core/vk/Formats.h"

namespace fovea::graph {

namespace {

std::string kindList(const Reflection& r, FieldKind kind) {
    std::string out;
    for (const auto& n : r.names(kind)) out += (out.empty() ? "" : ", ") + n;
    return out.empty() ? "none" : out;
}

// The field an endpoint names, with errors for unknown fields and wrong direction.
const FieldDesc& endpointField(const CompiledPlan& plan, const std::string& file,
                               const std::string& pointer, const Endpoint& ep, FieldKind wanted) {
    size_t n = plan.findNode(ep.pass);
    if (n == kNone) throw InputError(file, pointer, "unknown pass '" + ep.pass + "'");
    const PassNode& node = plan.nodes[n];
    const FieldDesc* f = node.reflection.find(ep.field);
    const char* want = wanted == FieldKind::Input ? "input" : "output";
    if (!f) {
        std::vector<std::string> candidates = node.reflection.names(wanted);
        throw InputError(file, pointer,
                         "pass '" + ep.pass + "' (" + node.type + ") has no " + want + " '" +
                             ep.field + "'" + didYouMean(ep.field, candidates) + " (" + want +
                             "s: " + kindList(node.reflection, wanted) + ")");
    }
    if (f->kind != wanted) {
        if (f->kind == FieldKind::Internal)
            throw InputError(
                file, pointer,
                "'" + ep.str() + "' is internal to pass '" + ep.pass + "' and cannot be connected");
        throw InputError(file, pointer,
                         "edge direction wrong: '" + ep.str() + "' is an " +
                             fieldKindName(f->kind) +
                             ", but edges go from an output ('from') to "
                             "an input ('to')");
    }
    return *f;
}

// Formats outside fovea's table are not integer ones as far as the compiler knows.
bool isIntegerFormat(vk::Format format) {
    try {
        return gpu::formatIsUint(format);
    } catch (const std::invalid_argument&) {
        return false;
    }
}

}  // namespace

void checkEdges(const GraphDesc& desc, CompiledPlan& plan) {
    const std::string& file = desc.file;
    for (const EdgeDesc& e : desc.edges) {
        const FieldDesc& from =
            endpointField(plan, file, e.pointer + "/from", e.from, FieldKind::Output);
        const FieldDesc& to = endpointField(plan, file, e.pointer + "/to", e.to, FieldKind::Input);
        if (from.isImage() != to.isImage())
            throw InputError(file, e.pointer,
                             "kind mismatch: '" + e.from.str() + "' is " +
                                 (from.isImage() ? "an image" : "a buffer") + " but '" +
                                 e.to.str() + "' expects " +
                                 (to.isImage() ? "an image" : "a buffer"));
        if (to.format != vk::Format::eUndefined && from.format != to.format)
            throw InputError(file, e.pointer,
                             "format mismatch: '" + e.from.str() + "' is " +
                                 gpu::formatName(from.format) + " but '" + e.to.str() +
                                 "' expects " + gpu::formatName(to.format));
        if (to.floatOnly && isIntegerFormat(from.format)) {
            const PassNode& reader = plan.nodes[plan.findNode(e.to.pass)];
            throw InputError(file, e.pointer,
                             "format not readable: pass '" + reader.name + "' (" + reader.type +
                                 ") reads input '" + e.to.field + "' as float, but '" +
                                 e.from.str() + "' is the integer format " +
                                 gpu::formatName(from.format));
        }
        InputSource src;
        src.node = plan.findNode(e.from.pass);
        src.field = e.from.field;
        src.delay = e.delay;
        src.pointer = e.pointer;
        plan.inputs[{plan.findNode(e.to.pass), e.to.field}] = src;
    }
    for (const OrderDesc& o : desc.order)
        plan.orderEdges.push_back({plan.findNode(o.before), plan.findNode(o.after)});
    for (const OutputDesc& o : desc.outputs) {
        endpointField(plan, file, o.pointer, o.source, FieldKind::Output);
        plan.outputs.push_back({plan.findNode(o.source.pass), o.source.field});
    }
    if (plan.outputs.empty())
        throw InputError(file, "/outputs", "the graph marks no outputs; nothing would be run");

    // Required inputs of enabled passes must be connected.
    for (size_t n = 0; n < plan.nodes.size(); ++n) {
        const PassNode& node = plan.nodes[n];
        if (!desc.passes[node.descIndex].enabled) continue;
        for (const FieldDesc& f : node.reflection.fields()) {
            if (f.kind != FieldKind::Input || f.optional) continue;
            if (!plan.inputs.count({n, f.name}))
                throw InputError(
                    file, node.pointer,
                    "missing required input: '" + node.name + "." + f.name +
                        "' has no edge (add {\"from\": \"<pass>.<output>\", \"to\": \"" +
                        node.name + "." + f.name + "\"})");
        }
    }

    // Cycles through undelayed edges (and order edges) cannot be scheduled. DFS with colours.
    std::vector<std::vector<std::pair<size_t, std::string>>> next(plan.nodes.size());
    for (const auto& [key, src] : plan.inputs)
        if (src.delay == 0)
            next[src.node].push_back({key.first, src.node == kNone ? "" : src.pointer});
    for (size_t i = 0; i < plan.orderEdges.size(); ++i)
        next[plan.orderEdges[i].first].push_back(
            {plan.orderEdges[i].second, desc.order[i].pointer});
    std::vector<int> colour(plan.nodes.size(), 0);
    std::vector<size_t> stack;
    std::function<void(size_t)> visit = [&](size_t n) {
        colour[n] = 1;
        stack.push_back(n);
        for (const auto& [m, pointer] : next[n]) {
            if (colour[m] == 1) {
                std::string cycle;
                auto it = std::find(stack.begin(), stack.end(), m);
                for (; it != stack.end(); ++it) cycle += plan.nodes[*it].name + " -> ";
                cycle += plan.nodes[m].name;
                throw InputError(file, pointer,
                                 "cycle without delay: " + cycle +
                                     " (give one edge of the cycle \"delay\": 1 to read the "
                                     "previous frame)");
            }
            if (colour[m] == 0) visit(m);
        }
        stack.pop_back();
        colour[n] = 2;
    };
    for (size_t n = 0; n < plan.nodes.size(); ++n)
        if (colour[n] == 0) visit(n);
}

}  // namespace fovea::graph
