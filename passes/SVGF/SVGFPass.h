// SVGF: Spatiotemporal Variance-Guided Filtering (Schied et al., HPG 2017; docs/references.md,
// docs/passes/SVGF.md). Temporal accumulation of the demodulated colour and of
// the luminance moments with per-tap disocclusion tests (§4.1), a variance estimate that falls
// back to a spatial one while the history is short (§4.2), `iterations` a-trous levels with
// variance-guided luminance, normal and depth-gradient edge stopping (§4.3-4.4), the output of
// level `feedbackTap` fed back as colour history, and remodulation by albedo (+ emission).
// Documentation: docs/passes/SVGF.md.
#pragma once
#include <memory>

#include "core/graph/Pass.h"

namespace fovea::passes {

class SVGFPass : public graph::Pass {
public:
    SVGFPass();
    ~SVGFPass() override;

    void params(graph::ParamVisitor& v) override;
    void reflect(graph::Reflection& r) const override;
    void validate(const graph::ValidateContext& ctx) const override;
    void compile(graph::CompileContext& ctx) override;
    void execute(graph::ExecuteContext& ctx) override;
    nlohmann::json statistics(const graph::StatisticsContext& ctx) const override;

private:
    // Parameters (declared and documented once, in params()).
    int mIterations{};
    int mFeedbackTap{};
    float mAlpha{};
    float mMomentsAlpha{};
    float mSigmaLuminance{};
    float mSigmaNormal{};
    float mSigmaDepth{};
    float mHistoryForVariance{};
    int mSpatialRadius{};
    float mMaxHistory{};
    float mPositionThreshold{};
    float mNormalThreshold{};

    // State.
    bool mUseMotion = false, mUseAlbedo = false, mUseEmission = false, mUseVp = false;
    std::unique_ptr<gpu::ComputePipeline> mReproject, mVariance, mATrous;
};

}  // namespace fovea::passes
