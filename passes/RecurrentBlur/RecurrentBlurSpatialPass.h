// RecurrentBlurSpatial: ReBLUR's second stage (seed 004; see RecurrentBlurStage.h for the chain):
// the blur whose radius shrinks with the frame count N, the post-blur whose output is the
// recurrent `history`, and temporal stabilization of luminance with antilag.
#pragma once
#include "passes/RecurrentBlur/RecurrentBlurStage.h"

namespace fovea::passes {

class RecurrentBlurSpatialPass : public RecurrentBlurStage {
public:
    RecurrentBlurSpatialPass() : RecurrentBlurStage("spatial") {}
    void params(graph::ParamVisitor& v) override;
    void reflect(graph::Reflection& r) const override;
    void validate(const graph::ValidateContext& ctx) const override { sharedValidate(ctx); }
    void compile(graph::CompileContext& ctx) override;
    void execute(graph::ExecuteContext& ctx) override;

private:
    int mHistoryFixFrames{};
    int mMaxStabilizedFrames{};
    bool mAntilag{};
    float mAntilagSigmaScale{};
    float mAntilagSensitivity{};
    std::unique_ptr<gpu::ComputePipeline> mStabilize;
};

}  // namespace fovea::passes
