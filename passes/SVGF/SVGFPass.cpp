#include "passes/SVGF/SVGFPass.h"

#include "core/graph/DenoiserInputs.h"
#include "core/sampling/VisualPolar.h"
#include "core/vk/ComputePipeline.h"

namespace fovea::passes {

namespace {
constexpr uint32_t kStatCount = 5;  // svgf_common.glsl SVGF_STAT_*
}  // namespace

SVGFPass::SVGFPass() = default;
SVGFPass::~SVGFPass() = default;

void SVGFPass::params(graph::ParamVisitor& v) {
    v.add("iterations", mIterations, 5,
          "a-trous levels; level i steps 2^i pixels (Schied et al. 2017 §4.3: 5)", {1.0f, 8.0f});
    v.add("feedbackTap", mFeedbackTap, 1,
          "how many a-trous levels the colour history has been through: 0 = the unfiltered "
          "temporal accumulation, 1 = the output of the first level (§4.1: the paper's "
          "choice), k = of level k (1-based, counting levels). The specs' and Falcor's "
          "FeedbackTap is a 0-based level index (-1 = unfiltered): their 0 is our 1, Falcor's "
          "default 1 is our 2. At most `iterations`",
          {0.0f, 8.0f});
    v.add("alpha", mAlpha, 0.2f,
          "colour: minimum weight of the new sample, used as max(alpha, 1/h): the exact running "
          "mean while 1/h >= alpha, then an EMA (§4.1: 0.2)",
          {0.001f, 1.0f});
    v.add("momentsAlpha", mMomentsAlpha, 0.2f,
          "luminance moments: the same for the first and second moment (§4.2: 0.2)",
          {0.001f, 1.0f});
    v.add("sigmaLuminance", mSigmaLuminance, 4.0f,
          "sigma_l of the a-trous luminance edge-stopping function, in standard deviations: "
          "the larger of the centre's prefiltered and the tap's (§4.4, Eq. 5 uses the centre's "
          "alone; symmetric here so that heavy-tailed noise keeps its mean, issue 12). Paper 4, "
          "Falcor 10. The spatial variance estimate (§4.2) has no luminance term",
          {1e-3f, 1e6f});
    v.add("sigmaNormal", mSigmaNormal, 128.0f,
          "sigma_n: exponent of max(0, n_p . n_q) (§4.4, Eq. 4: 128); 0 turns the term off",
          {0.0f, 1e4f});
    v.add("sigmaDepth", mSigmaDepth, 1.0f,
          "sigma_z: depth difference allowed, in units of the screen-space depth gradient times "
          "the tap offset (§4.4, Eq. 3: 1)",
          {0.0f, 1e6f});
    v.add("historyForVariance", mHistoryForVariance, 4.0f,
          "history length below which the variance is estimated spatially (§4.2: 4 frames)",
          {0.0f, 256.0f});
    v.add("spatialRadius", mSpatialRadius, 3,
          "radius of the spatial variance estimate: (2r+1)^2 pixels (§4.2: 7x7)", {0.0f, 8.0f});
    v.add("maxHistory", mMaxHistory, 32.0f,
          "cap of the history length h (specs §1: 32); with alpha 0.2 only the variance "
          "fallback and the output `accumulated` see it",
          {1.0f, 4096.0f});
    v.add("positionThreshold", mPositionThreshold, 0.02f,
          "disocclusion: a history tap is rejected when its world position is farther than this "
          "times the pixel's view depth (as BMFR)",
          {0.0f, 1e6f});
    v.add("normalThreshold", mNormalThreshold, 0.9f,
          "disocclusion: a history tap is rejected when the cosine between its normal and the "
          "pixel's is below this",
          {-1.0f, 1.0f});
}

void SVGFPass::reflect(graph::Reflection& r) const {
    // Every size follows `color`: the screen, or a Visual-Polar grid (seed 003 P5 runs the
    // denoisers in that space; graphs/koskela_vp_svgf.json).
    using graph::DenoiserInput;
    graph::declareDenoiserInput(r, DenoiserInput::Color);
    graph::declareDenoiserInput(r, DenoiserInput::Position);
    graph::declareDenoiserInput(r, DenoiserInput::Normal);
    graph::declareDenoiserInput(r, DenoiserInput::Depth);
    graph::declareDenoiserInput(r, DenoiserInput::Albedo);
    graph::declareDenoiserInput(r, DenoiserInput::Emission);
    graph::declareDenoiserInput(r, DenoiserInput::Motion);
    graph::declareDenoiserInput(
        r, DenoiserInput::VisualPolar,
        "with a Visual-Polar `color` and GBuffer VP `motion`: history taps, 3x3 fallback, "
        "spatial-variance and a-trous taps at each column's own phi "
        "height, wrapped on phi, the depth gradient too (P5 §3.3); open: screen addressing");

    const auto rgba32 = vk::Format::eR32G32B32A32Sfloat;
    r.output("filtered", rgba32).sameAs("color").doc("final colour: last level remodulated, a = 1");
    r.output("illumination", rgba32)
        .sameAs("color")
        .doc("last level, demodulated; a = propagated variance");
    r.output("accumulated", rgba32)
        .sameAs("color")
        .doc("temporal accumulation (demodulated); a = history length h");
    r.output("stats", vk::Format::eUndefined)
        .buffer(kStatCount * sizeof(uint32_t))
        .persistent()
        .zeroOnReset()
        .doc(
            "uint[5] since the last reset: non-finite colour samples, non-finite geometry/motion "
            "pixels, rejected reprojections, spatial-variance pixels, negative-variance clamps");
    // Pass-declared histories (prev_hist_* in the shaders): docs/passes/SVGF.md.
    r.internal("hist_color", rgba32)
        .sameAs("color")
        .history()
        .doc("colour after level `feedbackTap`");
    r.internal("hist_moments", vk::Format::eR32G32Sfloat)
        .sameAs("color")
        .history()
        .doc("luminance moments (mu1, mu2), fp32: l^2 overflows fp16 above l = 256");
    r.internal("hist_length", vk::Format::eR32Sfloat)
        .sameAs("color")
        .history()
        .doc("history length h");
    r.internal("hist_position", rgba32)
        .sameAs("color")
        .history()
        .doc("world position (disocclusion test)");
    r.internal("hist_normal", vk::Format::eR16G16B16A16Sfloat)
        .sameAs("color")
        .history()
        .doc("normal (disocclusion test)");
    r.internal("atrous_a", rgba32)
        .sameAs("color")
        .doc("a-trous ping-pong: rgb colour, a = variance");
    r.internal("atrous_b", rgba32)
        .sameAs("color")
        .doc("a-trous ping-pong: rgb colour, a = variance");
}

void SVGFPass::validate(const graph::ValidateContext& ctx) const {
    if (mFeedbackTap > mIterations)
        ctx.fail("feedbackTap", "must be at most `iterations` (" + std::to_string(mIterations) +
                                    "): there is no level " + std::to_string(mFeedbackTap));
    graph::validateVisualPolarInputs(ctx);
}

void SVGFPass::compile(graph::CompileContext& ctx) {
    mUseMotion = ctx.connected("motion");
    mUseVp = ctx.connected("vp");
    mUseAlbedo = ctx.connected("albedo");
    mUseEmission = ctx.connected("emission");
    mReproject = ctx.createPipeline("svgf/reproject.comp");
    mVariance = ctx.createPipeline("svgf/variance.comp", {}, {"atrous_out"});
    mATrous = ctx.createPipeline("svgf/atrous.comp", {}, {"atrous_in", "atrous_out"});
}

void SVGFPass::execute(graph::ExecuteContext& ctx) {
    // Every history is written each frame, so one answers for all of them.
    const bool history = ctx.historyValid("hist_length");
    const auto& out = ctx.image("filtered");
    const glm::ivec2 size(int(out.width()), int(out.height()));

    // `stats` restarts with the history: the graph zeroes it (zeroOnReset).

    // §4.1 temporal accumulation.
    ctx.bindFields(*mReproject);
    mReproject->set("size", size)
        .set("history", int(history))
        .set("useMotion", int(mUseMotion))
        .set("useVp", int(mUseVp))
        .set("writeColorHistory", int(mFeedbackTap == 0))
        .set("alpha", mAlpha)
        .set("momentsAlpha", mMomentsAlpha)
        .set("maxHistory", mMaxHistory)
        .set("positionThreshold", mPositionThreshold)
        .set("normalThreshold", mNormalThreshold);
    ctx.dispatch(*mReproject, out.width(), out.height());

    // §4.2 variance estimate into the first ping-pong image.
    const gpu::Image* ping = &ctx.image("atrous_a");
    const gpu::Image* pong = &ctx.image("atrous_b");
    ctx.bindFields(*mVariance);
    mVariance->bind("atrous_out", *ping);
    mVariance->set("size", size)
        .set("radius", mSpatialRadius)
        .set("useVp", int(mUseVp))
        .set("historyForVariance", mHistoryForVariance)
        .set("sigmaNormal", mSigmaNormal)
        .set("sigmaDepth", mSigmaDepth);
    ctx.dispatch(*mVariance, out.width(), out.height());

    // §4.3 a-trous levels, step 2^i.
    ctx.bindFields(*mATrous);
    mATrous->set("size", size)
        .set("useAlbedo", int(mUseAlbedo))
        .set("useEmission", int(mUseEmission))
        .set("useVp", int(mUseVp))
        .set("sigmaLuminance", mSigmaLuminance)
        .set("sigmaNormal", mSigmaNormal)
        .set("sigmaDepth", mSigmaDepth);
    for (int level = 0; level < mIterations; ++level) {
        mATrous->bind("atrous_in", *ping).bind("atrous_out", *pong);
        mATrous->set("stepSize", 1 << level)
            .set("writeColorHistory", int(level + 1 == mFeedbackTap))
            .set("last", int(level + 1 == mIterations));
        ctx.dispatch(*mATrous, out.width(), out.height());
        std::swap(ping, pong);
    }
}

nlohmann::json SVGFPass::statistics(const graph::StatisticsContext& ctx) const {
    // The `stats` counters (docs/passes/SVGF.md#stats), since the last reset or camera cut.
    const auto counts = ctx.buffer("stats").downloadAs<uint32_t>(ctx.gpu);
    if (counts.size() < kStatCount) return nullptr;
    return {{"nonfinite_color_samples", counts[0]},
            {"nonfinite_geometry_pixels", counts[1]},
            {"rejected_reprojections", counts[2]},
            {"spatial_variance_pixels", counts[3]},
            {"negative_variance_clamps", counts[4]}};
}

}  // namespace fovea::passes
