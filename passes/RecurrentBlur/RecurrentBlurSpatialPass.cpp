#include "passes/RecurrentBlur/RecurrentBlurSpatialPass.h"

#include "core/vk/ComputePipeline.h"

namespace fovea::passes {

namespace {
constexpr auto kRgba32 = vk::Format::eR32G32B32A32Sfloat;
constexpr auto kR32 = vk::Format::eR32Sfloat;
}  // namespace

void RecurrentBlurSpatialPass::params(graph::ParamVisitor& v) {
    sharedParams(v);
    v.add("historyFixFrames", mHistoryFixFrames, 3,
          "N below which HistoryFix rebuilds a pixel; the blur keeps its full radius while N < "
          "2/3 of it and fades the boost until 4/3 of it (specs §2)",
          {0, 3});
    v.add("maxStabilizedFrames", mMaxStabilizedFrames, 63,
          "temporal stabilization of luminance, strength <= m/(1+m); 0 = off", {0, 63});
    v.add("antilag", mAntilag, true,
          "shorten the stabilization where the stabilized history leaves the neighbourhood's "
          "mean +- antilagSigmaScale sigma");
    v.add("antilagSigmaScale", mAntilagSigmaScale, 4.0f, "antilag band in sigmas", {0.0, 100.0});
    v.add("antilagSensitivity", mAntilagSensitivity, 3.0f,
          "A = 1/(1 + sensitivity*d*N), d = relative distance outside the band", {0.0, 1000.0});
}

void RecurrentBlurSpatialPass::reflect(graph::Reflection& r) const {
    r.input("color").floatOnly().doc(
        "accumulated colour, a = N (RecurrentBlurTemporal's accumulated, or HistoryFix's "
        "result)");
    r.input("hit").floatOnly().sameAs("color").doc(
        "RecurrentBlurTemporal's accumulated normalized hit distance");
    sharedInputs(r, "color");
    r.output("blurred", kRgba32).sameAs("color").doc("after the blur, a = N");
    r.output("history", kRgba32)
        .sameAs("color")
        .doc(
            "after the post-blur, a = h: the recurrent history (delay-1 edge to "
            "RecurrentBlurTemporal's history)");
    r.output("result", kRgba32)
        .sameAs("color")
        .doc("denoised demodulated radiance after temporal stabilization, a = 1");
    r.output("radius", kR32).sameAs("color").doc("debug: blur radius in px (0 on sky)");
    r.internal("stabilized", kR32)
        .sameAs("color")
        .history()
        .doc("own history: stabilized luminance");
}

void RecurrentBlurSpatialPass::compile(graph::CompileContext& ctx) {
    compileBlur(ctx);
    mStabilize = ctx.createPipeline("recurrent_blur/stabilize.comp");
}

void RecurrentBlurSpatialPass::execute(graph::ExecuteContext& ctx) {
    const auto& out = ctx.image("result");
    const EyeLayout e = eyeLayout(ctx, out);
    const float radius = mMaxBlurRadius * resolutionScale(e);
    // Blur: color -> blurred, radius from N (color.a) and h.
    blur(ctx, e, "color", "hit", "blurred", 1, radius, mHistoryFixFrames, false);
    // Post-blur: blurred -> history (the recurrent feedback).
    blur(ctx, e, "blurred", "hit", "history", 2, radius, mHistoryFixFrames, false);

    // Temporal stabilization of luminance (own history: stabilized).
    ctx.bindFields(*mStabilize);
    mStabilize->set("size", e.size)
        .set("eyeWidth", e.eyeWidth)
        .set("eyes", e.eyes)
        .set("useHistory", int(ctx.historyValid("stabilized")))
        .set("useMotion", int(mUseMotion))
        .set("maxStabilized", float(mMaxStabilizedFrames))
        .set("antilag", int(mAntilag))
        .set("antilagSigma", mAntilagSigmaScale)
        .set("antilagSensitivity", mAntilagSensitivity);
    ctx.dispatch(*mStabilize, out.width(), out.height());
}

}  // namespace fovea::passes
