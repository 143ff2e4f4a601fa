// Accumulate: running per-pixel mean of its input over frames, restarted on reset/camera cut —
// used to build converged references. Optionally stops after `maxFrames` (then it is skipped and
// its persistent output keeps the converged mean).
#pragma once
#include "core/graph/Pass.h"

namespace fovea::passes {

class AccumulatePass : public graph::Pass {
public:
    void params(graph::ParamVisitor& v) override;
    void reflect(graph::Reflection& r) const override;
    void compile(graph::CompileContext& ctx) override;
    void execute(graph::ExecuteContext& ctx) override;
    bool isActive(const graph::FrameInfo&) const override;
    void onReset() override { mCount = 0; }

private:
    int mMaxFrames{};
    std::string mWeight;
    int mCount = 0;
    std::unique_ptr<gpu::ComputePipeline> mPipeline;
};

}  // namespace fovea::passes
