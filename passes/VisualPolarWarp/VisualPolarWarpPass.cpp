#include "passes/VisualPolarWarp/VisualPolarWarpPass.h"

#include <cmath>

#include "core/sampling/BlockGrid.h"
#include "core/sampling/VisualPolar.h"
#include "core/vk/ComputePipeline.h"
#include "core/vk/Resources.h"

namespace fovea::passes {

void VisualPolarWarpPass::params(graph::ParamVisitor& v) {
    v.add("reduction", mReduction, 0.61f,
          "share of the screen's samples saved (P5 §4.2: 0.61; 0.5-0.88): both VP axes are the "
          "screen's times sqrt((1 - reduction) / (1 - foveaFraction / 2))",
          {0.5, 0.88});
    v.add("foveaFraction", mFoveaFraction, 0.24f,
          "rho_f, the fovea's share of the rho axis: linear rho and the triangular phi clip "
          "inside it (P5 §3.2: the clip removes foveaFraction / 2 = 12 % of the space)",
          {sampling::kVisualPolarMinFoveaFraction, 0.5});
    v.add("traceOffscreen", mTraceOffscreen, false,
          "also trace texels whose ray leaves the screen (P5 traced them; §7 lists skipping as "
          "an optimization)");
    v.add("staircase", mStaircase, false,
          "P5 §3.3's staircase clip for BMFR: every 32-column block column (P2 §6.1's moving "
          "block grid, this frame's offset) takes the phi height of its last column, so a BMFR "
          "block never mixes heights; BMFR with the `vp` input follows the warp's x offset. "
          "More texels are traced than with the triangular clip (the fovea is never thinner); "
          "the grid moves every frame, so the warp re-runs every frame. false = the triangular "
          "clip (P5 §3.2), cached while the gaze and size do not change");
}

void VisualPolarWarpPass::reflect(graph::Reflection& r) const {
    float scale = float(sampling::visualPolarScale(mReduction, mFoveaFraction));
    r.output("coords", vk::Format::eR32G32B32A32Sfloat)
        .scaled(scale)
        .doc(
            "per VP texel (eye halves side by side): xy screen position of its primary ray "
            "(pixels of the side-by-side image), z 1 = traced (0 = clipped or off-screen), w eye");
    r.output("vp", vk::Format::eUndefined)
        .buffer(sampling::kVisualPolarParamsBytes)
        .doc(
            "the mapping's parameters (visual_polar.glsl VisualPolarParams): grid, fovea, gaze, "
            "staircase offsets (this and the previous frame)");
}

void VisualPolarWarpPass::validate(const graph::ValidateContext& ctx) const {
    // P5's mapping is defined on the screen of a pinhole camera (its dMax, its pixel rays).
    if (ctx.sceneFeatures() & graph::kSceneEquirect)
        ctx.fail("reduction",
                 "VisualPolarWarp needs a perspective camera, not --camera-model equirect");
    if (!std::isfinite(mReduction)) ctx.fail("reduction", "must be finite");
    if (!std::isfinite(mFoveaFraction)) ctx.fail("foveaFraction", "must be finite");
}

void VisualPolarWarpPass::compile(graph::CompileContext& ctx) {
    mPipeline = ctx.createPipeline("visual_polar/warp.comp");
}

void VisualPolarWarpPass::execute(graph::ExecuteContext& ctx) {
    const auto& coords = ctx.image("coords");
    // e_f = f^-1(rho_f) in double on the CPU (the shaders' float Newton agrees to ~1e-5).
    auto grid = sampling::VisualPolarGrid::make(1, 1, mFoveaFraction);
    ctx.bindFields(*mPipeline);
    mPipeline->set("foveaFraction", float(grid.foveaFraction))
        .set("foveaDegrees", float(grid.foveaDegrees))
        .set("traceOffscreen", uint32_t(mTraceOffscreen));
    // The x offsets of this and the previous frame's block grid (history images were traced
    // with the previous one; visual_polar.glsl vpPrevious).
    const uint64_t frame = ctx.frame().index;
    const auto now = sampling::blockGridOffset(frame);
    const auto before = sampling::blockGridOffset(frame > 0 ? frame - 1 : frame);
    mPipeline->set("stairBlock", uint32_t(mStaircase ? sampling::kBlockGridSize : 0))
        .set("stairOffset", uint32_t(now[0]))
        .set("stairPrevOffset", uint32_t(before[0]));
    ctx.dispatch(*mPipeline, coords.width(), coords.height());
}

}  // namespace fovea::passes
