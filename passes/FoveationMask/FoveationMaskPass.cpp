#include "passes/FoveationMask/FoveationMaskPass.h"

#include <algorithm>
#include <cmath>

#include "core/util/Error.h"
#include "core/vk/ComputePipeline.h"
#include "core/vk/Resources.h"

namespace fovea::passes {

namespace {
const std::vector<std::string> kUnits = {"pixels", "degrees"};
constexpr int kDefaultCapacity = 2048 * 2048;
}  // namespace

void FoveationMaskPass::params(graph::ParamVisitor& v) {
    // Defaults: seed 000 Table 1, FHD (960x1080 per eye): r0 = 144, r1 = 288 pixels, 4/3/2 spp;
    // §4.1: the toss probability p = 0.5 (the outer layer's 1 - p = 0.5 too, §3.2).
    v.add("r0", mR0, 144.0f, "fovea radius (every pixel sampled), in radiusUnit", {0, 1e6});
    v.add("r1", mR1, 288.0f,
          "outer radius of the middle ring (probability falls linearly from 1 at r0 to "
          "outerProbability at r1), in radiusUnit; >= r0",
          {0, 1e6});
    v.add("radiusUnit", mRadiusUnit, "pixels",
          "pixels: distance to the gaze point in pixels; degrees: eccentricity, the angle between "
          "the pixel's and the gaze point's view rays (from the camera's vertical FOV)",
          kUnits);
    v.add("outerProbability", mOuterProbability, 0.5f,
          "sampling probability beyond r1 (seed 000 §3.2: 1 - p, p = 0.5 in §4.1)", {0, 1});
    v.add("sppFovea", mSppFovea, 4, "samples per sampled fovea pixel (Table 1: 4)", {1, 65535});
    v.add("sppMiddle", mSppMiddle, 3, "samples per sampled middle-ring pixel (Table 1: 3)",
          {1, 65535});
    v.add("sppOuter", mSppOuter, 2, "samples per sampled outer pixel (Table 1: 2)", {1, 65535});
    v.add("seed", mSeed, 0, "seed of the random toss, mixed with the run's --seed",
          {0, 2147483647});
    v.add("animate", mAnimate, false,
          "a new random toss every frame (frame index in the seed); seed 000 §3.2 keeps the "
          "distribution fixed for all frames");
    v.add("capacity", mCapacity, kDefaultCapacity,
          "entries the layout buffer holds (16 + 8 * capacity bytes); must cover width * height",
          {1, 1 << 27});
}

void FoveationMaskPass::reflect(graph::Reflection& r) const {
    // Reflection has no buffer size rule that follows the screen, hence `capacity` (as SampleList).
    r.output(scene::kSampleLayoutField, vk::Format::eUndefined)
        .buffer(scene::sampleLayoutBytes(uint64_t(std::max(mCapacity, 1))))
        .doc(
            "sample layout: the sampled pixels of both eyes, row-major, each with its layer's spp");
    r.output("mask", vk::Format::eR32Uint)
        .doc(
            "bit 0: sampled (B of seed 000 Eq. 2); bits 1-2: layer (0 fovea, 1 middle, 2 outer); "
            "bits 16-31: samples (0 when not sampled)");
}

void FoveationMaskPass::check() const {
    auto fail = [&](const std::string& what) {
        throw RuntimeError("pass '" + name() + "' (FoveationMask): " + what);
    };
    if (!std::isfinite(mR0) || !std::isfinite(mR1) || mR0 < 0.0f)
        fail("params.r0 / params.r1 must be finite and >= 0");
    if (mR1 < mR0)
        fail("params.r1 = " + std::to_string(mR1) +
             " is smaller than params.r0 = " + std::to_string(mR0));
    if (mRadiusUnit == "degrees" && mR1 > 180.0f)
        fail("params.r1 = " + std::to_string(mR1) + " degrees exceeds 180 (radiusUnit degrees)");
}

void FoveationMaskPass::compile(graph::CompileContext& ctx) {
    check();
    const auto& size = ctx.renderSize();
    uint64_t pixels = uint64_t(size.width) * size.height;
    if (uint64_t(mCapacity) < pixels)
        throw RuntimeError("pass '" + name() + "' (FoveationMask): params.capacity = " +
                           std::to_string(mCapacity) + " entries cannot list the " +
                           std::to_string(size.width) + "x" + std::to_string(size.height) + " = " +
                           std::to_string(pixels) + " pixels; raise it");
    if (size.width > scene::kSampleLayoutMaxCoordinate + 1 ||
        size.height > scene::kSampleLayoutMaxCoordinate + 1)
        throw RuntimeError("pass '" + name() +
                           "' (FoveationMask): layouts store 16-bit coordinates; the image is " +
                           std::to_string(size.width) + "x" + std::to_string(size.height));
    mPipeline =
        ctx.createPipeline("foveation_mask/foveation_mask.comp", {}, {scene::kSampleLayoutBinding});
}

void FoveationMaskPass::execute(graph::ExecuteContext& ctx) {
    const auto& frame = ctx.frame();
    // Same seed rule as SampleList: run seed + pass seed, the frame index only when animated.
    uint32_t seed = scene::sampleListSeed(
        frame.seed + uint64_t(uint32_t(mSeed)) * 0x9E3779B97F4A7C15ull, frame.index, mAnimate);
    ctx.bindFields(*mPipeline);
    mPipeline->bind(scene::kSampleLayoutBinding, ctx.buffer(scene::kSampleLayoutField));
    mPipeline->set("size", glm::uvec2(std::max(frame.width, 1u), std::max(frame.height, 1u)))
        .set("radii", glm::vec2(mR0, mR1))
        .set("unitDegrees", uint32_t(mRadiusUnit == "degrees"))
        .set("outerProbability", mOuterProbability)
        .set("seed", seed)
        .set("sppFovea", uint32_t(std::clamp(mSppFovea, 1, 65535)))
        .set("sppMiddle", uint32_t(std::clamp(mSppMiddle, 1, 65535)))
        .set("sppOuter", uint32_t(std::clamp(mSppOuter, 1, 65535)));
    mPipeline->dispatch(ctx.cmd(), 256);  // one workgroup (see the shader)
}

}  // namespace fovea::passes
