// Compile stage 6: one resource per live output/internal: sizes, formats, lifetimes, history
// rings, use intervals; input size rules and bypass pairs are checked here.
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/graph/CompilerStages.h"
#include "core/util/Error.h"

namespace fovea::graph {

namespace {

std::string sizeText(uint32_t w, uint32_t h) {
    return std::to_string(w) + "x" + std::to_string(h);
}

// The size a field's rule asks for, or false when it depends on an unresolved input.
bool ruleSize(const CompiledPlan& plan, size_t node, const FieldDesc& f, uint32_t& w, uint32_t& h) {
    const CompileOptions& o = plan.options;
    switch (f.size) {
        case SizeRule::Any:
        case SizeRule::Screen:
            w = o.width;
            h = o.height;
            return true;
        case SizeRule::Scaled:
            // Round up so a scaled buffer always covers the screen it is scaled from.
            w = std::max(1u, uint32_t(std::ceil(o.width * double(f.scale))));
            h = std::max(1u, uint32_t(std::ceil(o.height * double(f.scale))));
            return true;
        case SizeRule::Fixed:
            w = f.width;
            h = f.height;
            return true;
        case SizeRule::SameAsInput: {
            auto it = plan.inputs.find({node, f.sameAs});
            if (it == plan.inputs.end()) {  // optional input left open: fall back to screen
                w = o.width;
                h = o.height;
                return true;
            }
            auto res = plan.resourceOf.find({it->second.node, it->second.field});
            if (res == plan.resourceOf.end() || plan.resources[res->second].width == 0)
                return false;
            w = plan.resources[res->second].width;
            h = plan.resources[res->second].height;
            return true;
        }
        case SizeRule::Buffer:
            w = h = 0;
            return true;
    }
    return false;
}

// A bypassed pass's outputs are filled by vkCmdCopyImage from its inputs, which needs equal size
// and format. Checked here (not when pipelines exist) so `fovea validate` rejects what `fovea
// run` would. An unconnected bypass input is cleared instead, so it needs no check.
void checkBypassPairs(const CompiledPlan& plan) {
    for (size_t n : plan.order) {
        const PassNode& node = plan.nodes[n];
        for (const auto& [input, output] : node.pass->bypass()) {
            auto in = plan.inputs.find({n, input});
            auto out = plan.resourceOf.find({n, output});
            if (out == plan.resourceOf.end())
                throw std::logic_error("pass type " + node.type + ": bypass into '" + output +
                                       "', which is not an output");
            if (in == plan.inputs.end()) continue;
            const ResourcePlan& a = plan.resources[in->second.resource];
            const ResourcePlan& b = plan.resources[out->second];
            if (a.width != b.width || a.height != b.height || a.format != b.format || !a.isImage ||
                !b.isImage)
                throw InputError(plan.file, node.pointer,
                                 "pass '" + node.name + "' bypasses '" + input + "' into '" +
                                     output + "' but they differ in size or format");
        }
    }
}

}  // namespace

void resolveResources(CompiledPlan& plan) {
    plan.resources.clear();
    plan.resourceOf.clear();
    // Create every resource, then resolve sizes until no progress (same-as-input chains may run
    // through delayed edges whose producer comes later in the order).
    for (int pos = 0; pos < int(plan.order.size()); ++pos) {
        size_t n = plan.order[pos];
        for (const FieldDesc& f : plan.nodes[n].reflection.fields()) {
            if (f.kind == FieldKind::Input) continue;
            if (f.size == SizeRule::SameAsInput && !plan.nodes[n].reflection.find(f.sameAs))
                throw std::logic_error("pass type " + plan.nodes[n].type + ": field '" + f.name +
                                       "' is sized like unknown input '" + f.sameAs + "'");
            ResourcePlan r;
            r.name = plan.nodes[n].name + "." + f.name;
            r.producer = n;
            r.field = f.name;
            r.isImage = f.isImage();
            r.format = f.format;
            r.bufferBytes =
                f.isImage() ? 0 : f.buffer.bytes(plan.options.width, plan.options.height);
            r.indirect = f.indirect;
            r.hostVisible = f.hostVisible;
            r.init = f.init;
            r.contents = f.contents;
            r.firstUse = r.lastUse = pos;
            if (f.persistent || plan.nodes[n].pass->cacheable()) r.lifetime = Lifetime::Persistent;
            if (f.historyFrames > 0) {  // images only (checked by reflectPasses)
                r.lifetime = Lifetime::History;
                r.declaredHistory = f.historyFrames;
                r.ringSize = f.historyFrames + 1;
            }
            plan.resourceOf[{n, f.name}] = plan.resources.size();
            plan.resources.push_back(r);
        }
    }
    for (bool progress = true; progress;) {
        progress = false;
        for (auto& r : plan.resources) {
            if (!r.isImage || r.width != 0) continue;
            const FieldDesc& f = *plan.nodes[r.producer].reflection.find(r.field);
            if (ruleSize(plan, r.producer, f, r.width, r.height)) progress = true;
        }
    }
    for (const auto& r : plan.resources)
        if (r.isImage && r.width == 0)
            throw InputError(plan.file, "/edges",
                             "cannot resolve the size of '" + r.name +
                                 "': its same-as-input chain loops through delayed edges");

    // Buffers sized by an input's image (FieldDesc::sizeOf); an open input means the screen.
    for (auto& r : plan.resources) {
        const FieldDesc& f = *plan.nodes[r.producer].reflection.find(r.field);
        if (r.isImage || f.sizeOf.empty()) continue;
        auto in = plan.inputs.find({r.producer, f.sizeOf});
        if (in == plan.inputs.end()) continue;
        const ResourcePlan& source =
            plan.resources[plan.resourceOf.at({in->second.node, in->second.field})];
        if (source.isImage) r.bufferBytes = f.buffer.bytes(source.width, source.height);
    }

    // Connect inputs, check their size rules, extend lifetimes, mark history rings.
    for (auto& [key, src] : plan.inputs) {
        const auto& [n, field] = key;
        src.resource = plan.resourceOf.at({src.node, src.field});
        ResourcePlan& r = plan.resources[src.resource];
        const FieldDesc& f = *plan.nodes[n].reflection.find(field);
        if (f.isImage() && f.size != SizeRule::Any) {
            uint32_t w = 0, h = 0;
            if (ruleSize(plan, n, f, w, h) && (w != r.width || h != r.height))
                throw InputError(
                    plan.file, src.pointer,
                    "size mismatch: '" + r.name + "' is " + sizeText(r.width, r.height) + " but '" +
                        plan.nodes[n].name + "." + field + "' expects " + sizeText(w, h) + " (" +
                        sizeRuleName(f.size) +
                        (f.size == SizeRule::SameAsInput ? " '" + f.sameAs + "'" : "") + ")");
        }
        if (src.delay > 0) {
            r.lifetime = Lifetime::History;
            r.ringSize = std::max(r.ringSize, src.delay + 1);
        } else {
            r.lastUse = std::max(r.lastUse, plan.positionOf(n));
        }
    }
    checkBypassPairs(plan);
    for (const auto& [n, field] : plan.outputs) {
        if (!plan.nodes[n].alive) continue;
        ResourcePlan& r = plan.resources[plan.resourceOf.at({n, field})];
        if (r.lifetime != Lifetime::History) r.lifetime = Lifetime::Output;
    }
    // Anything that outlives the frame is live for the whole frame.
    for (auto& r : plan.resources)
        if (r.lifetime != Lifetime::Transient) {
            r.firstUse = 0;
            r.lastUse = int(plan.order.size()) - 1;
        }
}

}  // namespace fovea::graph
