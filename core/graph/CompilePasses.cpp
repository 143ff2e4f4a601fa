// Compile stages 1, 2 and 4b: one node per pass with its parameters, the passes' fields, and
// Pass::validate (parameters against each other and the edges).
#include <stdexcept>

#include "core/graph/CompilerStages.h"
#include "core/util/DidYouMean.h"
#include "core/util/Error.h"

namespace fovea::graph {

void instantiatePasses(const GraphDesc& desc, const PassRegistry& registry, CompiledPlan& plan) {
    plan.file = desc.file;
    for (size_t i = 0; i < desc.passes.size(); ++i) {
        const PassDesc& p = desc.passes[i];
        if (const std::string retired = registry.retiredHint(p.type); !retired.empty())
            throw InputError(desc.file, p.pointer + "/type",
                             "pass type '" + p.type + "' no longer exists: " + retired);
        if (!registry.find(p.type))
            throw InputError(desc.file, p.pointer + "/type",
                             "unknown pass type '" + p.type + "'" +
                                 didYouMean(p.type, registry.types()) +
                                 " (run 'fovea passes' for the list; a plugin's type needs "
                                 "--plugin LIB.so or FOVEA_PLUGIN_PATH)");
        PassNode node;
        node.name = p.name;
        node.type = p.type;
        node.pointer = p.pointer;
        node.descIndex = i;
        node.pass = registry.create(p.type, p.name);
        loadParams(*node.pass, p.params, desc.file, p.pointer + "/params");
        if (!p.enabled) {
            node.alive = false;
            node.cullReason = "disabled in the graph file (\"enabled\": false)";
        }
        plan.nodes.push_back(std::move(node));
    }
}

namespace {

// A pass author's mistakes in a field declaration (logic_error: not the graph file's fault).
void checkFieldDesc(const PassNode& node, const FieldDesc& f) {
    auto fail = [&](const std::string& what) {
        throw std::logic_error("pass type " + node.type + ": field '" + f.name + "' " + what);
    };
    const bool ownBuffer = f.kind != FieldKind::Input && !f.isImage();
    if (f.historyFrames > 0 && (f.kind == FieldKind::Input || !f.isImage()))
        fail("declares history but is not an output/internal image");
    if ((f.indirect || f.hostVisible || f.init != BufferInit::Undefined || !f.sizeOf.empty()) &&
        !ownBuffer)
        fail("asks for buffer usage or initial content but is not an output/internal buffer");
    if (f.init == BufferInit::Contents && (!f.contents || f.contentsBytes != f.buffer.bytes(1, 1) ||
                                           f.buffer.perPixel != 0 || f.buffer.perBlock != 0))
        fail("has contents whose size is not its fixed buffer size");
    if (f.hostVisible && f.indirect) fail("is both host-visible and indirect");
    if (!f.sizeOf.empty()) {
        const FieldDesc* in = node.reflection.find(f.sizeOf);
        if (!in || in->kind != FieldKind::Input || !in->isImage())
            fail("is sized by '" + f.sizeOf + "', which is not an image input");
    }
}

}  // namespace

void reflectPasses(CompiledPlan& plan) {
    for (auto& node : plan.nodes) {
        node.reflection = Reflection();
        node.pass->reflect(node.reflection);
        // A pass author's mistakes, caught the first time the pass type is compiled.
        for (const auto& f : node.reflection.fields()) checkFieldDesc(node, f);
    }
}

namespace {

class PlanValidateContext final : public ValidateContext {
public:
    PlanValidateContext(const CompiledPlan& plan, size_t node) : mPlan(plan), mNode(node) {}
    bool connected(const std::string& input) const override {
        return mPlan.inputs.count({mNode, input}) > 0;
    }
    uint32_t width() const override { return mPlan.options.width; }
    uint32_t height() const override { return mPlan.options.height; }
    uint32_t sceneFeatures() const override { return mPlan.options.sceneFeatures; }
    [[noreturn]] void fail(const std::string& param, const std::string& message) const override {
        const PassNode& node = mPlan.nodes[mNode];
        throw InputError(
            mPlan.file, node.pointer + "/params/" + param,
            "pass '" + node.name + "' (" + node.type + "): params." + param + ": " + message);
    }

private:
    const CompiledPlan& mPlan;
    size_t mNode;
};

}  // namespace

void validatePasses(CompiledPlan& plan) {
    for (size_t n = 0; n < plan.nodes.size(); ++n)
        if (plan.nodes[n].alive) plan.nodes[n].pass->validate(PlanValidateContext(plan, n));
}

}  // namespace fovea::graph
