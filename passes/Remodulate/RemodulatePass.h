// Remodulate: undoes PathTrace's albedo demodulation after a denoiser (seed 000 §3.4 filters the
// demodulated signal; P2 §3 remodulates after BMFR). Same albedo rule as PathTrace.
#pragma once
#include "core/graph/Pass.h"

namespace fovea::passes {

class RemodulatePass : public graph::Pass {
public:
    void params(graph::ParamVisitor& v) override;
    void reflect(graph::Reflection& r) const override;
    void compile(graph::CompileContext& ctx) override;
    void execute(graph::ExecuteContext& ctx) override;
    bool cacheable() const override { return true; }

private:
    float mAlbedoEpsilon{};
    std::unique_ptr<gpu::ComputePipeline> mPipeline;
};

}  // namespace fovea::passes
