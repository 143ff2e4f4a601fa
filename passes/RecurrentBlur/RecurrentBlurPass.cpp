#include "passes/RecurrentBlur/RecurrentBlurPass.h"

#include <algorithm>
#include <cmath>

#include "core/scene/Camera.h"
#include "core/vk/Barriers.h"
#include "core/vk/ComputePipeline.h"

namespace fovea::passes {

namespace {
constexpr auto kRgba32 = vk::Format::eR32G32B32A32Sfloat;
constexpr auto kR32 = vk::Format::eR32Sfloat;
constexpr float kGoldenAngle = 2.39996323f;  // per-frame rotation of the 8-tap disk
}  // namespace

void RecurrentBlurPass::params(graph::ParamVisitor& v) {
    v.add("stage", mStage, "temporal",
          "temporal = pre-blur + temporal accumulation (+ firefly suppressor); spatial = blur + "
          "post-blur (the recurrent history) + temporal stabilization. A ReBLUR graph uses one "
          "node of each with HistoryFix between them (docs/passes/RecurrentBlur.md)",
          {"temporal", "spatial"});
    v.add("signal", mSignal, "diffuse",
          "diffuse = the talk's diffuse denoiser; specular = its specular one (seed 004 "
          "\"Cooking specular denoiser\", issue 26): accumulation capped by roughness, NoV and "
          "parallax, a world-space kernel along the GGX dominant direction, radius x roughness "
          "curve x lerp(K roughness, 1, f), lobe-angle normal weight and roughness weight. "
          "Needs the `roughness` input",
          {"diffuse", "specular"});
    v.add("maxAccumulatedFrames", mMaxAccumulatedFrames, 30,
          "cap of the frame count N; the new frame's weight is 1/(1+N), so 1/31 at the cap "
          "(seed 004: accumulation speed 1/(1+N); NRD maxAccumulatedFrameNum)",
          {0, 63});
    v.add("historyFixFrames", mHistoryFixFrames, 3,
          "spatial: N below which HistoryFix rebuilds a pixel; the blur keeps its full radius "
          "while N < 2/3 of it and fades the boost until 4/3 of it (specs §2)",
          {0, 3});
    v.add("maxBlurRadius", mMaxBlurRadius, 30.0f,
          "px at referenceHeight rows: blur radius at N = 0 and h = 1 (post-blur: twice this). "
          "Also sets the firefly "
          "suppressor's strength",
          {0.0, 256.0});
    v.add("minBlurRadius", mMinBlurRadius, 1.0f, "px: smallest blur radius", {0.0, 256.0});
    v.add("prepassBlurRadius", mPrepassBlurRadius, 30.0f,
          "temporal: px (at referenceHeight rows) of the pre-blur at h = 1 (0 = off); fixes "
          "outliers before accumulation",
          {0.0, 256.0});
    v.add("referenceHeight", mReferenceHeight, 1080.0f,
          "image rows at which maxBlurRadius and prepassBlurRadius hold (NRD's pixel defaults "
          "and the talk's timings are for 720p-1440p); at H rows both are scaled by "
          "H / referenceHeight (30 px -> 4 px at 144 rows), minBlurRadius is not. 0 = radii in "
          "pixels as given",
          {0.0, 16384.0});
    v.add("radiusScaling", mRadiusScaling, "sqrt",
          "how the radius shrinks with N: sqrt = maxBlurRadius*sqrt(h*s') (NRD), linear = "
          "maxBlurRadius*h*s' (the talk's 1/(1+N)); s' = 1/(1+N) once HistoryFix is done",
          {"sqrt", "linear"});
    v.add("planeDistanceSensitivity", mPlaneDistanceSensitivity, 0.02f,
          "blur: a tap whose distance to the pixel's plane reaches this fraction of the frustum "
          "size gets weight 0 (NRD 0.02)",
          {1e-6, 1.0});
    v.add("disocclusionThreshold", mDisocclusionThreshold, 0.01f,
          "temporal: a history tap is dropped when the previous surface is farther than this "
          "fraction of the frustum size from the pixel's plane (talk: 0.5-1.5 %)",
          {0.0, 1.0});
    v.add("disocclusionNormal", mDisocclusionNormal, 0.5f,
          "temporal: a history tap is also dropped when the cosine between the previous "
          "surface's normal and the pixel's is below this (ours, as BMFR's normalThreshold: the "
          "talk's plane distance alone keeps a tap of the floor or wall that lies in the plane "
          "of a box's side face, and a revealed face inherits their colour); -1 = off",
          {-1.0, 1.0});
    v.add("hitNormalized", mHitNormalized, false,
          "temporal: hit_distance already holds saturate(t / maxHitT) (PathTrace.diffuse_hit / "
          "specular_hit, shaders/common/hit_distance.glsl) instead of a distance t");
    v.add("minHitDistanceWeight", mMinHitDistanceWeight, 0.1f,
          "blur: floor of the hit-distance weight (NRD 0.1)", {0.0, 1.0});
    v.add("fireflySuppression", mFireflySuppression, true,
          "temporal: limit a new sample's luminance to (2 + 38/(N+1)) x the history's");
    v.add("maxStabilizedFrames", mMaxStabilizedFrames, 63,
          "spatial: temporal stabilization of luminance, strength <= m/(1+m); 0 = off", {0, 63});
    v.add("antilag", mAntilag, true,
          "spatial: shorten the stabilization where the stabilized history leaves the "
          "neighbourhood's mean +- antilagSigmaScale sigma");
    v.add("antilagSigmaScale", mAntilagSigmaScale, 4.0f, "spatial: antilag band in sigmas",
          {0.0, 100.0});
    v.add("antilagSensitivity", mAntilagSensitivity, 3.0f,
          "spatial: A = 1/(1 + sensitivity*d*N), d = relative distance outside the band",
          {0.0, 1000.0});
    v.add("specAccumBasePower", mSpecAccumBasePower, 0.66f,
          "specular, temporal: SPEC_ACCUM_BASE_POWER of GetMaxAllowedAccumulatedFrameNum (seed "
          "004 slide \"Specular accumulation using surface motion\"): N <= maxAccumulatedFrames "
          "x roughness^(power (1 + parallax x sensitivity)); larger = less accumulation. NRD "
          "used 0.66 before its virtual-motion reprojection and 0.5 with it; we reproject by "
          "surface motion only. 0 = no cap (naive surface-motion accumulation, the talk's "
          "\"doesn't work\" baseline)",
          {0.0, 16.0});
    v.add("specAccumCurve", mSpecAccumCurve, 1.0f,
          "specular, temporal: SPEC_ACCUM_CURVE, exponent of saturate(1 - NoV) in the "
          "sensitivity to parallax (NRD 1; smaller = less accumulation at grazing angles)",
          {0.01, 16.0});
    v.add("virtualMotion", mVirtualMotion, true,
          "specular, temporal: also reproject the reflected image (the virtual point hitDist "
          "behind the surface along the view ray, projected with the previous camera) and blend "
          "it with the surface-motion history by (1 - r)(sqrt(1 - r) + r) (1 for a mirror, 0 at "
          "roughness 1); the virtual history is not capped by parallax. Ours after NRD's "
          "virtual-motion reprojection; the talk (seed 004) only caps surface-motion "
          "accumulation, which leaves smooth reflections unaccumulated while the camera moves");
    v.add("parallaxFrameRate", mParallaxFrameRate, 60.0f,
          "specular, temporal: 1 / frameTime of the talk's parallax = |camera delta| / "
          "(distance x frameTime), in frames per second of the camera path",
          {1e-3, 1e4});
    v.add("hitRadiusK", mHitRadiusK, 0.5f,
          "specular, spatial: K of blurRadius *= lerp(K roughness, 1, hitDist / (hitDist + "
          "viewDistance)) (seed 004 \"Using hit distance to control blur radius\": K in (0, 1), "
          "no value given; 0.5 is ours)",
          {0.0, 1.0});
    v.add("eyes", mEyes, 0,
          "side-by-side eyes (no tap crosses the seam); 0 = the frame camera's eye count", {0, 2});
}

void RecurrentBlurPass::reflect(graph::Reflection& r) const {
    const bool temporal = mStage == "temporal";
    if (temporal) {
        r.input("radiance")
            .floatOnly()
            .doc("noisy demodulated radiance (PathTrace.demodulated); NaN/Inf read as 0");
        r.input("hit_distance")
            .floatOnly()
            .sameAs("radiance")
            .doc(
                "first indirect hit distance (PathTrace.hit_distance; 0 = no hit = far), or with "
                "hitNormalized the normalized one (PathTrace.diffuse_hit / specular_hit)");
    } else {
        r.input("color").floatOnly().doc(
            "accumulated colour, a = N (temporal stage's accumulated, or HistoryFix's result)");
        r.input("hit").floatOnly().sameAs("color").doc(
            "temporal stage's accumulated normalized hit distance");
    }
    const char* ref = temporal ? "radiance" : "color";
    r.input("normal").floatOnly().sameAs(ref).doc("GBuffer normal (world, w 1 = hit)");
    r.input("position").floatOnly().sameAs(ref).doc("GBuffer world position");
    r.input("depth").floatOnly().sameAs(ref).doc("GBuffer linear view depth; 0 = sky");
    r.input("motion").optional().floatOnly().sameAs(ref).doc(
        "GBuffer motion (previous - current pixel); open = still camera");
    r.input("roughness")
        .optional()
        .floatOnly()
        .sameAs(ref)
        .doc("GBuffer roughness_metallic (r = linear roughness); required by signal = specular");
    if (temporal) {
        r.input("history").optional().floatOnly().sameAs(ref).doc(
            "the recurrent history: the spatial stage's `history` through a delay-1 edge");
        r.output("preblurred", kRgba32)
            .sameAs(ref)
            .doc("pre-blurred radiance, a = normalized hit distance h");
        r.output("accumulated", kRgba32)
            .sameAs(ref)
            .doc("temporally accumulated radiance, a = frame count N (0 = no history)");
        r.output("hit", kR32).sameAs(ref).doc("accumulated normalized hit distance h in [0, 1]");
        r.output("radius", kR32).sameAs(ref).doc("debug: pre-blur radius in px (0 on sky)");
        r.internal("geo", kRgba32)
            .sameAs(ref)
            .history()
            .doc("own history: world position, w = N (-1 = no surface)");
        r.internal("geonormal", vk::Format::eR16G16B16A16Sfloat)
            .sameAs(ref)
            .history()
            .doc("own history: shading normal (0 = no surface), for disocclusionNormal");
    } else {
        r.output("blurred", kRgba32).sameAs(ref).doc("after the blur, a = N");
        r.output("history", kRgba32)
            .sameAs(ref)
            .doc(
                "after the post-blur, a = h: the recurrent history (delay-1 edge to the temporal "
                "stage's history)");
        r.output("result", kRgba32)
            .sameAs(ref)
            .doc("denoised demodulated radiance after temporal stabilization, a = 1");
        r.output("radius", kR32).sameAs(ref).doc("debug: blur radius in px (0 on sky)");
        r.internal("stabilized", kR32)
            .sameAs(ref)
            .history()
            .doc("own history: stabilized luminance");
    }
}

void RecurrentBlurPass::validate(const graph::ValidateContext& ctx) const {
    if (mMinBlurRadius > mMaxBlurRadius) ctx.fail("minBlurRadius", "must not exceed maxBlurRadius");
    if (mSignal == "specular" && !ctx.connected("roughness"))
        ctx.fail("signal",
                 "signal = specular needs the 'roughness' input (GBuffer.roughness_metallic)");
    if (mStage == "temporal" && !ctx.connected("history"))
        ctx.fail("stage",
                 "the temporal stage needs its 'history' input: a delay-1 edge from the spatial "
                 "stage's 'history' output (the recurrence)");
}

void RecurrentBlurPass::compile(graph::CompileContext& ctx) {
    mUseMotion = ctx.connected("motion");
    const std::vector<std::pair<std::string, std::string>> defines = {
        {"REBLUR_SPECULAR", mSignal == "specular" ? "1" : "0"}};
    mBlur = ctx.createPipeline("recurrent_blur/blur.comp", defines, {"src", "hitSrc", "dst"});
    mHavePreviousEyes = false;
    if (mStage == "temporal")
        mTemporal = ctx.createPipeline("recurrent_blur/temporal.comp", defines);
    else
        mStabilize = ctx.createPipeline("recurrent_blur/stabilize.comp");
}

void RecurrentBlurPass::setBlurConstants(graph::ExecuteContext& ctx, int mode, float maxRadius) {
    const auto& cam = ctx.camera();
    const float angle = kGoldenAngle * float(ctx.frame().index % 1024);
    mBlur->set("tanHalfFov", std::tan(0.5f * cam.yfov))
        .set("mode", mode)
        .set("maxRadius", maxRadius)
        .set("minRadius", mode == 0 ? std::min(mMinBlurRadius, maxRadius) : mMinBlurRadius)
        .set("linearScaling", int(mRadiusScaling == "linear"))
        .set("historyFixFrames", float(mHistoryFixFrames))
        .set("planeDistance", mPlaneDistanceSensitivity)
        .set("minHitWeight", mMinHitDistanceWeight)
        .set("rotation", glm::vec2(std::cos(angle), std::sin(angle)))
        .set("writeRadius", int(mode != 2))
        .set("maxFrames", float(mMaxAccumulatedFrames))
        .set("hitRadiusK", mHitRadiusK);
}

void RecurrentBlurPass::execute(graph::ExecuteContext& ctx) {
    if (mStage == "temporal")
        executeTemporal(ctx);
    else
        executeSpatial(ctx);
}

RecurrentBlurPass::EyeLayout RecurrentBlurPass::eyeLayout(const gpu::Image& out, int eyesParam,
                                                          uint32_t cameraEyes) {
    const auto split = scene::splitEyes(out.width(), eyesParam, cameraEyes);
    return {{int(out.width()), int(out.height())}, split.eyeWidth, split.eyes};
}

float RecurrentBlurPass::resolutionScale(const EyeLayout& e) const {
    // Radii are pixels at referenceHeight rows; the blur covers the same fraction of the view
    // at any size (issue 13: NRD's 30 px covered a fifth of a 144-row image).
    return mReferenceHeight > 0.0f ? float(e.size.y) / mReferenceHeight : 1.0f;
}

void RecurrentBlurPass::blur(graph::ExecuteContext& ctx, const EyeLayout& e, const char* src,
                             const char* hit, const char* dst, int mode, float maxRadius) {
    // One dispatch of blur.comp (pre-blur, blur or post-blur by `mode`), then a barrier: every
    // blur's output is the next kernel's input.
    ctx.bindFields(*mBlur);
    mBlur->bind("src", ctx.image(src)).bind("hitSrc", ctx.image(hit)).bind("dst", ctx.image(dst));
    mBlur->set("hitNormalized", int(mHitNormalized));
    mBlur->set("size", e.size).set("eyeWidth", e.eyeWidth).set("eyes", e.eyes);
    setBlurConstants(ctx, mode, maxRadius);
    mBlur->dispatch(ctx.cmd(), uint32_t(e.size.x), uint32_t(e.size.y));
    gpu::computeToComputeBarrier(ctx.cmd());
}

void RecurrentBlurPass::executeTemporal(graph::ExecuteContext& ctx) {
    const auto& cmd = ctx.cmd();
    const auto& out = ctx.image("accumulated");
    const EyeLayout e = eyeLayout(out, mEyes, ctx.camera().eyeCount);

    // Pre-blur: radiance -> preblurred (a = h). prepassBlurRadius 0 copies (sanitized).
    blur(ctx, e, "radiance", "hit_distance", "preblurred", 0,
         mPrepassBlurRadius * resolutionScale(e));

    // Temporal accumulation. Both histories must hold a frame: the recurrent input (false on the
    // first frame, after a reset or cut) and our own geometry.
    const bool useHistory =
        ctx.historyValid("history") && ctx.historyValid("geo") && ctx.historyValid("geonormal");
    ctx.bindFields(*mTemporal);
    mTemporal->set("size", e.size)
        .set("eyeWidth", e.eyeWidth)
        .set("eyes", e.eyes)
        .set("tanHalfFov", std::tan(0.5f * ctx.camera().yfov))
        .set("useHistory", int(useHistory))
        .set("useMotion", int(mUseMotion))
        .set("maxFrames", float(mMaxAccumulatedFrames))
        .set("threshold", mDisocclusionThreshold)
        .set("cosNormal", mDisocclusionNormal)
        .set("firefly", int(mFireflySuppression))
        .set("maxBlurRadius", mMaxBlurRadius);
    // Specular parallax: this frame's eyes against the previous frame's (w = 0: unknown).
    const auto& cam = ctx.camera();
    const float known = useHistory && mHavePreviousEyes ? 1.0f : 0.0f;
    mTemporal->set("prevEyePosition0", glm::vec4(mPreviousEyes[0], known))
        .set("prevEyePosition1", glm::vec4(mPreviousEyes[1], known))
        .set("frameRate", mParallaxFrameRate)
        .set("accumBasePower", mSpecAccumBasePower)
        .set("accumCurve", mSpecAccumCurve)
        .set("virtualMotion", int(mVirtualMotion));
    mTemporal->dispatch(cmd, out.width(), out.height());
    // As camera_info holds them: a mono camera's eye 0 in both slots.
    for (uint32_t e = 0; e < 2; ++e) mPreviousEyes[e] = cam.eyes[e < cam.eyeCount ? e : 0].position;
    mHavePreviousEyes = true;
}

void RecurrentBlurPass::executeSpatial(graph::ExecuteContext& ctx) {
    const auto& cmd = ctx.cmd();
    const auto& out = ctx.image("result");
    const EyeLayout e = eyeLayout(out, mEyes, ctx.camera().eyeCount);

    // Blur: color -> blurred, radius from N (color.a) and h.
    blur(ctx, e, "color", "hit", "blurred", 1, mMaxBlurRadius * resolutionScale(e));

    // Post-blur: blurred -> history (the recurrent feedback).
    blur(ctx, e, "blurred", "hit", "history", 2, mMaxBlurRadius * resolutionScale(e));

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
    mStabilize->dispatch(cmd, out.width(), out.height());
}

}  // namespace fovea::passes
