#include "passes/Combine/CombinePass.h"

#include "core/vk/ComputePipeline.h"

namespace fovea::passes {

void CombinePass::params(graph::ParamVisitor& v) {
    v.add("weightA", mWeightA, 1.0f, "weight of input a (all four channels, alpha included)",
          {-1e6, 1e6});
    v.add("weightB", mWeightB, 1.0f, "weight of input b (all four channels, alpha included)",
          {-1e6, 1e6});
    v.add("absolute", mAbsolute, false, "take the absolute value of the sum");
}

void CombinePass::reflect(graph::Reflection& r) const {
    r.input("a").floatOnly().doc("first image");
    r.input("b").sameAs("a").optional().floatOnly().doc(
        "second image (optional; may be a delayed history)");
    r.output("result", vk::Format::eR32G32B32A32Sfloat)
        .sameAs("a")
        .doc("weightA*a + weightB*b on all four channels, alpha included");
}

void CombinePass::compile(graph::CompileContext& ctx) {
    mPipeline = ctx.createPipeline("combine/combine.comp");
}

void CombinePass::execute(graph::ExecuteContext& ctx) {
    const auto& out = ctx.image("result");
    bool useB = ctx.connected("b") && ctx.historyValid("b");
    ctx.bindFields(*mPipeline);
    mPipeline->set("size", glm::ivec2(out.width(), out.height()))
        .set("weightA", mWeightA)
        .set("weightB", mWeightB)
        .set("useB", int(useB))
        .set("absolute", int(mAbsolute));
    ctx.dispatch(*mPipeline, out.width(), out.height());
}

}  // namespace fovea::passes
