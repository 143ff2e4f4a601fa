// Unwarp: a Visual-Polar image back to the screen (seed 003 P5 §3.4-3.5). phi-only mipmaps,
// backward mapping of every screen pixel (wrap on phi, clamp on rho, trilinear across the phi
// mips), then the two-pass separable foveated Gaussian blur (sigma 0 in the fovea, linear to
// blurSigma at blurDegrees). docs/passes/Unwarp.md.
#pragma once
#include "core/graph/Pass.h"

namespace fovea::passes {

class UnwarpPass : public graph::Pass {
public:
    void params(graph::ParamVisitor& v) override;
    void reflect(graph::Reflection& r) const override;
    // The blur's eccentricity in degrees comes from the camera's field of view.
    bool usesCamera() const override { return true; }
    void compile(graph::CompileContext& ctx) override;
    void execute(graph::ExecuteContext& ctx) override;
    void onReset() override;

private:
    int mLevels{};
    bool mBlur{};
    float mBlurSigma{};
    float mBlurDegrees{};
    bool mCache{};
    bool mKeyStored = false;  // lookup_key holds the key of the last rebuild
    std::unique_ptr<gpu::ComputePipeline> mMips, mLookup, mMap, mMapFine, mBlurRows, mBlurColumns;
};

}  // namespace fovea::passes
