// RecurrentBlurTemporal: ReBLUR's first stage (seed 004; see RecurrentBlurStage.h for the chain):
// pre-blur, then temporal accumulation with weight 1/(1+N) and the firefly suppressor, reading the
// spatial stage's post-blurred `history` through a delay-1 edge.
#pragma once
#include <glm/vec3.hpp>

#include "passes/RecurrentBlur/RecurrentBlurStage.h"

namespace fovea::passes {

class RecurrentBlurTemporalPass : public RecurrentBlurStage {
public:
    RecurrentBlurTemporalPass() : RecurrentBlurStage("temporal") {}
    void params(graph::ParamVisitor& v) override;
    void reflect(graph::Reflection& r) const override;
    void validate(const graph::ValidateContext& ctx) const override { sharedValidate(ctx); }
    void compile(graph::CompileContext& ctx) override;
    void execute(graph::ExecuteContext& ctx) override;

private:
    float mPrepassBlurRadius{};
    float mDisocclusionThreshold{};
    float mDisocclusionNormal{};
    bool mHitNormalized{};
    bool mFireflySuppression{};
    float mSpecAccumBasePower{};
    float mSpecAccumCurve{};
    bool mVirtualMotion{};
    float mParallaxFrameRate{};
    std::unique_ptr<gpu::ComputePipeline> mTemporal;
    // Specular parallax: the eyes of the frame before (none after a compile).
    glm::vec3 mPreviousEyes[2] = {};
    bool mHavePreviousEyes = false;
};

}  // namespace fovea::passes
