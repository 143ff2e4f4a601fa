#include "passes/Unwarp/UnwarpPass.h"

#include <algorithm>

#include "core/graph/DenoiserInputs.h"
#include "core/sampling/VisualPolar.h"
#include "core/vk/ComputePipeline.h"
#include "core/vk/Resources.h"

namespace fovea::passes {

namespace {
constexpr int kMaxLevels = 4;           // level 0 (the input) + mip1..mip3
constexpr uint64_t kKeyBytes = 5 * 16;  // unwarp_lookup.comp: uvec4 key[5]
// unwarp_lookup.comp's unwarp_rebuild: 5 VkDispatchIndirectCommands padded to 16 bytes (the
// lookup rebuild, phi mip levels 1..3, unwarp.comp's fine dispatch), a uvec4 box per eye and
// the highest column the fine dispatch reads per eye (uint[2], padded to 16 bytes).
constexpr uint64_t kArgsStride = 16;
constexpr uint64_t kFineArgsOffset = 4 * kArgsStride;
constexpr uint64_t kRebuildArgsBytes = 8 * kArgsStride;
}  // namespace

void UnwarpPass::params(graph::ParamVisitor& v) {
    v.add("levels", mLevels, 4,
          "phi mip levels incl. the input (P5 §3.4: mipmaps along phi only); 1 = bilinear only",
          {1, kMaxLevels});
    v.add("blur", mBlur, true, "apply the foveated Gaussian blur (P5 §3.5); false = mapping only");
    v.add("blurSigma", mBlurSigma, 6.8f,
          "blur sigma in pixels at blurDegrees for a 1440-pixel-high eye image (P5 §3.5: 6.8 at "
          "1280x1440), scaled by height / 1440; clamped beyond blurDegrees",
          {0, 32});
    v.add("blurDegrees", mBlurDegrees, 30.0f,
          "eccentricity (degrees, from the camera's vertical field of view) where sigma reaches "
          "blurSigma; sigma rises linearly from 0 at the fovea's edge",
          {1, 90});
    v.add("cache", mCache, true,
          "keep the per-pixel sampling positions, mip level and blur sigma (P5 §3.4: precomputed "
          "per gaze and size) and recompute them only when the mapping, the field of view or "
          "these parameters change; false = every frame (benchmarks; same image)");
}

void UnwarpPass::reflect(graph::Reflection& r) const {
    r.input("color").floatOnly().doc("the Visual-Polar image (eye halves side by side)");
    graph::declareDenoiserInput(r, graph::DenoiserInput::VisualPolar, "`color` is in this mapping")
        .required();
    r.output("result", vk::Format::eR32G32B32A32Sfloat)
        .screen()
        .doc("the screen image (finite everywhere; a = the VP alpha, interpolated)");
    const auto rgba32 = vk::Format::eR32G32B32A32Sfloat;
    r.internal("mip1", rgba32).sameAs("color").doc("phi mip level 1 (pair averages, wrapped)");
    r.internal("mip2", rgba32).sameAs("color").doc("phi mip level 2");
    r.internal("mip3", rgba32).sameAs("color").doc("phi mip level 3");
    r.internal("unwarped", rgba32).doc("the mapped image before the blur");
    r.internal("blur_tmp", rgba32).doc("after the horizontal blur pass");
    r.internal("lookup", rgba32)
        .persistent()
        .doc(
            "per pixel: rho, t, mip level and the blur's sigma (P5 §3.4-3.5), kept while the "
            "mapping key does not change");
    r.internal("rebuild_args", vk::Format::eUndefined)
        .buffer(kRebuildArgsBytes)
        .indirect()
        .doc(
            "unwarp_rebuild block: the group counts of the lookup rebuild's indirect dispatches, "
            "0 when the mapping key is unchanged");
    r.internal("lookup_key", vk::Format::eUndefined)
        .buffer(kKeyBytes)
        .persistent()
        .doc("the mapping key `lookup` was built for (unwarp_lookup.comp mappingKey)");
}

void UnwarpPass::compile(graph::CompileContext& ctx) {
    mMips = ctx.createPipeline("visual_polar/phi_mips.comp");
    mLookup = ctx.createPipeline("visual_polar/unwarp_lookup.comp", {}, {"unwarp_rebuild"});
    mMap = ctx.createPipeline("visual_polar/unwarp.comp");
    mMapFine =
        ctx.createPipeline("visual_polar/unwarp.comp", {{"UNWARP_FINE", "1"}}, {"unwarp_rebuild"});
    mBlurRows = ctx.createPipeline("visual_polar/foveated_blur.comp");
    mBlurColumns =
        ctx.createPipeline("visual_polar/foveated_blur.comp", {{"FOVEATED_BLUR_VERTICAL", "1"}});
    mKeyStored = false;  // a new lookup_key buffer holds no key yet
}

void UnwarpPass::onReset() {
    mKeyStored = false;
}

void UnwarpPass::execute(graph::ExecuteContext& ctx) {
    const auto& vpImage = ctx.image("mip1");
    const auto& out = ctx.image("result");
    const int levels = std::clamp(mLevels, 1, kMaxLevels);
    // P5 §3.4-3.5: the sampling positions and sigma per pixel live in `lookup`. A one-thread
    // dispatch compares the mapping key with the stored one and writes the group count of the
    // rebuild (none when unchanged), so it costs no dispatch over the image for nothing: a
    // per-pixel branch would not skip the rebuild's math on llvmpipe (docs/passes/Unwarp.md
    // "Cost").
    const float sigmaMax = mBlurSigma * float(out.height()) / 1440.0f;
    const auto groups = mLookup->groupCount(out.width(), out.height());
    const auto mipGroups = mMips->groupCount(vpImage.width(), (vpImage.height() + 1) / 2);
    const gpu::Buffer& rebuildArgs = ctx.buffer("rebuild_args");
    ctx.bindFields(*mLookup);
    mLookup->bind("unwarp_rebuild", rebuildArgs)
        .set("levels", uint32_t(levels))
        .set("sigmaMax", sigmaMax)
        .set("blurDegrees", mBlurDegrees)
        .set("useCache", uint32_t(mCache && mKeyStored))
        .set("groupsX", groups[0])
        .set("groupsY", groups[1])
        .set("mipGroupsY", mipGroups[1])
        .set("mode", 0u);
    ctx.dispatch(*mLookup, 1, 1);
    mLookup->set("mode", 1u);
    ctx.dispatchIndirect(*mLookup, rebuildArgs);
    // The group counts of the fine mapping and of the phi mips, from the boxes of pixels with
    // L > 0 the rebuild grew (or kept).
    mLookup->set("mode", 2u);
    ctx.dispatch(*mLookup, 1, 1);
    // P5 §3.4: level k of a column holds ceil(n / 2^k) rows, each the average of two rows of
    // level k - 1 (wrapped); one dispatch per level (the context orders each after the last: one
    // image), over the columns the fine mapping reads (none for a level it never reads).
    ctx.bindFields(*mMips);
    for (int level = 1; level < levels; ++level) {
        mMips->set("level", uint32_t(level));
        ctx.dispatchIndirect(*mMips, rebuildArgs, kArgsStride * uint64_t(level));
    }
    // P5 §3.4's trilinear fetch only where a pixel covers more than one phi row (L > 0: the fovea
    // at the default reduction): the full-screen dispatch samples level 0, the fine one redoes
    // the pixels in each eye's box of L > 0 (the same arithmetic as one trilinear dispatch).
    ctx.bindFields(*mMap);
    mMap->set("levels", uint32_t(levels)).set("toResult", uint32_t(!mBlur));
    ctx.dispatch(*mMap, out.width(), out.height());
    ctx.bindFields(*mMapFine);
    mMapFine->bind("unwarp_rebuild", rebuildArgs)
        .set("levels", uint32_t(levels))
        .set("toResult", uint32_t(!mBlur));
    ctx.dispatchIndirect(*mMapFine, rebuildArgs, kFineArgsOffset);
    mKeyStored = true;
    if (!mBlur) return;
    // Two separable passes: rows into blur_tmp, then columns into result.
    ctx.bindFields(*mBlurRows);
    ctx.dispatch(*mBlurRows, out.width(), out.height());
    ctx.bindFields(*mBlurColumns);
    ctx.dispatch(*mBlurColumns, out.width(), out.height());
}

}  // namespace fovea::passes
