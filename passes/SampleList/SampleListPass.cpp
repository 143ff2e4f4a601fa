#include "passes/SampleList/SampleListPass.h"

#include <algorithm>

#include "core/util/Error.h"
#include "core/vk/ComputePipeline.h"
#include "core/vk/Resources.h"

namespace fovea::passes {

namespace {
const std::vector<std::string> kPatterns = {"all", "checkerboard", "every_nth", "random"};
constexpr int kDefaultCapacity = 2048 * 2048;
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
    v.add("capacity", mCapacity, kDefaultCapacity,
          "entries the output buffer holds (16 + 8 * capacity bytes); must cover width * height",
          {1, 1 << 27});
}

void SampleListPass::reflect(graph::Reflection& r) const {
    // Reflection has no buffer size rule that follows the screen, hence the capacity parameter.
    r.output(scene::kSampleLayoutField, vk::Format::eUndefined)
        .buffer(scene::sampleLayoutBytes(uint64_t(std::max(mCapacity, 1))))
        .doc("sample layout: 16-byte header + one uvec2 (x | y << 16, spp) per listed pixel");
}

void SampleListPass::compile(graph::CompileContext& ctx) {
    const auto& size = ctx.renderSize();
    uint64_t pixels = uint64_t(size.width) * size.height;
    if (uint64_t(mCapacity) < pixels)
        throw RuntimeError(
            "pass '" + name() + "' (SampleList): params.capacity = " + std::to_string(mCapacity) +
            " entries cannot list the " + std::to_string(size.width) + "x" +
            std::to_string(size.height) + " = " + std::to_string(pixels) + " pixels; raise it");
    if (size.width > scene::kSampleLayoutMaxCoordinate + 1 ||
        size.height > scene::kSampleLayoutMaxCoordinate + 1)
        throw RuntimeError("pass '" + name() +
                           "' (SampleList): layouts store 16-bit coordinates; the image is " +
                           std::to_string(size.width) + "x" + std::to_string(size.height));
    mPipeline =
        ctx.createPipeline("sample_list/sample_list.comp", {}, {scene::kSampleLayoutBinding});
}

scene::SamplePatternOptions SampleListPass::options(const graph::FrameInfo& frame) const {
    scene::SamplePatternOptions o;
    auto it = std::find(kPatterns.begin(), kPatterns.end(), mPattern);
    o.pattern = scene::SamplePattern(it == kPatterns.end() ? 0 : it - kPatterns.begin());
    o.n = uint32_t(std::max(mN, 1));
    o.fraction = mFraction;
    o.seed = scene::sampleListSeed(frame.seed + uint64_t(uint32_t(mSeed)) * 0x9E3779B97F4A7C15ull,
                                   frame.index, mAnimate);
    o.samples = uint32_t(std::max(mSpp, 1));
    return o;
}

void SampleListPass::execute(graph::ExecuteContext& ctx) {
    const auto& frame = ctx.frame();
    scene::SamplePatternOptions o = options(frame);
    ctx.bindFields(*mPipeline);
    mPipeline->bind(scene::kSampleLayoutBinding, ctx.buffer(scene::kSampleLayoutField));
    mPipeline->set("size", glm::uvec2(std::max(frame.width, 1u), std::max(frame.height, 1u)))
        .set("pattern", uint32_t(o.pattern))
        .set("n", o.n)
        .set("threshold", scene::sampleFractionThreshold(o.fraction))
        .set("seed", o.seed)
        .set("samples", o.samples);
    mPipeline->dispatch(ctx.cmd(), 256);  // one workgroup (see the shader)
}

}  // namespace fovea::passes
