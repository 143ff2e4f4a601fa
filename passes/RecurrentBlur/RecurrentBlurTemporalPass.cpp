#include "passes/RecurrentBlur/RecurrentBlurTemporalPass.h"

#include <cmath>

#include "core/scene/Camera.h"
#include "core/vk/ComputePipeline.h"

namespace fovea::passes {

namespace {
constexpr auto kRgba32 = vk::Format::eR32G32B32A32Sfloat;
constexpr auto kR32 = vk::Format::eR32Sfloat;
// blur.comp's pre-blur (mode 0) uses s' = 1/11 and no HistoryFix boost (the count is 0).
constexpr int kPreBlurHistoryFixFrames = 0;
}  // namespace

void RecurrentBlurTemporalPass::params(graph::ParamVisitor& v) {
    sharedParams(v);
    v.add("prepassBlurRadius", mPrepassBlurRadius, 30.0f,
          "px (at referenceHeight rows) of the pre-blur at h = 1 (0 = off); fixes outliers "
          "before accumulation",
          {0.0, 256.0});
    v.add("disocclusionThreshold", mDisocclusionThreshold, 0.01f,
          "a history tap is dropped when the previous surface is farther than this fraction of "
          "the frustum size from the pixel's plane (talk: 0.5-1.5 %)",
          {0.0, 1.0});
    v.add("disocclusionNormal", mDisocclusionNormal, 0.5f,
          "a history tap is also dropped when the cosine between the previous surface's normal "
          "and the pixel's is below this (ours, as BMFR's normalThreshold: the talk's plane "
          "distance alone keeps a tap of the floor or wall that lies in the plane of a box's "
          "side face, and a revealed face inherits their colour); -1 = off",
          {-1.0, 1.0});
    v.add("hitNormalized", mHitNormalized, false,
          "hit_distance already holds saturate(t / maxHitT) (PathTrace.diffuse_hit / "
          "specular_hit, shaders/common/hit_distance.glsl) instead of a distance t");
    v.add("fireflySuppression", mFireflySuppression, true,
          "limit a new sample's luminance to (2 + 38/(N+1)) x the history's");
    v.add("specAccumBasePower", mSpecAccumBasePower, 0.66f,
          "specular: SPEC_ACCUM_BASE_POWER of GetMaxAllowedAccumulatedFrameNum (seed 004 slide "
          "\"Specular accumulation using surface motion\"): N <= maxAccumulatedFrames x "
          "roughness^(power (1 + parallax x sensitivity)); larger = less accumulation. NRD used "
          "0.66 before its virtual-motion reprojection and 0.5 with it; we reproject by surface "
          "motion only. 0 = no cap (naive surface-motion accumulation, the talk's \"doesn't "
          "work\" baseline)",
          {0.0, 16.0});
    v.add("specAccumCurve", mSpecAccumCurve, 1.0f,
          "specular: SPEC_ACCUM_CURVE, exponent of saturate(1 - NoV) in the sensitivity to "
          "parallax (NRD 1; smaller = less accumulation at grazing angles)",
          {0.01, 16.0});
    v.add("virtualMotion", mVirtualMotion, true,
          "specular: also reproject the reflected image (the virtual point hitDist behind the "
          "surface along the view ray, projected with the previous camera) and blend it with the "
          "surface-motion history by (1 - r)(sqrt(1 - r) + r) (1 for a mirror, 0 at roughness "
          "1); the virtual history is not capped by parallax. Ours after NRD's virtual-motion "
          "reprojection; the talk (seed 004) only caps surface-motion accumulation, which leaves "
          "smooth reflections unaccumulated while the camera moves");
    v.add("parallaxFrameRate", mParallaxFrameRate, 60.0f,
          "specular: 1 / frameTime of the talk's parallax = |camera delta| / (distance x "
          "frameTime), in frames per second of the camera path",
          {1e-3, 1e4});
}

void RecurrentBlurTemporalPass::reflect(graph::Reflection& r) const {
    r.input("radiance")
        .floatOnly()
        .doc("noisy demodulated radiance (PathTrace.demodulated); NaN/Inf read as 0");
    r.input("hit_distance")
        .floatOnly()
        .sameAs("radiance")
        .doc(
            "first indirect hit distance (PathTrace.hit_distance; 0 = no hit = far), or with "
            "hitNormalized the normalized one (PathTrace.diffuse_hit / specular_hit)");
    sharedInputs(r, "radiance");
    // Required: without the recurrence the accumulation would never have history.
    r.input("history")
        .floatOnly()
        .sameAs("radiance")
        .doc("the recurrent history: RecurrentBlurSpatial's `history` through a delay-1 edge");
    r.output("preblurred", kRgba32)
        .sameAs("radiance")
        .doc("pre-blurred radiance, a = normalized hit distance h");
    r.output("accumulated", kRgba32)
        .sameAs("radiance")
        .doc("temporally accumulated radiance, a = frame count N (0 = no history)");
    r.output("hit", kR32).sameAs("radiance").doc("accumulated normalized hit distance h in [0, 1]");
    r.output("radius", kR32).sameAs("radiance").doc("debug: pre-blur radius in px (0 on sky)");
    r.internal("geo", kRgba32)
        .sameAs("radiance")
        .history()
        .doc("own history: world position, w = N (-1 = no surface)");
    r.internal("geonormal", vk::Format::eR16G16B16A16Sfloat)
        .sameAs("radiance")
        .history()
        .doc("own history: shading normal (0 = no surface), for disocclusionNormal");
}

void RecurrentBlurTemporalPass::compile(graph::CompileContext& ctx) {
    mTemporal = ctx.createPipeline("recurrent_blur/temporal.comp", compileBlur(ctx));
    mHavePreviousEyes = false;
}

void RecurrentBlurTemporalPass::execute(graph::ExecuteContext& ctx) {
    const auto& out = ctx.image("accumulated");
    const EyeLayout e = eyeLayout(ctx, out);

    // Pre-blur: radiance -> preblurred (a = h). prepassBlurRadius 0 copies (sanitized).
    blur(ctx, e, "radiance", "hit_distance", "preblurred", 0,
         mPrepassBlurRadius * resolutionScale(e), kPreBlurHistoryFixFrames, mHitNormalized);

    // Temporal accumulation. Both histories must hold a frame: the recurrent input (false on the
    // first frame, after a reset or cut) and our own geometry.
    const bool useHistory =
        ctx.historyValid("history") && ctx.historyValid("geo") && ctx.historyValid("geonormal");
    const auto& cam = ctx.camera();
    ctx.bindFields(*mTemporal);
    mTemporal->set("size", e.size)
        .set("eyeWidth", e.eyeWidth)
        .set("eyes", e.eyes)
        .set("tanHalfFov", std::tan(0.5f * cam.yfov))
        .set("useHistory", int(useHistory))
        .set("useMotion", int(mUseMotion))
        .set("maxFrames", float(mMaxAccumulatedFrames))
        .set("threshold", mDisocclusionThreshold)
        .set("cosNormal", mDisocclusionNormal)
        .set("firefly", int(mFireflySuppression))
        .set("maxBlurRadius", mMaxBlurRadius);
    // Specular parallax: this frame's eyes against the previous frame's (w = 0: unknown).
    const float known = useHistory && mHavePreviousEyes ? 1.0f : 0.0f;
    mTemporal->set("prevEyePosition0", glm::vec4(mPreviousEyes[0], known))
        .set("prevEyePosition1", glm::vec4(mPreviousEyes[1], known))
        .set("frameRate", mParallaxFrameRate)
        .set("accumBasePower", mSpecAccumBasePower)
        .set("accumCurve", mSpecAccumCurve)
        .set("virtualMotion", int(mVirtualMotion));
    ctx.dispatch(*mTemporal, out.width(), out.height());
    // As camera_info holds them: a mono camera's eye 0 in both slots.
    for (uint32_t i = 0; i < 2; ++i) mPreviousEyes[i] = cam.eyes[i < cam.eyeCount ? i : 0].position;
    mHavePreviousEyes = true;
}

}  // namespace fovea::passes
