#include "passes/BMFR/BMFRPass.h"

#include "core/graph/DenoiserInputs.h"
#include "core/sampling/BlockGrid.h"
#include "core/sampling/VisualPolar.h"
#include "core/vk/ComputePipeline.h"
#include "core/vk/Timestamps.h"

namespace fovea::passes {

namespace {

constexpr uint32_t kStatsBytes = 16;  // uint counters[4]
constexpr uint32_t kCoefStride = 96;  // floats per block (bmfr_common.glsl)
constexpr float kMaxCount = 255.0f;   // P2 §3.2: the count is only needed while small (8 bits)

}  // namespace

BMFRPass::BMFRPass() = default;
BMFRPass::~BMFRPass() = default;

void BMFRPass::params(graph::ParamVisitor& v) {
    v.add("features", mFeatures, "default",
          "feature set: default = [1, n.xyz, w.xyz, w.xyz^2] (P2 Eq. 8); albedo = default + "
          "albedo.rgb (needs the albedo input)",
          {"default", "albedo"});
    v.add("variant", mVariant, "default",
          "sets the six choices below that are left at 'variant': published = what the authors' "
          "OpenCL code computes (maZZZu/bmfr bmfr.cl, the code P2 measured); fovea = fovea's "
          "first reading of P2 §3; default = per choice, the one measured better on the "
          "shoot-out scenes: fovea's featureScaling and misses, the published rest "
          "(docs/passes/BMFR.md#variants)",
          {"default", "published", "fovea"});
    v.add("offsetTable", mOffsetTable, "variant",
          "block-grid offsets (P2 §6.1): published = the authors' 16 BLOCK_OFFSETS; fovea = 16 "
          "drawn uniformly over [0, 32)^2 (core/sampling/BlockGrid.h)",
          {"variant", "published", "fovea"});
    v.add("featureScaling", mScaling, "variant",
          "P2 §3.4 scaling and noise: published = raw positions and raw squares mapped to [0, 1] "
          "per block (only shifted when the block spans <= 1 scene unit), normals raw, noise on "
          "all but the constant column; fovea = positions centred before squaring, every feature "
          "stretched to [-1, 1], noise on every column",
          {"variant", "published", "fovea"});
    v.add("blockEdges", mEdges, "variant",
          "block rows outside the image: mirror = the edge pixels mirrored into them (published); "
          "zero = no rows (fovea)",
          {"variant", "mirror", "zero"});
    v.add("misses", mMisses, "variant",
          "pixels without a surface: fit = rows of the fit with the G-buffer's miss features, and "
          "given the fit's value (published); skip = not fitted, their accumulated value kept "
          "(fovea)",
          {"variant", "fit", "skip"});
    v.add("historyCount", mCount, "variant",
          "phase I blend weight 1/(n+1) from the bilinearly interpolated history count: "
          "unrounded = n as interpolated, only the stored count rounded (published); rounded = n "
          "rounded first (fovea; P2 §3.2 says the count is rounded)",
          {"variant", "unrounded", "rounded"});
    v.add("fitClamp", mClamp, "variant",
          "phase II result: nonnegative = clamped at 0 (published); blockmax = also at the "
          "block's largest accumulated value (fovea)",
          {"variant", "nonnegative", "blockmax"});
    v.add("epsilon", mEpsilon, 0.01f,
          "stochastic regularization: uniform noise in [-epsilon, epsilon] added to the scaled "
          "features for the fit only (P2 §3.4: 0.01); 0 = off (the drop guard still holds)",
          {0.0f, 1.0f});
    v.add("alpha", mAlpha1, 0.2f,
          "phase I: minimum weight of the new sample; CMA until 1/(n+1) would fall below it, then "
          "EMA (P2 §3.2: 0.2)",
          {0.001f, 1.0f});
    v.add("alphaFiltered", mAlpha3, 0.1f,
          "phase III: the same for the second accumulation of the fitted frame (P2 §3.5: 0.1)",
          {0.001f, 1.0f});
    v.add("positionThreshold", mPositionThreshold, 0.02f,
          "discard test: a history tap is rejected when its world position is farther than this "
          "times the pixel's distance from the camera",
          {0.0f, 1e6f});
    v.add("normalThreshold", mNormalThreshold, 0.5f,
          "discard test: a history tap is rejected when the cosine between its normal and the "
          "pixel's is below this",
          {-1.0f, 1.0f});
    v.add("blockOffsets", mOffsets, true,
          "move the block grid every frame by one of 16 fixed offsets (P2 §3.5, §6.1; which 16: "
          "offsetTable); false = blocks aligned with the image corner");
    v.add("dropTolerance", mDropTolerance, 1e-3f,
          "QR guard: a column whose remaining norm is at most this times its original norm is "
          "numerically dependent and dropped (coefficient 0) instead of dividing by ~0",
          {0.0f, 0.5f});
    v.add("fp16History", mFp16History, false,
          "store the colour histories (phase I and III) as rgba16f instead of rgba32f (P2 §6.1: "
          "half precision halves their bandwidth); values saturate at 65504");
    v.add("timings", mTimings, false,
          "benchmarks: GPU timestamps around each of the 4 kernels (BMFRPass::kernelMs)");
}

void BMFRPass::reflect(graph::Reflection& r) const {
    const auto undefined = vk::Format::eUndefined;
    // Every size follows `color`: the screen, or a Visual-Polar grid (seed 003 P5 §3.3: BMFR runs
    // unchanged on the VP image; reprojection comes from the VP-space `motion`).
    using graph::DenoiserInput;
    graph::declareDenoiserInput(r, DenoiserInput::Color);
    graph::declareDenoiserInput(r, DenoiserInput::Position);
    graph::declareDenoiserInput(r, DenoiserInput::Normal);
    graph::declareDenoiserInput(r, DenoiserInput::Albedo, "a feature with features = albedo");
    graph::declareDenoiserInput(r, DenoiserInput::Emission);
    graph::declareDenoiserInput(r, DenoiserInput::Motion);
    graph::declareDenoiserInput(
        r, DenoiserInput::VisualPolar,
        "with a Visual-Polar `color` and GBuffer VP `motion`: history taps at each column's own "
        "phi height, wrapped on phi (P5 §3.3); with the "
        "warp's staircase the block columns follow its x offset (P5 §3.3); open: screen "
        "addressing");

    const auto rgba32 = vk::Format::eR32G32B32A32Sfloat;
    r.output("filtered", rgba32)
        .sameAs("color")
        .doc("final colour: phase III result remodulated, a = 1");
    r.output("accumulated", rgba32)
        .sameAs("color")
        .doc("phase I: accumulated demodulated radiance, a = samples");
    r.output("fitted", rgba32)
        .sameAs("color")
        .doc("phase II: weighted sum of the block fits (demodulated)");
    r.output("stats", undefined)
        .buffer(kStatsBytes)
        .persistent()
        .zeroOnReset()
        .doc(
            "uint[4] since the last reset: non-finite colour samples, non-finite geometry "
            "pixels, negative colour samples, blocks with dropped columns");
    // Private histories: the graph keeps each one's previous frame (shaders: prev_hist_*) and says
    // when it holds none (first frame, reset, camera cut, resize).
    r.internal("hist_position", rgba32)
        .sameAs("color")
        .history()
        .doc("phase I history: world positions");
    r.internal("hist_normal", vk::Format::eR16G16B16A16Sfloat)
        .sameAs("color")
        .history()
        .doc("phase I history: normals");
    const auto history = mFp16History ? vk::Format::eR16G16B16A16Sfloat : rgba32;
    r.internal("hist_accum", history)
        .sameAs("color")
        .history()
        .doc("phase I history: colour + count");
    r.internal("hist_filtered", history)
        .sameAs("color")
        .history()
        .doc("phase III history: colour + count");
    r.internal("coefficients", vk::Format::eUndefined)
        .bufferPerBlock(32, kCoefStride * sizeof(float), 0, 1)
        .doc(
            "phase II: per-block fit (bmfr_common.glsl layout); one block more per axis than "
            "the image needs, so every block offset is covered");
    r.internal("reprojection", rgba32)
        .sameAs("color")
        .doc("phase I -> III: xy previous pixel, z accepted-tap mask (4 bits)");
}

void BMFRPass::validate(const graph::ValidateContext& ctx) const {
    if (mFeatures == "albedo" && !ctx.connected("albedo"))
        ctx.fail("features", "'albedo' needs the input 'albedo' connected");
    graph::validateVisualPolarInputs(ctx);
}

BMFRPass::Choices BMFRPass::choices() const {
    // A choice left at "variant" follows `variant` (`defaultIsPublished`: what the default variant
    // takes, docs/passes/BMFR.md#variants); otherwise its own value names the behaviour.
    auto pick = [&](const std::string& value, const char* publishedValue, bool defaultIsPublished) {
        if (value != "variant") return value == publishedValue;
        return mVariant == "default" ? defaultIsPublished : mVariant == "published";
    };
    Choices c;
    c.publishedOffsets = pick(mOffsetTable, "published", true);
    c.publishedScaling = pick(mScaling, "published", false);
    c.mirrorEdges = pick(mEdges, "mirror", true);
    c.fitMisses = pick(mMisses, "fit", false);
    c.unroundedCount = pick(mCount, "unrounded", true);
    c.clampBlockMax = !pick(mClamp, "nonnegative", true);
    return c;
}

std::string BMFRPass::variant() const {
    const Choices c = choices();
    return mFeatures + ",offsets=" + (c.publishedOffsets ? "published" : "fovea") +
           ",scaling=" + (c.publishedScaling ? "published" : "fovea") +
           ",edges=" + (c.mirrorEdges ? "mirror" : "zero") +
           ",misses=" + (c.fitMisses ? "fit" : "skip") +
           ",count=" + (c.unroundedCount ? "unrounded" : "rounded") +
           ",clamp=" + (c.clampBlockMax ? "blockmax" : "nonnegative");
}

void BMFRPass::compile(graph::CompileContext& ctx) {
    const bool albedoFeature = mFeatures == "albedo";
    mChoices = choices();
    auto flag = [](bool b) { return std::string(b ? "1" : "0"); };
    mUseMotion = ctx.connected("motion");
    mUseAlbedo = ctx.connected("albedo");
    mUseEmission = ctx.connected("emission");
    mUseVp = ctx.connected("vp");
    const std::vector<std::pair<std::string, std::string>> defines = {
        {"BMFR_ALBEDO", albedoFeature ? "1" : "0"},
        {"BMFR_FP16_HISTORY", mFp16History ? "1" : "0"},
        {"BMFR_PUBLISHED_SCALING", flag(mChoices.publishedScaling)},
        {"BMFR_MIRROR_EDGES", flag(mChoices.mirrorEdges)},
        {"BMFR_FIT_MISSES", flag(mChoices.fitMisses)},
        {"BMFR_CLAMP_BLOCKMAX", flag(mChoices.clampBlockMax)},
        {"BMFR_UNROUNDED_COUNT", flag(mChoices.unroundedCount)}};
    mAccumulate = ctx.createPipeline("bmfr/accumulate.comp", defines);
    mFit = ctx.createPipeline("bmfr/fit.comp", defines);
    mWeightedSum = ctx.createPipeline("bmfr/weighted_sum.comp", defines);
    mSecond = ctx.createPipeline("bmfr/accumulate_filtered.comp", defines);
    mTimestamps.reset();
    mTimingsPending = false;
    if (mTimings) mTimestamps = std::make_unique<gpu::TimestampPool>(ctx.gpu(), 5);
}

void BMFRPass::readTimings() {
    if (!mTimestamps || !mTimingsPending) return;
    mTimingsPending = false;
    // Frames are synchronous (the graph waits for each), so last frame's queries are done.
    std::vector<uint64_t> t = mTimestamps->readTicks(5);
    for (int i = 0; i < 4; ++i) mKernelMs[size_t(i)] = mTimestamps->ticksToMs(t[i + 1] - t[i]);
}

void BMFRPass::execute(graph::ExecuteContext& ctx) {
    const auto& cmd = ctx.cmd();
    readTimings();
    // Every history is written each frame, so one answers for all four.
    const bool history = ctx.historyValid("hist_accum");
    const auto& out = ctx.image("filtered");
    const glm::ivec2 size(int(out.width()), int(out.height()));
    // Blocks of the image BMFR runs on (the render size, or a smaller Visual-Polar grid: the
    // per-block buffer follows the render size, which covers it).
    mBlocksX = blocksAcross(out.width());
    mBlocksY = blocksAcross(out.height());

    // `stats` restarts with the history: the graph zeroes it (zeroOnReset).
    if (mTimestamps) {
        mTimestamps->reset(cmd);
        mTimestamps->write(cmd, 0);
    }
    auto stamp = [&](uint32_t i) {
        if (mTimestamps) mTimestamps->write(cmd, i);
    };

    // (I) accumulation.
    ctx.bindFields(*mAccumulate);
    mAccumulate->set("size", size)
        .set("history", int(history))
        .set("useMotion", int(mUseMotion))
        .set("alpha", mAlpha1)
        .set("maxCount", kMaxCount)
        .set("positionThreshold", mPositionThreshold)
        .set("normalThreshold", mNormalThreshold)
        .set("useVp", int(mUseVp));
    ctx.dispatch(*mAccumulate, out.width(), out.height());
    stamp(1);

    // (II) fit: one workgroup of 256 threads per block.
    // P2 §6.1's moving block grid (core/sampling/BlockGrid.h, shared with VisualPolarWarp).
    const auto table = mChoices.publishedOffsets ? sampling::BlockGridTable::Published
                                                 : sampling::BlockGridTable::Fovea;
    const auto offset =
        mOffsets ? sampling::blockGridOffset(ctx.frame().index, table) : std::array<int, 2>{0, 0};
    const uint64_t seed = ctx.frame().seed;
    const uint32_t frameSeed = uint32_t(seed) ^ (uint32_t(seed >> 32) * 0x9e3779b9u) ^
                               (uint32_t(ctx.frame().index) * 0x85ebca6bu);
    ctx.bindFields(*mFit);
    mFit->set("size", size)
        .set("offset", glm::ivec2(offset[0], offset[1]))
        .set("blocksX", mBlocksX)
        .set("seed", frameSeed)
        .set("epsilon", mEpsilon)
        .set("dropTolerance", mDropTolerance)
        .set("useVp", int(mUseVp))
        .set("frame", uint32_t(ctx.frame().index));
    ctx.dispatch(*mFit, uint32_t(mBlocksX * mBlocksY) * 256u, 1);
    stamp(2);

    // (II) weighted sum with the noise-free features.
    ctx.bindFields(*mWeightedSum);
    mWeightedSum->set("size", size)
        .set("offset", glm::ivec2(offset[0], offset[1]))
        .set("blocksX", mBlocksX)
        .set("useVp", int(mUseVp));
    ctx.dispatch(*mWeightedSum, out.width(), out.height());
    stamp(3);

    // (III) second accumulation + remodulation.
    ctx.bindFields(*mSecond);
    mSecond->set("size", size)
        .set("useAlbedo", int(mUseAlbedo))
        .set("useEmission", int(mUseEmission))
        .set("alpha", mAlpha3)
        .set("maxCount", kMaxCount)
        .set("useVp", int(mUseVp));
    ctx.dispatch(*mSecond, out.width(), out.height());
    stamp(4);
    mTimingsPending = mTimestamps != nullptr;
}

nlohmann::json BMFRPass::statistics(const graph::StatisticsContext& ctx) const {
    // The `stats` counters (docs/passes/BMFR.md#stats), since the last reset or camera cut.
    const auto counts = ctx.buffer("stats").downloadAs<uint32_t>(ctx.gpu);
    if (counts.size() < 4) return nullptr;
    return {{"nonfinite_color_samples", counts[0]},
            {"nonfinite_geometry_pixels", counts[1]},
            {"negative_color_samples", counts[2]},
            {"rank_deficient_blocks", counts[3]}};
}

}  // namespace fovea::passes
