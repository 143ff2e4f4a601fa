// BMFR: Blockwise Multi-Order Feature Regression (seed 003, P2 §3): (I) temporal accumulation of
// the demodulated noisy radiance with a per-tap discard test, (II) per-32x32-block least-squares
// fit of noise-free features [1, n, w, w^2] (augmented Householder QR with stochastic
// regularization, block offsets moving every frame), weighted sum, (III) second accumulation
// reusing phase I's discard decisions, and remodulation by albedo. Numerically guarded: see
// docs/passes/BMFR.md. `variant` picks what the authors' OpenCL code (maZZZu/bmfr) computes or
// fovea's reading of the paper, one named parameter per difference (docs/passes/BMFR.md#variants).
#pragma once
#include <array>
#include <cstdint>
#include <memory>
#include <string>

#include "core/graph/Pass.h"

namespace fovea::gpu {
class TimestampPool;
}

namespace fovea::passes {

class BMFRPass : public graph::Pass {
public:
    BMFRPass();
    ~BMFRPass() override;

    void params(graph::ParamVisitor& v) override;
    void reflect(graph::Reflection& r) const override;
    void compile(graph::CompileContext& ctx) override;
    void validate(const graph::ValidateContext& ctx) const override;
    void execute(graph::ExecuteContext& ctx) override;
    std::string variant() const override;
    nlohmann::json statistics(const graph::StatisticsContext& ctx) const override;

    // Blocks per row for an image `width` wide (one more than needed without offsets, so that
    // any offset still covers the image).
    static int blocksAcross(uint32_t extent) { return int((extent + 31u) / 32u) + 1; }

    // GPU ms of each kernel in the last frame whose timestamps were read back (they are read at
    // the start of the next execute): accumulate, fit, weighted sum, second accumulation.
    // Negative until available.
    const std::array<double, 4>& kernelMs() const { return mKernelMs; }

    // Each difference between fovea's BMFR and the authors' OpenCL code (maZZZu/bmfr), resolved
    // from `variant` and the per-choice parameters (docs/passes/BMFR.md "Variants").
    struct Choices {
        bool publishedOffsets = true;   // the authors' BLOCK_OFFSETS table
        bool publishedScaling = false;  // raw squares, [0, 1] positions, raw normals, their noise
        bool mirrorEdges = true;        // block rows outside the image mirror the edge pixels
        bool fitMisses = false;         // misses are rows of the fit and get the fit's value
        bool unroundedCount = true;     // phase I weight from the interpolated count
        bool clampBlockMax = false;     // fitted values clamped to the block's max (else >= 0)
    };
    Choices choices() const;

private:
    void readTimings();

    // Parameters.
    std::string mFeatures{};
    std::string mVariant{};
    std::string mOffsetTable{}, mScaling{}, mEdges{}, mMisses{}, mCount{}, mClamp{};
    float mEpsilon{};
    float mAlpha1{};
    float mAlpha3{};
    float mPositionThreshold{};
    float mNormalThreshold{};
    bool mOffsets{};
    float mDropTolerance{};
    bool mTimings{};
    bool mFp16History{};

    // State.
    int mBlocksX = 0, mBlocksY = 0;
    bool mUseMotion = false, mUseAlbedo = false, mUseEmission = false, mUseVp = false;
    Choices mChoices;
    std::unique_ptr<gpu::ComputePipeline> mAccumulate, mFit, mWeightedSum, mSecond;
    std::unique_ptr<gpu::TimestampPool> mTimestamps;
    bool mTimingsPending = false;
    std::array<double, 4> mKernelMs{-1.0, -1.0, -1.0, -1.0};
};

}  // namespace fovea::passes
