#include "passes/FoveationMask/FoveationMaskPass.h"

#include <algorithm>
#include <cmath>

#include "core/util/Error.h"
#include "core/vk/ComputePipeline.h"
#include "core/vk/Resources.h"

namespace fovea::passes {

namespace {
const std::vector<std::string> kUnits = {"pixels", "degrees"};
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
}

void FoveationMaskPass::reflect(graph::Reflection& r) const {
    // Room for every pixel of the render size: a layout never lists a pixel twice.
    r.output(sampling::kSampleLayoutField, vk::Format::eUndefined)
        .bufferPerPixel(sampling::kSampleLayoutEntryBytes, sampling::kSampleLayoutHeaderBytes)
        .doc(
            "sample layout: the sampled pixels of both eyes, row-major, each with its layer's spp");
    r.output("mask", vk::Format::eR32Uint)
        .doc(
            "bit 0: sampled (B of seed 000 Eq. 2); bits 1-2: layer (0 fovea, 1 middle, 2 outer); "
            "bits 16-31: samples (0 when not sampled)");
}

void FoveationMaskPass::validate(const graph::ValidateContext& ctx) const {
    // The layers are discs around the gaze in a pinhole image (seed 000 §3.2); on a 360° image a
    // pixel radius means nothing (docs/camera-path.md "Camera models").
    if (ctx.sceneFeatures() & graph::kSceneEquirect)
        ctx.fail("radiusUnit",
                 "FoveationMask needs a perspective camera, not --camera-model equirect (360° "
                 "foveation is PreviewSamples' method foveated)");
    if (!std::isfinite(mR0) || !std::isfinite(mR1)) ctx.fail("r0", "r0 and r1 must be finite");
    if (mR1 < mR0)
        ctx.fail("r1", std::to_string(mR1) + " is smaller than r0 = " + std::to_string(mR0));
    if (mRadiusUnit == "degrees" && mR1 > 180.0f)
        ctx.fail("r1", std::to_string(mR1) + " degrees exceeds 180 (radiusUnit degrees)");
    sampling::checkSampleLayoutSize(ctx.width(), ctx.height());
}

void FoveationMaskPass::compile(graph::CompileContext& ctx) {
    mPipeline = ctx.createPipeline("foveation_mask/foveation_mask.comp", {},
                                   {sampling::kSampleLayoutBinding});
}

void FoveationMaskPass::execute(graph::ExecuteContext& ctx) {
    const auto& frame = ctx.frame();
    // Same seed rule as SampleList: run seed + pass seed, the frame index only when animated.
    uint32_t seed = sampling::sampleListSeed(
        frame.seed + uint64_t(uint32_t(mSeed)) * 0x9E3779B97F4A7C15ull, frame.index, mAnimate);
    ctx.bindFields(*mPipeline);
    mPipeline->bind(sampling::kSampleLayoutBinding, ctx.buffer(sampling::kSampleLayoutField));
    mPipeline->set("size", glm::uvec2(std::max(frame.width, 1u), std::max(frame.height, 1u)))
        .set("radii", glm::vec2(mR0, mR1))
        .set("unitDegrees", uint32_t(mRadiusUnit == "degrees"))
        .set("outerProbability", mOuterProbability)
        .set("seed", seed)
        .set("sppFovea", uint32_t(std::clamp(mSppFovea, 1, 65535)))
        .set("sppMiddle", uint32_t(std::clamp(mSppMiddle, 1, 65535)))
        .set("sppOuter", uint32_t(std::clamp(mSppOuter, 1, 65535)));
    ctx.dispatch(*mPipeline, 256);  // one workgroup (see the shader)
}

}  // namespace fovea::passes
