#include "passes/ATrousNH/ATrousNHPass.h"

#include <algorithm>
#include <glm/vec2.hpp>

#include "core/scene/Camera.h"
#include "core/vk/ComputePipeline.h"
#include "core/vk/Resources.h"

namespace fovea::passes {

namespace {
const std::vector<std::string> kStepOrders = {"decreasing", "increasing"};
const std::vector<std::string> kSchedules = {"levels", "layers"};
const std::vector<std::string> kPositionUnits = {"scene", "depth"};
const std::vector<std::string> kPositionTerms = {"plane", "distance"};
const std::vector<std::string> kDispatches = {"tiles", "full"};
constexpr int kMaxIterations = 16;
// atrous_fill block: uvec4 fillArgs, uvec4 copyArgs, uint holes, uint executed (+ padding).
constexpr vk::DeviceSize kFillStateBytes = 48;
constexpr vk::DeviceSize kFillArgsOffset = 0, kCopyArgsOffset = 16;
// State image codes of the shader: 0 = input colour (source) or `denoised` (destination),
// 1 = ping, 3 = `denoised` as a source.
constexpr int kInput = 0, kPing = 1, kDenoisedSource = 3, kDenoised = 0;
enum FillArgsMode { kResetCounters = 0, kFillLevelArgs = 1, kCopyBackArgs = 2 };
// atrous_tiles block (tile_lists.comp): 8 x uvec4 indirect args + count, then 8 lists.
constexpr vk::DeviceSize kTileArgsBytes = 8 * 16;
constexpr uint32_t kTileSize = 8;                  // = atrous_nh.comp's workgroup
constexpr uint64_t kTileListBytesPerTile = 8 * 4;  // one uint entry in each of the 8 lists
enum TileListMode { kResetTiles = 0, kBuildTiles = 1, kFinalizeTiles = 2 };

// 1 / sigma^2, or 0 = the term is off (sigma 0 would divide by zero).
float invSquare(float sigma) {
    return sigma > 0.0f ? 1.0f / (sigma * sigma) : 0.0f;
}
}  // namespace

void ATrousNHPass::params(graph::ParamVisitor& v) {
    v.add("layers", mLayers, 1,
          "foveation layers (seed 000 §3.4): 1 = classic full-screen à-trous (mask layer ids "
          "ignored), 2 = NH2LD, 3 = NH3LD; mask layer ids >= layers count as the last layer",
          {1, 3});
    v.add("iterations0", mIterations[0], 5,
          "à-trous iterations of layer 0 (fovea; seed 000's M); the only one used with 1 layer",
          {0, kMaxIterations});
    v.add("iterations1", mIterations[1], 0,
          "iterations of layer 1 (middle; seed 000's N, expected > M)", {0, kMaxIterations});
    v.add("iterations2", mIterations[2], 0,
          "iterations of layer 2 (outer; seed 000's P, expected > N)", {0, kMaxIterations});
    v.add("stepOrder", mStepOrder, "decreasing",
          "decreasing: steps 2^(n-1) .. 1 (Qi et al., seed 000 §3.4 Fig. 7); increasing: 1 .. "
          "2^(n-1) (Dammertz 2010)",
          kStepOrders);
    v.add("schedule", mSchedule, "levels",
          "levels: one dispatch per step level for all layers at once (max(M,N,P) dispatches); "
          "layers: Algorithm 1 literally, layer after layer (M+N+P dispatches)",
          kSchedules);
    v.add("fill", mFill, true,
          "after the iterations, hole-fill levels (steps 1, 2, 4, ...) give every pixel still "
          "without a value the weighted mean of valid pixels (no holes)");
    v.add("eyes", mEyes, 0,
          "side-by-side eyes (no tap crosses the seam); 0 = the frame camera's eye count", {0, 2});
    v.add("sigmaColor", mSigmaColor, 1.0f,
          "colour weight exp(-|c_p - c_q|^2 / sigma^2) (Dammertz Eq. 6); 0 = off", {0.0, 1e30});
    v.add("sigmaNormal", mSigmaNormal, 0.2f,
          "normal weight exp(-|n_p - n_q|^2 / (step^2 sigma^2)) (Dammertz's code); 0 = off",
          {0.0, 1e30});
    v.add("sigmaPosition", mSigmaPosition, 0.5f,
          "position weight exp(-|x_p - x_q|^2 / sigma^2) in positionUnit; 0 = off", {0.0, 1e30});
    v.add("positionUnit", mPositionUnit, "scene",
          "scene: sigmaPosition in scene units (Dammertz); depth: |x_p - x_q| divided by p's "
          "distance to its eye, so sigmaPosition is a fraction of the view distance and one "
          "value suits scenes of any scale (e.g. 0.05)",
          kPositionUnits);
    v.add("positionTerm", mPositionTerm, "plane",
          "geometry distance of the position weight: plane = |n_p . (x_q - x_p)|, the distance of "
          "x_q to p's tangent plane (seed 004's plane distance; needs `normal`): taps far along "
          "a flat surface keep their weight, so the large steps of the schedule still average; "
          "distance = |x_q - x_p| (Dammertz 2010): a tap 2^i px away is rejected at large i "
          "unless sigmaPosition is loose enough to blur across depth edges",
          kPositionTerms);
    v.add("sigmaTangent", mSigmaTangent, 0.0f,
          "plane term only: weight exp(-|x_q - x_p|_along^2 / sigma^2) on the distance along p's "
          "tangent plane, in positionUnit (bounds how far along a surface a tap may reach: a "
          "lighting gradient over a wall is not flattened); 0 = unbounded",
          {0.0, 1e30});
    v.add("dispatch", mDispatch, "tiles",
          "tiles: with a mask and 2-3 layers each level runs only on the 8x8 tiles holding the "
          "layers it updates (indirect dispatch from tile lists built on the GPU from the mask, "
          "rebuilt only when the mask changes; seed 000 §3.4, Alg. 1: the fovea does less work); "
          "full: every level is a full-screen dispatch (same output)",
          kDispatches);
}

void ATrousNHPass::reflect(graph::Reflection& r) const {
    r.input("color", vk::Format::eR32G32B32A32Sfloat)
        .doc("noisy radiance (e.g. PathTrace demodulated); a = samples, 0 = unsampled");
    r.input("normal").optional().floatOnly().sameAs("color").doc(
        "GBuffer world normal (rgb); open = no normal weight");
    r.input("position")
        .optional()
        .floatOnly()
        .sameAs("color")
        .doc("GBuffer world position (rgb); open = no position weight");
    r.input("mask", vk::Format::eR32Uint)
        .optional()
        .sameAs("color")
        .doc(
            "FoveationMask word: bit 0 sampled, bits 1-2 layer (0 fovea, 1 middle, 2 outer); "
            "open = one layer, sampled = color.a > 0");
    r.output("denoised", vk::Format::eR32G32B32A32Sfloat)
        .sameAs("color")
        .doc("denoised radiance; a = 1 where the pixel has a value, 0 where its eye has none");
    r.internal("fill_state", vk::Format::eUndefined)
        .buffer(kFillStateBytes)
        .indirect()
        .doc(
            "atrous_fill block (shaders/atrous_nh): the fill levels' indirect group counts, set "
            "to 0 on the GPU once no hole is left, and the hole counter");
    // Lists only when the tiles dispatch can happen (a mask is connected is known at compile).
    const bool tileLists = mDispatch == "tiles" && mLayers > 1;
    r.internal("tiles", vk::Format::eUndefined)
        .bufferPerBlock(tileLists ? kTileSize : 0, tileLists ? kTileListBytesPerTile : 0,
                        tileLists ? kTileArgsBytes : kTileArgsBytes + 4)
        .sizedBy("color")
        .indirect()
        .persistent()
        .doc(
            "atrous_tiles block (shaders/atrous_nh/tile_lists.comp): per key, the indirect "
            "group count and the list of 8x8 tiles holding the layers it updates; kept until the "
            "mask changes");
    r.internal("ping", vk::Format::eR32G32B32A32Sfloat)
        .sameAs("color")
        .doc(
            "iteration state: rgb colour, a = valid (1) or not (0); levels ping-pong between "
            "it and `denoised`");
}

void ATrousNHPass::validate(const graph::ValidateContext& ctx) const {
    // In validate(), not compile(): `fovea validate` names the graph file and the JSON pointer.
    if (ctx.connected("position") && !ctx.connected("normal") && mPositionTerm == "plane")
        ctx.fail("positionTerm",
                 "'plane' needs the normal input (the tangent plane is n_p's); connect `normal` "
                 "or set positionTerm to 'distance'");
}

void ATrousNHPass::compile(graph::CompileContext& ctx) {
    mUseMask = ctx.connected("mask");
    mUseNormal = ctx.connected("normal");
    mUsePosition = ctx.connected("position");
    // Not enforced: M < N < P is the paper's advice (§3.4), not a validity condition.
    mVariant =
        "layers=" + std::to_string(mLayers) + ",iterations=" + std::to_string(mIterations[0]);
    for (int l = 1; l < mLayers; ++l) mVariant += "/" + std::to_string(mIterations[l]);
    mUseTiles = mDispatch == "tiles" && mUseMask && mLayers > 1;
    mVariant +=
        "," + mStepOrder + "," + mSchedule + (mFill ? ",fill" : "") + (mUseMask ? ",mask" : "") +
        (mUseTiles ? ",tiles" : "") + (mUseNormal ? ",normal" : "") +
        (mUsePosition ? ",position" + std::string(mPositionUnit == "depth" ? "/depth" : "") + "/" +
                            mPositionTerm
                      : "");
    mPipeline = ctx.createPipeline("atrous_nh/atrous_nh.comp", {}, {"atrous_fill", "atrous_tiles"});
    mFillArgs = ctx.createPipeline("atrous_nh/fill_args.comp", {}, {"atrous_fill"});
    // Tile lists: one per key (set of layers), each with room for every tile of the image (the
    // `tiles` field's size, which follows `color`).
    const auto extent = ctx.extent("color");
    mTileCount = ((extent.width + kTileSize - 1) / kTileSize) *
                 ((extent.height + kTileSize - 1) / kTileSize);
    mTileLists =
        mUseTiles ? ctx.createPipeline("atrous_nh/tile_lists.comp", {}, {"atrous_tiles"}) : nullptr;
    mTilesBuilt = false;
}

nlohmann::json ATrousNHPass::statistics(const graph::StatisticsContext& ctx) const {
    nlohmann::json out = {{"tile_list_builds", mTileBuilds}, {"tiles_full", mTileCount}};
    if (mLastSchedule.empty()) return out;
    // Read back after the run: the tile counts per key (tileArgs[k].w) and the fill levels the
    // GPU let run (atrous_fill.executed, word 9).
    std::vector<uint32_t> tileWords;
    if (mUseTiles && mTilesBuilt) tileWords = ctx.buffer("tiles").downloadAs<uint32_t>(ctx.gpu);
    const auto fillWords = ctx.buffer("fill_state").downloadAs<uint32_t>(ctx.gpu);
    nlohmann::json levels = nlohmann::json::array();
    uint64_t dispatched = 0;
    for (size_t i = 0; i < mLastKeys.size(); ++i) {
        const uint32_t key = mLastKeys[i];
        const size_t word = size_t(key) * 4 + 3;
        const uint64_t tiles = key == 0                  ? mTileCount
                               : word < tileWords.size() ? tileWords[word]
                                                         : 0;
        dispatched += tiles;
        levels.push_back({{"step", mLastSchedule[i].step},
                          {"layers", mLastSchedule[i].layers},
                          {"tiles", tiles}});
    }
    const bool anyFill = mLastKeys.size() < mLastSchedule.size();
    out["levels"] = levels;
    out["main_level_tiles"] = dispatched;
    out["fill_levels_run"] = anyFill && fillWords.size() > 9 ? fillWords[9] : 0u;
    return out;
}

ATrousScheduleOptions ATrousNHPass::scheduleOptions(int width, int height, int eyes) const {
    ATrousScheduleOptions o;
    o.layerCount = mLayers;
    for (int l = 0; l < 3; ++l) o.iterations[l] = mIterations[l];
    o.decreasing = mStepOrder != "increasing";
    o.perLayer = mSchedule == "layers";
    o.fill = mFill;
    o.fillReach = std::max(width / std::max(eyes, 1), height);
    return o;
}

std::vector<uint32_t> ATrousNHPass::levelTileKeys(const std::vector<ATrousDispatch>& schedule,
                                                  int layers, bool tiles) {
    // Tile lists (seed 000 §3.4, Algorithm 1: a level reconstructs only its layers' area).
    // Invariant, after main level i: every pixel's current state is in dst_i, and every pixel
    // that level i did not filter is valid in BOTH state images (ping and `denoised`). Then:
    //  - level 0 runs on the whole screen and also writes each pixel it copies unchanged into
    //    the other image (alsoDst): the invariant holds after it;
    //  - level i > 0 must run on the tiles it filters (layers_i) and on the tiles level i - 1
    //    filtered (layers_{i-1}): their pixels are valid only in src_i and are copied to dst_i.
    //    Any other tile was not filtered by level i - 1, so it is valid in both images already
    //    and needs no work. Hence key_i = layers_i | layers_{i-1};
    //  - the last level, when it counts holes for the fill levels, sees every pixel (full).
    // 0 = full-screen dispatch; a key equal to every layer is full screen too (no list needed).
    std::vector<uint32_t> keys;
    size_t mainLevels = 0;
    while (mainLevels < schedule.size() && !schedule[mainLevels].fill) ++mainLevels;
    const bool anyFill = mainLevels < schedule.size();
    const uint32_t all = (1u << std::clamp(layers, 1, 3)) - 1u;
    for (size_t i = 0; i < mainLevels; ++i) {
        uint32_t key = 0;
        if (tiles && i > 0 && !(anyFill && i + 1 == mainLevels)) {
            key = (schedule[i].layers | schedule[i - 1].layers) & all;
            if (key == all) key = 0;
        }
        keys.push_back(key);
    }
    return keys;
}

void ATrousNHPass::buildTileLists(graph::ExecuteContext& ctx, uint32_t keys) {
    // Rebuilt only when the mask changed: the graph bumps an input's version whenever its
    // producer writes it, and FoveationMask is cached while the gaze, size and parameters stay
    // (one build per gaze, no read-back). The image handle guards against a rebuilt graph.
    const auto version = ctx.inputVersion("mask");
    const vk::Image maskImage = ctx.image("mask").image();
    if (mTilesBuilt && version && *version == mTileVersion && maskImage == mTileMaskImage &&
        (keys & ~mTileKeys) == 0)
        return;
    const auto& out = ctx.image("denoised");
    ctx.bindFields(*mTileLists);
    ctx.bindField(*mTileLists, "atrous_tiles", "tiles");
    mTileLists->set("size", glm::ivec2(int(out.width()), int(out.height())))
        .set("layerCount", mLayers)
        .set("tileStride", int(mTileCount))
        .set("keys", int(keys));
    // Last frame's indirect reads of the lists are ordered before this by the graph's barrier
    // at the start of the frame (it covers indirect-argument reads of `indirect()` fields); the
    // context orders the three steps and the levels that read the lists after them.
    ctx.dispatch(mTileLists->set("mode", int(kResetTiles)), 1);
    ctx.dispatch(mTileLists->set("mode", int(kBuildTiles)), out.width(), out.height());
    ctx.dispatch(mTileLists->set("mode", int(kFinalizeTiles)), 1);
    mTilesBuilt = true;
    mTileVersion = version.value_or(0);
    mTileMaskImage = maskImage;
    mTileKeys = keys;
    ++mTileBuilds;
}

void ATrousNHPass::execute(graph::ExecuteContext& ctx) {
    const auto& out = ctx.image("denoised");
    const int width = int(out.width()), height = int(out.height());
    const auto [eyes, eyeWidth] = scene::splitEyes(out.width(), mEyes, ctx.camera().eyeCount);
    const auto schedule = buildATrousSchedule(scheduleOptions(width, height, eyes));
    setFilterConstants(ctx, glm::ivec2(width, height), eyes, eyeWidth);

    // Main levels ping-pong between ping and `denoised`, ending in `denoised`; their count is
    // fixed by the parameters. Full screen, or (tiles) only over the tiles that need them.
    size_t mainLevels = 0;
    while (mainLevels < schedule.size() && !schedule[mainLevels].fill) ++mainLevels;
    const bool anyFill = mainLevels < schedule.size();
    const auto keys = levelTileKeys(schedule, mLayers, mUseTiles);
    mLastSchedule = schedule;
    mLastKeys = keys;
    uint32_t usedKeys = 0;
    for (uint32_t k : keys) usedKeys |= k != 0 ? 1u << k : 0u;
    if (usedKeys != 0) buildTileLists(ctx, usedKeys);
    mPipeline->bind("atrous_fill", ctx.buffer("fill_state"))
        .bind("atrous_tiles", ctx.buffer("tiles"));
    mFillArgs->bind("atrous_fill", ctx.buffer("fill_state"));
    if (anyFill) {
        // Last frame's indirect reads are ordered before this by the graph's barrier at the
        // start of the frame (it covers indirect-argument reads of `indirect()` fields).
        dispatchFillArgs(ctx, kResetCounters);
    }
    runMainLevels(ctx, schedule, keys, mainLevels, anyFill);
    if (anyFill) runFillLevels(ctx, schedule, mainLevels);
}

void ATrousNHPass::setFilterConstants(graph::ExecuteContext& ctx, glm::ivec2 size, int eyes,
                                      int eyeWidth) {
    ctx.bindFields(*mPipeline);
    mPipeline->set("size", size)
        .set("eyeWidth", eyeWidth)
        .set("eyes", eyes)
        .set("layerCount", mLayers)
        .set("useMask", int(mUseMask))
        .set("invSigmaColor2", invSquare(mSigmaColor))
        .set("invSigmaNormal2", mUseNormal ? invSquare(mSigmaNormal) : 0.0f)
        .set("invSigmaPosition2", mUsePosition ? invSquare(mSigmaPosition) : 0.0f)
        .set("positionRelative", int(mPositionUnit == "depth"))
        .set("positionPlane", int(mPositionTerm == "plane"))
        .set("invSigmaTangent2",
             mUsePosition && mPositionTerm == "plane" ? invSquare(mSigmaTangent) : 0.0f)
        .set("tileKey", 0)
        .set("tileStride", int(mTileCount))
        .set("alsoDst", -1);
}

void ATrousNHPass::dispatchFillArgs(graph::ExecuteContext& ctx, int mode) {
    const auto& out = ctx.image("denoised");
    const auto groups = mPipeline->groupCount(out.width(), out.height());
    mFillArgs->set("mode", mode).set("fullGroups", glm::ivec2(groups[0], groups[1]));
    ctx.dispatch(*mFillArgs, 1);
}

void ATrousNHPass::runMainLevels(graph::ExecuteContext& ctx,
                                 const std::vector<ATrousDispatch>& schedule,
                                 const std::vector<uint32_t>& keys, size_t mainLevels,
                                 bool anyFill) {
    const auto& out = ctx.image("denoised");
    int src = kInput;
    for (size_t i = 0; i < mainLevels; ++i) {
        const bool last = i + 1 == mainLevels;
        const int dst = (mainLevels - 1 - i) % 2 == 0 ? kDenoised : kPing;
        mPipeline->set("src", src)
            .set("dst", dst)
            .set("activeLayers", int(schedule[i].layers))
            .set("stepWidth", schedule[i].step)
            .set("fillOnly", 0)
            .set("countHoles", int(last && anyFill))
            .set("tileKey", int(keys[i]))
            .set("alsoDst", mUseTiles && i == 0 && !last ? (dst == kPing ? kDenoised : kPing) : -1);
        if (keys[i] == 0)
            ctx.dispatch(*mPipeline, out.width(), out.height());
        else
            ctx.dispatchIndirect(*mPipeline, ctx.buffer("tiles"), vk::DeviceSize(keys[i]) * 16);
        src = dst == kPing ? kPing : kDenoisedSource;
    }
    mPipeline->set("tileKey", 0).set("alsoDst", -1);
}

void ATrousNHPass::runFillLevels(graph::ExecuteContext& ctx,
                                 const std::vector<ATrousDispatch>& schedule, size_t mainLevels) {
    const auto& out = ctx.image("denoised");
    const gpu::Buffer& fillState = ctx.buffer("fill_state");
    if (mainLevels == 0) {
        // No main level: a copy brings the input into `denoised` and counts its holes.
        mPipeline->set("src", kInput)
            .set("dst", kDenoised)
            .set("activeLayers", 0)
            .set("stepWidth", 1)
            .set("fillOnly", 0)
            .set("countHoles", 1);
        ctx.dispatch(*mPipeline, out.width(), out.height());
    }
    // Fill levels alternate denoised -> ping -> denoised ...; each runs only while the previous
    // level left a hole (fill_args.comp writes 0 groups otherwise), so the levels that run are a
    // prefix of the schedule and an odd count leaves the result in ping: copied back at the end.
    // The output equals running every fill level (a level without holes only copies).
    for (size_t i = mainLevels; i < schedule.size(); ++i) {
        const bool even = (i - mainLevels) % 2 == 0;
        dispatchFillArgs(ctx, kFillLevelArgs);
        mPipeline->set("src", even ? kDenoisedSource : kPing)
            .set("dst", even ? kPing : kDenoised)
            .set("activeLayers", int(schedule[i].layers))
            .set("stepWidth", schedule[i].step)
            .set("fillOnly", 1)
            .set("countHoles", 1);
        ctx.dispatchIndirect(*mPipeline, fillState, kFillArgsOffset);
    }
    dispatchFillArgs(ctx, kCopyBackArgs);
    mPipeline->set("src", kPing)
        .set("dst", kDenoised)
        .set("activeLayers", 0)
        .set("fillOnly", 0)
        .set("countHoles", 0);
    ctx.dispatchIndirect(*mPipeline, fillState, kCopyArgsOffset);
}

}  // namespace fovea::passes
