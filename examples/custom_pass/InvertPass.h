// A pass written outside fovea's tree: result = 1 - color (RGB), alpha kept. The smallest
// complete pass: one parameter, one input, one output, one compute shader.
#pragma once
#include <memory>

#include "core/graph/Pass.h"
#include "core/vk/ComputePipeline.h"

class InvertPass : public fovea::graph::Pass {
public:
    void params(fovea::graph::ParamVisitor& v) override;
    void reflect(fovea::graph::Reflection& r) const override;
    void compile(fovea::graph::CompileContext& ctx) override;
    void execute(fovea::graph::ExecuteContext& ctx) override;

private:
    float mWhite = 1.0f;
    std::unique_ptr<fovea::gpu::ComputePipeline> mPipeline;
};
