// Text and JSON dumps of a compiled plan (fovea validate --dump, tests, the inspector).
#include <sstream>

#include "core/graph/CompilerStages.h"
#include "core/vk/Formats.h"

namespace fovea::graph {

nlohmann::json dumpPlanJson(const CompiledPlan& plan) {
    using nlohmann::json;
    json j;
    j["file"] = plan.file;
    j["size"] = {plan.options.width, plan.options.height};
    j["aliasing"] = plan.options.aliasing;
    json passes = json::array();
    for (size_t n = 0; n < plan.nodes.size(); ++n) {
        const PassNode& node = plan.nodes[n];
        json p = {{"name", node.name}, {"type", node.type}, {"alive", node.alive}};
        if (!node.alive) p["reason"] = node.cullReason;
        p["position"] = plan.positionOf(n);
        passes.push_back(p);
    }
    j["passes"] = passes;
    json order = json::array();
    for (size_t n : plan.order) order.push_back(plan.nodes[n].name);
    j["order"] = order;
    json resources = json::array();
    for (const auto& r : plan.resources) {
        json jr = {{"name", r.name},
                   {"lifetime", lifetimeName(r.lifetime)},
                   {"first_use", r.firstUse},
                   {"last_use", r.lastUse},
                   {"alias_group", r.aliasGroup},
                   {"ring", r.ringSize},
                   {"declared_history", r.declaredHistory},
                   {"bytes", r.bytes()}};
        if (r.isImage) {
            jr["size"] = {r.width, r.height};
            jr["format"] = gpu::formatName(r.format);
        } else {
            jr["buffer_bytes"] = r.bufferBytes;
            jr["indirect"] = r.indirect;
            jr["host_visible"] = r.hostVisible;
            jr["init"] = bufferInitName(r.init);
        }
        resources.push_back(jr);
    }
    j["resources"] = resources;
    json groups = json::array();
    for (const auto& g : plan.aliasGroups) {
        json members = json::array();
        for (size_t m : g.members) members.push_back(plan.resources[m].name);
        groups.push_back({{"bytes", g.bytes}, {"members", members}});
    }
    j["alias_groups"] = groups;
    json barriers = json::array();
    for (const auto& b : plan.barriers) {
        json init = json::array();
        for (size_t r : b.initialize) init.push_back(plan.resources[r].name);
        barriers.push_back({{"before", plan.nodes[plan.order[b.position]].name},
                            {"position", b.position},
                            {"initialize", init},
                            {"hazards", b.hazards}});
    }
    j["barriers"] = barriers;
    j["memory"] = {{"transient_bytes", plan.transientBytes()},
                   {"transient_bytes_without_aliasing", plan.transientBytesWithoutAliasing()},
                   {"persistent_bytes", plan.persistentBytes()},
                   {"history_bytes", plan.historyBytes()}};
    return j;
}

std::string dumpPlanText(const CompiledPlan& plan) {
    std::ostringstream s;
    s << "graph " << plan.file << " at " << plan.options.width << "x" << plan.options.height
      << "\n\norder:\n";
    for (size_t pos = 0; pos < plan.order.size(); ++pos) {
        const PassNode& node = plan.nodes[plan.order[pos]];
        for (const auto& b : plan.barriers)
            if (b.position == int(pos))
                for (const auto& h : b.hazards) s << "     | barrier: " << h << "\n";
        s << "  " << pos << ". " << node.name << " (" << node.type << ")\n";
    }
    bool anyCulled = false;
    for (const auto& node : plan.nodes)
        if (!node.alive) {
            if (!anyCulled) s << "\nculled:\n";
            anyCulled = true;
            s << "  " << node.name << " (" << node.type << "): " << node.cullReason << "\n";
        }
    s << "\nresources:\n";
    for (const auto& r : plan.resources) {
        s << "  " << r.name << "  ";
        if (r.isImage)
            s << r.width << "x" << r.height << " " << gpu::formatName(r.format);
        else
            s << "buffer " << r.bufferBytes << " B" << (r.indirect ? " indirect" : "")
              << (r.hostVisible ? " host-visible" : "")
              << (r.init != BufferInit::Undefined ? std::string(" init ") + bufferInitName(r.init)
                                                  : std::string());
        s << "  " << lifetimeName(r.lifetime);
        if (r.ringSize > 1) s << " ring " << r.ringSize;
        if (r.declaredHistory > 0)
            s << " (pass keeps " << r.declaredHistory << " previous frame"
              << (r.declaredHistory > 1 ? "s" : "") << ")";
        s << "  live [" << r.firstUse << ", " << r.lastUse << "]";
        if (r.aliasGroup >= 0) s << "  alias group " << r.aliasGroup;
        s << "\n";
    }
    s << "\nmemory: transient " << plan.transientBytes() << " B (without aliasing "
      << plan.transientBytesWithoutAliasing() << " B), persistent " << plan.persistentBytes()
      << " B (of which history " << plan.historyBytes() << " B)\n";
    return s.str();
}

}  // namespace fovea::graph
