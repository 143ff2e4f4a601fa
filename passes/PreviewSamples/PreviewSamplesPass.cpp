#include "passes/PreviewSamples/PreviewSamplesPass.h"

#include <algorithm>

#include "core/sampling/SampleLayout.h"
#include "core/scene/SceneFeatures.h"
#include "core/vk/ComputePipeline.h"

namespace fovea::passes {

namespace {
const std::vector<std::string> kMethods = {"omni", "viewport", "foveated"};
uint32_t indexOf(const std::vector<std::string>& list, const std::string& v) {
    return uint32_t(std::find(list.begin(), list.end(), v) - list.begin());
}
}  // namespace

void PreviewSamplesPass::params(graph::ParamVisitor& v) {
    v.add("method", mMethod, "foveated",
          "P4 §4.1's preview methods: omni (OD) = uniform over the equirect image, every texel "
          "alike; viewport (VP) = uniform over the HMD viewport (its image plane); foveated (FV) "
          "= eccentricity from the acuity CDF around the gaze (P4 Eq. 2-7), uniform angle",
          kMethods);
    v.add("budget", mBudget, 100000,
          "samples per frame, the same for every method (P4 §5: ~100,000 per 14 ms frame); "
          "several may land in one texel",
          {1, 1 << 26});
    v.add("inverse", mInverse, "polynomial",
          "foveated: the inverse CDF, P4 Eq. 7's fitted polynomial (as published) or the exact "
          "numerical inverse (Newton on Eq. 5; docs/preview.md compares them)",
          {"polynomial", "exact"});
    v.add("head", mHead, "forward",
          "where the HMD looks (viewport method): forward = the camera's forward direction (the "
          "eye moves inside a still viewport), gaze = the viewport turns with the gaze",
          {"forward", "gaze"});
    v.add("fovDeg", mFovDeg, 100.0f, "viewport: the HMD's vertical field of view in degrees",
          {1.0f, 179.0f});
    v.add("aspect", mAspect, 1.0f, "viewport: the HMD eye image's width / height", {0.1f, 10.0f});
    v.add("seed", mSeed, 0, "mixed with the run's --seed and the frame index", {0, 2147483647});
}

void PreviewSamplesPass::reflect(graph::Reflection& r) const {
    r.output(sampling::kSampleLayoutField, vk::Format::eUndefined)
        .bufferPerPixel(sampling::kSampleLayoutEntryBytes, sampling::kSampleLayoutHeaderBytes)
        .doc(
            "sample layout of the equirect texels this frame's samples landed in, row-major, "
            "each with its number of samples (sum of counts = budget)");
    r.internal("counts", vk::Format::eUndefined)
        .bufferPerPixel(4)
        .doc("samples per equirect texel of this frame");
}

void PreviewSamplesPass::validate(const graph::ValidateContext& ctx) const {
    sampling::checkSampleLayoutSize(ctx.width(), ctx.height());
    // The samples are directions on the sphere binned into equirect texels: with a loaded scene
    // the camera must be the equirect one, else PathTrace would trace them through a pinhole.
    const uint32_t f = ctx.sceneFeatures();
    if ((f & scene::kSceneGeometry) && !(f & scene::kSceneEquirect))
        ctx.fail("method",
                 "PreviewSamples bins samples into a 360° equirect image: run with "
                 "--camera-model equirect (or defaults.camera_model / a camera path's "
                 "camera_model)");
}

void PreviewSamplesPass::compile(graph::CompileContext& ctx) {
    mClear = ctx.createPipeline("preview_samples/clear.comp");
    mGenerate = ctx.createPipeline("preview_samples/generate.comp");
    mCompact =
        ctx.createPipeline("preview_samples/compact.comp", {}, {sampling::kSampleLayoutBinding});
}

void PreviewSamplesPass::execute(graph::ExecuteContext& ctx) {
    const auto& frame = ctx.frame();
    const glm::uvec2 size(std::max(frame.width, 1u), std::max(frame.height, 1u));
    const uint64_t seed = frame.seed + uint64_t(uint32_t(mSeed)) * 0x9E3779B97F4A7C15ull;
    const auto& counts = ctx.buffer("counts");

    mClear->bind("counts", counts).set("size", size);
    ctx.dispatch(*mClear, size.x, size.y);

    ctx.bindFields(*mGenerate);
    mGenerate->set("size", size)
        .set("budget", uint32_t(mBudget))
        .set("method", indexOf(kMethods, mMethod))
        .set("exactInverse", uint32_t(mInverse == "exact"))
        .set("headFollowsGaze", uint32_t(mHead == "gaze"))
        .set("tanHalfFov", std::tan(0.5f * glm::radians(mFovDeg)))
        .set("aspect", mAspect)
        .set("seedLo", uint32_t(seed))
        .set("seedHi", uint32_t(seed >> 32))
        .set("frame", uint32_t(frame.index));
    ctx.dispatch(*mGenerate, uint32_t(mBudget));

    mCompact->bind("counts", counts);
    mCompact->bind(sampling::kSampleLayoutBinding, ctx.buffer(sampling::kSampleLayoutField));
    mCompact->set("size", size);
    ctx.dispatch(*mCompact, 256);  // one workgroup (see the shader)
}

}  // namespace fovea::passes
