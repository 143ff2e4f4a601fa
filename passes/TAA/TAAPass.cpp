#include "passes/TAA/TAAPass.h"

#include <algorithm>

#include "core/graph/DenoiserInputs.h"
#include "core/sampling/VisualPolar.h"
#include "core/scene/Camera.h"
#include "core/vk/ComputePipeline.h"

namespace fovea::passes {

void TAAPass::params(graph::ParamVisitor& v) {
    v.add("alpha", mAlpha, 0.1f,
          "weight of the current frame: result = mix(history, current, alpha); 1 = no history "
          "(Karis 2014 uses ~0.04-0.1)",
          {0.0, 1.0});
    v.add("clip", mClip, "variance",
          "history constraint in YCoCg over the 3x3 neighbourhood: variance = Salvi 2016 box "
          "mean +- gamma*sigma, minmax = min/max box (Karis 2014), none = no constraint",
          {"variance", "minmax", "none"});
    v.add("gamma", mGamma, 1.0f, "variance box half-width in standard deviations (clip=variance)",
          {0.0, 8.0});
    v.add("historyFilter", mHistoryFilter, "bilinear",
          "how the reprojected history is sampled: bilinear, or catmull-rom (sharper; may "
          "overshoot, which the clip bounds)",
          {"bilinear", "catmull-rom"});
    v.add("eyes", mEyes, 0,
          "side-by-side eyes (no tap crosses the seam); 0 = the frame camera's eye count", {0, 2});
}

void TAAPass::reflect(graph::Reflection& r) const {
    r.input("color").floatOnly().doc(
        "the frame to antialias (rgba32f/16f, jittered when the run jitters); rgb filtered, a "
        "passed through");
    // Not the shared Motion: TAA has no positions, so an open `motion` means a still camera.
    r.input("motion").optional().floatOnly().sameAs("color").doc(
        "GBuffer motion: previous pixel - current pixel, jitter-free; open = still camera");
    graph::declareDenoiserInput(
        r, graph::DenoiserInput::VisualPolar,
        "with a Visual-Polar `color` and GBuffer VP `motion`: 3x3 neighbours and the history taps "
        "(bilinear or Catmull-Rom) wrap on phi at each "
        "column's own phi height, the previous frame's for the history (P5 §3.3); open: screen "
        "addressing");
    r.output("result", vk::Format::eR32G32B32A32Sfloat)
        .sameAs("color")
        .history(1)
        .doc(
            "antialiased colour (finite everywhere); the graph keeps the previous frame's result "
            "as this pass's history (no edge to wire)");
}

void TAAPass::compile(graph::CompileContext& ctx) {
    mUseMotion = ctx.connected("motion");
    mUseVp = ctx.connected("vp");
    mVariant = mClip + "," + mHistoryFilter + (mUseMotion ? ",motion" : "") + (mUseVp ? ",vp" : "");
    mPipeline = ctx.createPipeline("taa/taa.comp");
}

void TAAPass::execute(graph::ExecuteContext& ctx) {
    const auto& out = ctx.image("result");
    const int width = int(out.width()), height = int(out.height());
    const auto [eyes, eyeWidth] = scene::splitEyes(out.width(), mEyes, ctx.camera().eyeCount);
    // historyValid is false on the first frame and after a reset, resize or camera cut (the graph
    // invalidates every history then).
    const bool useHistory = ctx.historyValid("result");
    const int clipMode = mClip == "none" ? 0 : (mClip == "minmax" ? 1 : 2);
    ctx.bindFields(*mPipeline);
    mPipeline->set("size", glm::ivec2(width, height))
        .set("eyeWidth", eyeWidth)
        .set("eyes", eyes)
        .set("alpha", mAlpha)
        .set("clipMode", clipMode)
        .set("gamma", mGamma)
        .set("catmullRom", int(mHistoryFilter == "catmull-rom"))
        .set("useHistory", int(useHistory))
        .set("useMotion", int(mUseMotion))
        .set("useVp", int(mUseVp));
    ctx.dispatch(*mPipeline, out.width(), out.height());
}

}  // namespace fovea::passes
