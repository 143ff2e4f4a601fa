// PreviewSamples: where a progressive 360° render spends this frame's samples (seed 003 P3/P4,
// "Foveated instant preview"). Draws a fixed per-frame budget of sample directions on the sphere
// - OD uniformly over the equirect image, VP uniformly over the HMD viewport, FV by the visual
// acuity around the gaze (P4 Eq. 1-7) - bins them into the equirect image's texels and writes the
// texels that got any as a sample layout (pixel + count), for PathTrace. Accumulate with
// weight = alpha then sums them progressively.
#pragma once
#include "core/graph/Pass.h"

namespace fovea::passes {

class PreviewSamplesPass : public graph::Pass {
public:
    void params(graph::ParamVisitor& v) override;
    void reflect(graph::Reflection& r) const override;
    void validate(const graph::ValidateContext& ctx) const override;
    void compile(graph::CompileContext& ctx) override;
    void execute(graph::ExecuteContext& ctx) override;
    // The gaze (and, for VP, the head) comes from the frame camera.
    bool usesCamera() const override { return true; }

private:
    std::string mMethod;
    int mBudget{};
    std::string mInverse;
    std::string mHead;
    float mFovDeg{};
    float mAspect{};
    int mSeed{};
    std::unique_ptr<gpu::ComputePipeline> mClear, mGenerate, mCompact;
};

}  // namespace fovea::passes
