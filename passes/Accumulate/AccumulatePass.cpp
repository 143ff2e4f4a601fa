#include "passes/Accumulate/AccumulatePass.h"

#include "core/vk/ComputePipeline.h"

namespace fovea::passes {

void AccumulatePass::params(graph::ParamVisitor& v) {
    v.add("maxFrames", mMaxFrames, 0,
          "stop accumulating after this many frames (0 = never stop); the mean then stays",
          {0, 1 << 30});
    v.add("weight", mWeight, "frame",
          "frame: every frame counts once (a full image per frame); alpha: the input's alpha is "
          "the number of samples its value averages (PathTrace's radiance), added to the count, "
          "and a pixel with alpha 0 keeps its mean: progressive accumulation of scattered samples "
          "(seed 003 P4 §3, sum + count per texel)",
          {"frame", "alpha"});
}

void AccumulatePass::reflect(graph::Reflection& r) const {
    // rgba32f only: accumulating 8-bit data would quantize the reference (Blit converts).
    r.input("color", vk::Format::eR32G32B32A32Sfloat).doc("the frame to accumulate");
    r.output("mean", vk::Format::eR32G32B32A32Sfloat)
        .sameAs("color")
        .persistent()
        .doc("running mean of every finite sample since the last reset");
    r.output("count", vk::Format::eR32Sfloat)
        .sameAs("color")
        .persistent()
        .doc("per-pixel number of finite samples (weight alpha: the sum of their alphas)");
}

void AccumulatePass::compile(graph::CompileContext& ctx) {
    mPipeline = ctx.createPipeline("accumulate/accumulate.comp");
}

bool AccumulatePass::isActive(const graph::FrameInfo& frame) const {
    // After a reset the count restarts even if onReset was not called (fresh graph).
    int count = frame.framesSinceReset == 0 ? 0 : mCount;
    return mMaxFrames == 0 || count < mMaxFrames;
}

void AccumulatePass::execute(graph::ExecuteContext& ctx) {
    bool restart = ctx.frame().framesSinceReset == 0 || mCount == 0;
    if (ctx.frame().framesSinceReset == 0) mCount = 0;
    ++mCount;
    const auto& out = ctx.image("mean");
    ctx.bindFields(*mPipeline);
    mPipeline->set("size", glm::ivec2(out.width(), out.height()))
        .set("restart", int(restart))
        .set("alphaWeight", int(mWeight == "alpha"));
    ctx.dispatch(*mPipeline, out.width(), out.height());
}

}  // namespace fovea::passes
