// GBuffer: primary visibility by ray casting in compute over the scene BVH, for the full grid or
// the pixels of a sample layout, both eyes of a stereo image in one dispatch (seed 000 §3.1,
// §4.1). Outputs the visibility buffer (triangle + barycentrics) and the usual G-buffer
// channels; encodings in docs/passes/GBuffer.md.
#pragma once
#include "core/graph/Pass.h"
#include "core/sampling/SampleLayout.h"

namespace fovea::passes {

class GBufferPass : public graph::Pass {
public:
    void params(graph::ParamVisitor& v) override;
    void reflect(graph::Reflection& r) const override;
    uint32_t sceneNeeds() const override { return graph::kSceneGeometry; }
    void validate(const graph::ValidateContext& ctx) const override;
    void compile(graph::CompileContext& ctx) override;
    void execute(graph::ExecuteContext& ctx) override;
    // Outputs depend only on the scene, the camera (both in the graph's cache key for a pass
    // with scene needs: jitter and previous matrices included), the layout input and the
    // parameters - and on the frame index when the scene has BLEND materials (stochastic
    // transparency draws a new layer every frame: a cached one would never converge).
    bool cacheable() const override { return !mStochastic; }
    // The scene features the shader was compiled with, e.g. "emissive,no-punctual,no-textures".
    std::string variant() const override { return mVariant; }

private:
    bool mJitter{};
    bool mStochastic = false;  // the scene has BLEND materials (SceneGpu::hasStochasticAlpha)
    std::string mVariant;
    std::unique_ptr<gpu::ComputePipeline> mPipeline;
};

}  // namespace fovea::passes
