#include "passes/PathTrace/PathTracePass.h"

#include <algorithm>

#include "core/sampling/SampleLayout.h"
#include "core/scene/SceneFeatures.h"
#include "core/scene/SceneGpu.h"
#include "core/shading/SpecularAlbedo.h"
#include "core/util/Error.h"
#include "core/vk/ComputePipeline.h"
#include "core/vk/Resources.h"

namespace fovea::passes {

namespace {
const std::vector<std::string> kBrdfs = {"lambert", "ggx"};
// Order = the shader's PATHTRACE_EMITTER_SAMPLING values.
const std::vector<std::string> kEmitterSampling = {"mis", "light", "brdf"};
const std::vector<std::string> kLightSampling = {"area", "solidAngle"};
constexpr int kMaxSpp = 1024;
constexpr int kMaxBounceLimit = 16;

// "emissive" or "no-emissive" from a SCENE_HAS_* define.
std::string feature(const std::vector<std::pair<std::string, std::string>>& defines,
                    const std::string& define, const std::string& name) {
    for (const auto& [key, value] : defines)
        if (key == define) return value == "1" ? name : "no-" + name;
    return name;  // not specialized: compiled in
}
}  // namespace

PathTracePass::PathTracePass() = default;
PathTracePass::~PathTracePass() = default;

void PathTracePass::params(graph::ParamVisitor& v) {
    v.add("spp", mSpp, 1,
          "samples (paths) per pixel without a sample layout; a layout's per-pixel count "
          "overrides it (seed 000 Table 1 uses 4/3/2 per layer)",
          {1, kMaxSpp});
    v.add("maxBounces", mMaxBounces, 1,
          "indirect rays per path, each followed by next-event estimation (P2 §3.1: 1); 0 = "
          "direct light only",
          {0, kMaxBounceLimit});
    v.add("brdf", mBrdf, "lambert",
          "lambert: every surface diffuse with its base colour (seed 000 §4.1); ggx: glTF "
          "metallic-roughness (GGX/Smith specular + Lambert diffuse weighted by 1 - metallic)",
          kBrdfs);
    v.add("clampIndirect", mClampIndirect, 0.0f,
          "firefly clamp: largest channel of one indirect contribution (biased); 0 = off",
          {0.0, 1e30});
    v.add("lastBounceMis", mLastBounceMis, kLastBounceMisDefault,
          "one more BRDF-sampled ray at the last path vertex, looking for an emitter, combined "
          "with that vertex's shadow ray by MIS (Veach 1997 §9.2, power heuristic): bounds the "
          "noise next to lights; false = the strict P2 §3.1 ray budget (the last shadow ray "
          "alone, full weight)");
    v.add("emitterSampling", mEmitterSampling, "mis",
          "how light from emissive triangles is estimated at each path vertex: mis = shadow ray "
          "and BRDF ray combined by the power heuristic (Veach 1997 §9.2); light = shadow rays "
          "only; brdf = BRDF rays only (the last vertex traces one too). light and brdf are the "
          "two unbiased single-strategy estimators MIS combines (tests, variance studies); "
          "lastBounceMis applies to mis only",
          kEmitterSampling);
    v.add("lightSampling", mLightSampling, "area",
          "how a shadow ray's point on an emissive triangle is drawn: area = uniform on the "
          "triangle (pdf d^2 / (A cos), heavy-tailed next to the light); solidAngle = uniform "
          "in the solid angle the triangle subtends (Arvo 1995 spherical triangles; area "
          "sampling below 3e-4 sr or above 6 sr)",
          kLightSampling);
    v.add("stratifyLight", mStratifyLight, false,
          "the primary vertex's light samples of one pixel form a randomly shifted "
          "low-discrepancy set (R-sequence) instead of independent points: unbiased, less noise "
          "at several samples per pixel (no effect at spp 1)");
    v.add("bumpShadowing", mBumpShadowing, false,
          "where a normal texture bends the shading normal, the diffuse lobe times Chiang, Li "
          "and Burley's bump shadowing term (2019, \"Taming the Shadow Terminator\"), as "
          "Blender Cycles does: darker light at grazing angles to the surface; false = plain "
          "glTF shading with the bent normal. Nothing changes without normal textures");
    v.add("countRays", mCountRays, false,
          "benchmarks: count every traced ray by kind (atomic counters in the `rays` field; "
          "report.json statistics)");
}

namespace {
uint64_t specularAlbedoTableBytes() {
    return shading::bakedSpecularAlbedoTable().size() * sizeof(glm::vec2);
}
}  // namespace

void PathTracePass::reflect(graph::Reflection& r) const {
    r.input("visibility", vk::Format::eR32G32B32A32Uint)
        .optional()
        .doc(
            "GBuffer visibility (triangle + 1, barycentrics, flags): primary hits; open = own "
            "jittered primary rays per sample. The outputs take its size (a Visual-Polar grid: "
            "texels flagged clipped get no sample)");
    r.input("albedo").optional().doc(
        "first-hit base colour for demodulation; open = the pass's own first hit");
    r.input(sampling::kSampleLayoutField)
        .buffer(sampling::kSampleLayoutHeaderBytes)
        .optional()
        .doc("sample layout (CONTRACT): only listed pixels are traced, with their count");
    r.internal("rays", vk::Format::eUndefined)
        .buffer(kRayKinds * sizeof(uint32_t))
        .persistent()
        .zeroed()
        .doc(
            "countRays: rays traced since compile, by kind (primary, shadow of primary, indirect, "
            "shadow of indirect, last-vertex BRDF), uint32 each; report.json statistics");
    r.internal("specular_albedo_table", vk::Format::eUndefined)
        .buffer(specularAlbedoTableBytes())
        .contents(shading::bakedSpecularAlbedoTable().data(), specularAlbedoTableBytes())
        .doc("the pre-integrated GGX reflectance table (core/shading/SpecularAlbedo.h), constant");
    r.output("radiance", vk::Format::eR32G32B32A32Sfloat)
        .sameAs("visibility")
        .doc("mean radiance of the pixel's samples; a = samples traced (0 = untraced)");
    r.output("demodulated", vk::Format::eR32G32B32A32Sfloat)
        .sameAs("visibility")
        .doc(
            "(radiance - primary emission) / albedo' (albedo' = albedo > 1e-3 ? albedo : 1); "
            "a = samples");
    r.output("hit_distance", vk::Format::eR32Sfloat)
        .sameAs("visibility")
        .doc("mean distance of the first indirect ray's hit over the samples that hit; 0 = none");
    r.output("direct", vk::Format::eR16G16B16A16Sfloat)
        .sameAs("visibility")
        .doc("primary emission + light after one reflection; a = samples");
    r.output("indirect", vk::Format::eR16G16B16A16Sfloat)
        .sameAs("visibility")
        .doc("light after two or more reflections; a = samples");
    // Issue 26 (seed 004 "Cooking specular denoiser": diffuse and specular must be separated).
    r.output("diffuse", vk::Format::eR32G32B32A32Sfloat)
        .sameAs("visibility")
        .doc(
            "light leaving through the primary vertex's diffuse lobe / diffuse_albedo' (emission "
            "excluded; albedo' as for demodulated); a = samples");
    r.output("specular", vk::Format::eR32G32B32A32Sfloat)
        .sameAs("visibility")
        .doc(
            "light leaving through the specular (GGX) lobe / specular_albedo'; 0 with brdf = "
            "lambert; a = samples");
    r.output("diffuse_hit", vk::Format::eR16Sfloat)
        .sameAs("visibility")
        .doc(
            "mean normalized hit distance saturate(t / maxHitT) of the diffuse-lobe first "
            "indirect rays (shaders/common/hit_distance.glsl); 1 = far or missed, -1 = no "
            "diffuse ray here (at 1 spp a pixel traces one lobe)");
    r.output("specular_hit", vk::Format::eR16Sfloat)
        .sameAs("visibility")
        .doc(
            "the same for the specular-lobe rays, maxHitT growing for smooth lobes (x20 at "
            "roughness 0)");
    r.output("diffuse_albedo", vk::Format::eR16G16B16A16Sfloat)
        .sameAs("visibility")
        .doc("(1 - metallic) baseColor of the primary vertex (lambert: baseColor); a = samples");
    r.output("specular_albedo", vk::Format::eR16G16B16A16Sfloat)
        .sameAs("visibility")
        .doc(
            "pre-integrated GGX reflectance E(F0, roughness, NoV) of the primary vertex "
            "(core/shading/SpecularAlbedo.h); 0 with brdf = lambert; a = samples");
}

void PathTracePass::compile(graph::CompileContext& ctx) {
    const scene::SceneGpu* scene = ctx.scene();
    if (!scene)  // sceneNeeds() culls the pass without a scene; never reached in a graph
        throw RuntimeError("pass '" + name() + "' (PathTrace): no scene");
    auto defines = scene->defines();
    bool ggx = mBrdf == "ggx";
    defines.emplace_back("BRDF_GGX", ggx ? "1" : "0");
    defines.emplace_back("PATHTRACE_COUNT_RAYS", mCountRays ? "1" : "0");
    defines.emplace_back("PATHTRACE_LAST_MIS", mLastBounceMis ? "1" : "0");
    defines.emplace_back("PATHTRACE_STRATIFY_LIGHT", mStratifyLight ? "1" : "0");
    defines.emplace_back("PATHTRACE_BUMP_SHADOWING",
                         mBumpShadowing && scene->hasNormalMaps() ? "1" : "0");
    const auto strategy =
        std::find(kEmitterSampling.begin(), kEmitterSampling.end(), mEmitterSampling);
    defines.emplace_back(
        "PATHTRACE_EMITTER_SAMPLING",
        std::to_string(strategy == kEmitterSampling.end() ? 0
                                                          : strategy - kEmitterSampling.begin()));
    defines.emplace_back("SCENE_LIGHT_SOLID_ANGLE", mLightSampling == "solidAngle" ? "1" : "0");
    mUseVisibility = ctx.connected("visibility");
    mUseAlbedo = ctx.connected("albedo");
    mUseLayout = ctx.connected(sampling::kSampleLayoutField);
    mVariant = std::string(ggx ? "ggx" : "lambert") + "," +
               feature(defines, "SCENE_HAS_EMISSIVE", "emissive") + "," +
               feature(defines, "SCENE_HAS_PUNCTUAL", "punctual") + "," +
               feature(defines, "SCENE_HAS_TEXTURES", "textures") +
               (scene->features() & scene::kSceneEnvironment ? ",environment" : "") +
               (scene->features() & scene::kSceneAlpha ? ",alpha" : "") +
               (mBumpShadowing && scene->hasNormalMaps() ? ",bump-shadowing" : "") +
               ",bounces=" + std::to_string(mMaxBounces) +
               ",primary=" + (mUseVisibility ? "gbuffer" : "own") +
               (mUseLayout ? ",layout" : ",spp=" + std::to_string(mSpp)) +
               (mEmitterSampling != "mis" ? "," + mEmitterSampling + "-only" : "") +
               (mLightSampling != "area" ? ",light-" + mLightSampling : "") +
               (mLastBounceMis ? ",last-mis" : "") + (mStratifyLight ? ",stratified" : "") +
               (mCountRays ? ",count-rays" : "");
    mTrace = ctx.createPipeline(
        "pathtrace/pathtrace.comp", defines,
        {sampling::kSampleLayoutBinding, "pathtrace_rays", "specular_albedo_table"});
    mCountersWritten = false;
    mClear = ctx.createPipeline("pathtrace/clear.comp");
}

void PathTracePass::execute(graph::ExecuteContext& ctx) {
    const auto& out = ctx.image("radiance");
    glm::ivec2 size(int(out.width()), int(out.height()));
    if (mUseLayout) {
        // Untraced pixels must read as invalid: clear everything, then trace the list (the
        // context orders the trace after the clear: both write `radiance`).
        ctx.bindFields(*mClear);
        mClear->set("size", size);
        ctx.dispatch(*mClear, out.width(), out.height());
    }
    // The graph zeroes `rays` on its first frame (counts accumulate from the first frame after
    // compile; 32 bits each: about 4000 frames of 640x360 at 1 spp before they wrap) and uploads
    // the reflectance table once.
    mCountersWritten = mCountRays;
    ctx.bindField(*mTrace, "pathtrace_rays", "rays");
    ctx.bindField(*mTrace, "specular_albedo_table", "specular_albedo_table");
    ctx.bindFields(*mTrace);
    ctx.bindField(*mTrace, sampling::kSampleLayoutBinding, sampling::kSampleLayoutField);
    uint64_t seed = ctx.frame().seed;
    mTrace->set("size", size)
        .set("seedLo", uint32_t(seed & 0xFFFFFFFFu))
        .set("seedHi", uint32_t(seed >> 32))
        .set("spp", mSpp)
        .set("maxBounces", mMaxBounces)
        .set("useVisibility", int(mUseVisibility))
        .set("useAlbedo", int(mUseAlbedo))
        .set("useLayout", int(mUseLayout))
        .set("clampIndirect", mClampIndirect);
    ctx.dispatch(*mTrace, out.width(), out.height());
}

PathTracePass::RayCounts PathTracePass::rayCounts(const gpu::Context& context,
                                                  const gpu::Buffer& rays) {
    RayCounts out{};
    auto counts = rays.downloadAs<uint32_t>(context);
    for (size_t k = 0; k < out.size() && k < counts.size(); ++k) out[k] = counts[k];
    return out;
}

nlohmann::json PathTracePass::statistics(const graph::StatisticsContext& ctx) const {
    if (!mCountersWritten) return nullptr;
    const auto c = rayCounts(ctx.gpu, ctx.buffer("rays"));
    return {{"rays_primary", c[0]},   {"rays_shadow_primary", c[1]},
            {"rays_indirect", c[2]},  {"rays_shadow_indirect", c[3]},
            {"rays_last_brdf", c[4]}, {"rays_total", c[0] + c[1] + c[2] + c[3] + c[4]}};
}

}  // namespace fovea::passes
