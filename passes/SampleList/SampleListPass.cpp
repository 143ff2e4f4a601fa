#include "passes/SampleList/SampleListPass.h"

#include <algorithm>

#include "core/util/Error.h"
#include "core/vk/ComputePipeline.h"
#include "core/vk/Resources.h"

namespace fovea::passes {

namespace {
const std::vector<std::string> kPatterns = {"all", "checkerboard", "every_nth", "random"};
}  // namespace

void SampleListPass::params(graph::ParamVisitor& v) {
    v.add("pattern", mPattern, "all",
          "all: every pixel; checkerboard: (x + y) even; every_nth: linear pixel index % n == 0; "
          "random: each pixel with probability 'fraction' (seeded)",
          kPatterns);
    v.add("n", mN, 2, "every_nth: keep one pixel in n (row-major index)", {1, 1 << 30});
    v.add("fraction", mFraction, 0.5f, "random: probability of listing a pixel", {0, 1});
    v.add("seed", mSeed, 0, "random: seed, mixed with the run's --seed", {0, 2147483647});
    v.add("animate", mAnimate, false, "random: a new selection every frame (frame index in seed)");
    v.add("spp", mSpp, 1, "samples per listed pixel", {1, 65535});
}

void SampleListPass::reflect(graph::Reflection& r) const {
    // Room for every pixel of the render size (pattern "all").
    r.output(sampling::kSampleLayoutField, vk::Format::eUndefined)
        .bufferPerPixel(sampling::kSampleLayoutEntryBytes, sampling::kSampleLayoutHeaderBytes)
        .doc("sample layout: 16-byte header + one uvec2 (x | y << 16, spp) per listed pixel");
}

void SampleListPass::validate(const graph::ValidateContext& ctx) const {
    sampling::checkSampleLayoutSize(ctx.width(), ctx.height());
}

void SampleListPass::compile(graph::CompileContext& ctx) {
    mPipeline =
        ctx.createPipeline("sample_list/sample_list.comp", {}, {sampling::kSampleLayoutBinding});
}

sampling::SamplePatternOptions SampleListPass::options(const graph::FrameInfo& frame) const {
    sampling::SamplePatternOptions o;
    auto it = std::find(kPatterns.begin(), kPatterns.end(), mPattern);
    o.pattern = sampling::SamplePattern(it == kPatterns.end() ? 0 : it - kPatterns.begin());
    o.n = uint32_t(std::max(mN, 1));
    o.fraction = mFraction;
    o.seed = sampling::sampleListSeed(
        frame.seed + uint64_t(uint32_t(mSeed)) * 0x9E3779B97F4A7C15ull, frame.index, mAnimate);
    o.samples = uint32_t(std::max(mSpp, 1));
    return o;
}

void SampleListPass::execute(graph::ExecuteContext& ctx) {
    const auto& frame = ctx.frame();
    sampling::SamplePatternOptions o = options(frame);
    ctx.bindFields(*mPipeline);
    mPipeline->bind(sampling::kSampleLayoutBinding, ctx.buffer(sampling::kSampleLayoutField));
    mPipeline->set("size", glm::uvec2(std::max(frame.width, 1u), std::max(frame.height, 1u)))
        .set("pattern", uint32_t(o.pattern))
        .set("n", o.n)
        .set("threshold", sampling::sampleFractionThreshold(o.fraction))
        .set("seed", o.seed)
        .set("samples", o.samples);
    ctx.dispatch(*mPipeline, 256);  // one workgroup (see the shader)
}

}  // namespace fovea::passes
