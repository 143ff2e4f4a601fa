// Tonemap: linear HDR -> 8-bit display colour (exposure in stops, clamp/Reinhard/ACES, sRGB).
#pragma once
#include "core/graph/Pass.h"

namespace fovea::passes {

class TonemapPass : public graph::Pass {
public:
    void params(graph::ParamVisitor& v) override;
    void reflect(graph::Reflection& r) const override;
    void compile(graph::CompileContext& ctx) override;
    void execute(graph::ExecuteContext& ctx) override;
    bool cacheable() const override { return true; }

private:
    float mExposure{};
    std::string mOperator;
    bool mSrgb{};
    std::unique_ptr<gpu::ComputePipeline> mPipeline;
};

}  // namespace fovea::passes
