// VisualPolarWarp: the Visual-Polar space of seed 003 P5 §3.2 for the frame's camera and gaze:
// per (rho, phi) texel the screen position of its primary ray and whether it is traced (the
// triangular fovea clip or P5 §3.3's staircase, off-screen samples), plus the `vp` parameter block
// every Visual-Polar consumer reads (shaders/common/visual_polar.glsl). GBuffer traces the `coords`
// grid (coherent primary rays, no compaction); Unwarp maps back to the screen.
// docs/passes/VisualPolarWarp.md.
#pragma once
#include "core/graph/Pass.h"

namespace fovea::passes {

class VisualPolarWarpPass : public graph::Pass {
public:
    void params(graph::ParamVisitor& v) override;
    void reflect(graph::Reflection& r) const override;
    // Depends on the camera (gaze, size, eyes), never on the geometry.
    bool usesCamera() const override { return true; }
    void validate(const graph::ValidateContext& ctx) const override;
    void compile(graph::CompileContext& ctx) override;
    void execute(graph::ExecuteContext& ctx) override;
    // Recomputed only when the camera (gaze), the size or a parameter changes; the staircase
    // moves every frame.
    bool cacheable() const override { return !mStaircase; }

private:
    float mReduction{};
    float mFoveaFraction{};
    bool mTraceOffscreen{};
    bool mStaircase{};
    std::unique_ptr<gpu::ComputePipeline> mPipeline;
};

}  // namespace fovea::passes
