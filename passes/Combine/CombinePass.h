// Combine: weighted sum of two images (b optional; an invalid history counts as absent). With
// weights (1, -1) and `absolute` it is an error image; with a delayed b it reads the past frame.
#pragma once
#include "core/graph/Pass.h"

namespace fovea::passes {

class CombinePass : public graph::Pass {
public:
    void params(graph::ParamVisitor& v) override;
    void reflect(graph::Reflection& r) const override;
    void compile(graph::CompileContext& ctx) override;
    void execute(graph::ExecuteContext& ctx) override;

private:
    float mWeightA{}, mWeightB{};
    bool mAbsolute{};
    std::unique_ptr<gpu::ComputePipeline> mPipeline;
};

}  // namespace fovea::passes
