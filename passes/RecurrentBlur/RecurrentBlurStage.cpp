#include "passes/RecurrentBlur/RecurrentBlurStage.h"

#include <algorithm>
#include <cmath>

#include "core/scene/Camera.h"
#include "core/vk/ComputePipeline.h"

namespace fovea::passes {

namespace {
constexpr float kGoldenAngle = 2.39996323f;  // per-frame rotation of the 8-tap disk
}  // namespace

void RecurrentBlurStage::sharedParams(graph::ParamVisitor& v) {
    v.add("signal", mSignal, "diffuse",
          "diffuse = the talk's diffuse denoiser; specular = its specular one (seed 004 "
          "\"Cooking specular denoiser\", issue 26): accumulation capped by roughness, NoV and "
          "parallax, a world-space kernel along the GGX dominant direction, radius x roughness "
          "curve x lerp(K roughness, 1, f), lobe-angle normal weight and roughness weight. "
          "Needs the `roughness` input; both stages of a chain must agree",
          {"diffuse", "specular"});
    v.add("maxAccumulatedFrames", mMaxAccumulatedFrames, 30,
          "cap of the frame count N; the new frame's weight is 1/(1+N), so 1/31 at the cap "
          "(seed 004: accumulation speed 1/(1+N); NRD maxAccumulatedFrameNum). The spatial "
          "stage's specular kernel reads N / this as the convergence",
          {0, 63});
    v.add("maxBlurRadius", mMaxBlurRadius, 30.0f,
          "px at referenceHeight rows: blur radius at N = 0 and h = 1 (post-blur: twice this). "
          "Also sets the firefly suppressor's strength",
          {0.0, 256.0});
    v.add("minBlurRadius", mMinBlurRadius, 1.0f, "px: smallest blur radius", {0.0, 256.0});
    v.add("referenceHeight", mReferenceHeight, 1080.0f,
          "image rows at which maxBlurRadius and prepassBlurRadius hold (NRD's pixel defaults "
          "and the talk's timings are for 720p-1440p); at H rows both are scaled by "
          "H / referenceHeight (30 px -> 4 px at 144 rows), minBlurRadius is not. 0 = radii in "
          "pixels as given",
          {0.0, 16384.0});
    v.add("radiusScaling", mRadiusScaling, "sqrt",
          "how the radius shrinks with N: sqrt = maxBlurRadius*sqrt(h*s') (NRD), linear = "
          "maxBlurRadius*h*s' (the talk's 1/(1+N)); s' = 1/(1+N) once HistoryFix is done (the "
          "pre-blur: s' = 1)",
          {"sqrt", "linear"});
    v.add("planeDistanceSensitivity", mPlaneDistanceSensitivity, 0.02f,
          "blur: a tap whose distance to the pixel's plane reaches this fraction of the frustum "
          "size gets weight 0 (NRD 0.02)",
          {1e-6, 1.0});
    v.add("minHitDistanceWeight", mMinHitDistanceWeight, 0.1f,
          "blur: floor of the hit-distance weight (NRD 0.1)", {0.0, 1.0});
    v.add("hitRadiusK", mHitRadiusK, 0.5f,
          "specular: K of blurRadius *= lerp(K roughness, 1, hitDist / (hitDist + "
          "viewDistance)) (seed 004 \"Using hit distance to control blur radius\": K in (0, 1), "
          "no value given; 0.5 is ours)",
          {0.0, 1.0});
    v.add("eyes", mEyes, 0,
          "side-by-side eyes (no tap crosses the seam); 0 = the frame camera's eye count", {0, 2});
}

void RecurrentBlurStage::sharedInputs(graph::Reflection& r, const char* ref) const {
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
}

void RecurrentBlurStage::sharedValidate(const graph::ValidateContext& ctx) const {
    if (mMinBlurRadius > mMaxBlurRadius) ctx.fail("minBlurRadius", "must not exceed maxBlurRadius");
    if (mSignal == "specular" && !ctx.connected("roughness"))
        ctx.fail("signal",
                 "signal = specular needs the 'roughness' input (GBuffer.roughness_metallic)");
}

std::vector<std::pair<std::string, std::string>> RecurrentBlurStage::compileBlur(
    graph::CompileContext& ctx) {
    mUseMotion = ctx.connected("motion");
    std::vector<std::pair<std::string, std::string>> defines = {
        {"REBLUR_SPECULAR", mSignal == "specular" ? "1" : "0"}};
    mBlur = ctx.createPipeline("recurrent_blur/blur.comp", defines, {"src", "hitSrc", "dst"});
    return defines;
}

RecurrentBlurStage::EyeLayout RecurrentBlurStage::eyeLayout(const graph::ExecuteContext& ctx,
                                                            const gpu::Image& out) const {
    const auto split = scene::splitEyes(out.width(), mEyes, ctx.camera().eyeCount);
    return {{int(out.width()), int(out.height())}, split.eyeWidth, split.eyes};
}

float RecurrentBlurStage::resolutionScale(const EyeLayout& e) const {
    // Radii are pixels at referenceHeight rows; the blur covers the same fraction of the view
    // at any size (issue 13: NRD's 30 px covered a fifth of a 144-row image).
    return mReferenceHeight > 0.0f ? float(e.size.y) / mReferenceHeight : 1.0f;
}

void RecurrentBlurStage::blur(graph::ExecuteContext& ctx, const EyeLayout& e, const char* src,
                              const char* hit, const char* dst, int mode, float maxRadius,
                              int historyFixFrames, bool hitNormalized) {
    ctx.bindFields(*mBlur);
    mBlur->bind("src", ctx.image(src)).bind("hitSrc", ctx.image(hit)).bind("dst", ctx.image(dst));
    const auto& cam = ctx.camera();
    const float angle = kGoldenAngle * float(ctx.frame().index % 1024);
    mBlur->set("hitNormalized", int(hitNormalized))
        .set("size", e.size)
        .set("eyeWidth", e.eyeWidth)
        .set("eyes", e.eyes)
        .set("tanHalfFov", std::tan(0.5f * cam.yfov))
        .set("mode", mode)
        .set("maxRadius", maxRadius)
        .set("minRadius", mode == 0 ? std::min(mMinBlurRadius, maxRadius) : mMinBlurRadius)
        .set("linearScaling", int(mRadiusScaling == "linear"))
        .set("historyFixFrames", float(historyFixFrames))
        .set("planeDistance", mPlaneDistanceSensitivity)
        .set("minHitWeight", mMinHitDistanceWeight)
        .set("rotation", glm::vec2(std::cos(angle), std::sin(angle)))
        .set("writeRadius", int(mode != 2))
        .set("maxFrames", float(mMaxAccumulatedFrames))
        .set("hitRadiusK", mHitRadiusK);
    ctx.dispatch(*mBlur, uint32_t(e.size.x), uint32_t(e.size.y));
}

}  // namespace fovea::passes
