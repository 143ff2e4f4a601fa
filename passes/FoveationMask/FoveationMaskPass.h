// FoveationMask: seed 000's foveation distribution step (Peres et al. 2023, §3.2 and §4.1):
// three concentric layers around each eye's gaze point - the fovea (radius r0, every pixel),
// the middle ring (r0..r1, sampling probability falling linearly from 1 to the outer one, after
// Weier et al.) and the outer layer (constant probability) - written as a coordinate-list sample
// layout (docs/sample-layouts.md) with a per-layer spp (Table 1: 4 / 3 / 2) and as the binary
// mask B of Eq. 2 (with the layer id, for the non-homogeneous denoiser, §3.4).
#pragma once
#include "core/graph/Pass.h"
#include "core/sampling/SampleLayout.h"

namespace fovea::passes {

class FoveationMaskPass : public graph::Pass {
public:
    void params(graph::ParamVisitor& v) override;
    void reflect(graph::Reflection& r) const override;
    // Reads only the camera (gaze, size, FOV), never the geometry: the camera enters the cache
    // key, and the pass runs without a scene too.
    bool usesCamera() const override { return true; }
    void validate(const graph::ValidateContext& ctx) const override;
    void compile(graph::CompileContext& ctx) override;
    void execute(graph::ExecuteContext& ctx) override;
    // Seed 000 §3.2: the distribution "is constant for all frames"; only `animate` (a new random
    // toss every frame) makes the output depend on the frame index.
    bool cacheable() const override { return !mAnimate; }
    std::string variant() const override { return mRadiusUnit; }
    // The radii per-layer errors split by (eval/metrics/EccentricityBands.h).
    graph::PassFacts facts() const override {
        graph::PassFacts facts;
        facts.foveationLayers = graph::LayerRadii{mR0, mR1, mRadiusUnit == "degrees"};
        return facts;
    }

private:
    float mR0{}, mR1{};
    std::string mRadiusUnit;
    float mOuterProbability{};
    int mSppFovea{}, mSppMiddle{}, mSppOuter{};
    int mSeed{};
    bool mAnimate{};
    std::unique_ptr<gpu::ComputePipeline> mPipeline;
};

}  // namespace fovea::passes
