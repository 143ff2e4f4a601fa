// ATrousNH: edge-avoiding à-trous wavelet denoiser (Dammertz et al. 2010) with seed 000's
// non-homogeneous changes (Peres et al. 2023, §3.4, Eq. 2, Algorithm 1): a sample mask in the
// weights, per-layer iteration counts, decreasing step width, both eyes in one dispatch. With one
// layer and no mask it is the classic full-screen à-trous (the Base pipeline's denoiser).
#pragma once
#include <glm/vec2.hpp>
#include <memory>
#include <string>
#include <vector>

#include "core/graph/Pass.h"
#include "passes/ATrousNH/ATrousSchedule.h"

namespace fovea::passes {

class ATrousNHPass : public graph::Pass {
public:
    void params(graph::ParamVisitor& v) override;
    void reflect(graph::Reflection& r) const override;
    void validate(const graph::ValidateContext& ctx) const override;
    void compile(graph::CompileContext& ctx) override;
    void execute(graph::ExecuteContext& ctx) override;
    std::string variant() const override { return mVariant; }
    // tile_list_builds: how often the tile lists were rebuilt (once per mask change); `levels`:
    // the last frame's main levels (step, layers, 8x8 tiles dispatched, read back from the tile
    // lists) and the fill levels that ran: the work a level does is its tiles, so a layer's
    // cost is in proportion to the pixels it filters (seed 000 §3.4, Alg. 1).
    nlohmann::json statistics(const graph::StatisticsContext& ctx) const override;

    // The schedule execute() records for an image of `width` x `height` with `eyes` eyes.
    ATrousScheduleOptions scheduleOptions(int width, int height, int eyes) const;
    // Per main level of `schedule`: the tile list (a set of layers, bit l = layer l) its dispatch
    // runs over, or 0 for a full-screen dispatch (always 0 without `tiles`). See the .cpp for why
    // key_i = layers_i | layers_{i-1} keeps the ping-pong images right.
    static std::vector<uint32_t> levelTileKeys(const std::vector<ATrousDispatch>& schedule,
                                               int layers, bool tiles);

    // For tests: the capacity of one tile list (the lists are the `tiles` field, the
    // atrous_tiles block of shaders/atrous_nh/tile_lists.comp).
    uint32_t tileCount() const { return mTileCount; }
    uint64_t tileListBuilds() const { return mTileBuilds; }

private:
    int mLayers{};
    int mIterations[3]{};
    std::string mStepOrder{};
    std::string mSchedule{};
    bool mFill{};
    int mEyes{};
    float mSigmaColor{};
    float mSigmaNormal{};
    float mSigmaPosition{};
    std::string mPositionUnit{};
    std::string mPositionTerm{};
    float mSigmaTangent{};
    std::string mDispatch{};
    bool mUseMask = false, mUseNormal = false, mUsePosition = false;
    std::string mVariant;
    std::unique_ptr<gpu::ComputePipeline> mPipeline;
    // GPU-driven hole filling: fill levels are indirect dispatches whose group count the GPU
    // sets to 0 once no hole is left (no read-back; most frames need no fill level at all).
    std::unique_ptr<gpu::ComputePipeline> mFillArgs;
    // Layer-restricted levels (dispatch = tiles, mask, >= 2 layers): per-key tile lists built by
    // tile_lists.comp, cached until the mask input's version (or image) changes.
    void buildTileLists(graph::ExecuteContext& ctx, uint32_t keys);
    // execute() in steps: the push constants every level shares, the main levels (full screen
    // or over tile lists), the GPU-driven fill levels and their copy-back.
    void setFilterConstants(graph::ExecuteContext& ctx, glm::ivec2 size, int eyes, int eyeWidth);
    void dispatchFillArgs(graph::ExecuteContext& ctx, int mode);  // fill_args.comp, one thread
    void runMainLevels(graph::ExecuteContext& ctx, const std::vector<ATrousDispatch>& schedule,
                       const std::vector<uint32_t>& keys, size_t mainLevels, bool anyFill);
    void runFillLevels(graph::ExecuteContext& ctx, const std::vector<ATrousDispatch>& schedule,
                       size_t mainLevels);
    bool mUseTiles = false;
    std::unique_ptr<gpu::ComputePipeline> mTileLists;
    uint32_t mTileCount = 0;
    bool mTilesBuilt = false;
    uint64_t mTileVersion = 0;
    vk::Image mTileMaskImage;
    uint32_t mTileKeys = 0;
    uint64_t mTileBuilds = 0;
    // The last frame's schedule and tile keys, for statistics().
    std::vector<ATrousDispatch> mLastSchedule;
    std::vector<uint32_t> mLastKeys;
};

}  // namespace fovea::passes
