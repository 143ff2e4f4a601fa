// Blit: copies/resamples an image to a scaled size and another format. `activeEvery` N > 1
// runs it every N-th frame only and passes the input through (bypass) on the others.
#pragma once
#include "core/graph/Pass.h"

namespace fovea::passes {

class BlitPass : public graph::Pass {
public:
    void params(graph::ParamVisitor& v) override;
    void reflect(graph::Reflection& r) const override;
    void compile(graph::CompileContext& ctx) override;
    void execute(graph::ExecuteContext& ctx) override;
    bool isActive(const graph::FrameInfo& frame) const override;
    std::vector<std::pair<std::string, std::string>> bypass() const override;

private:
    float mScale{};
    std::string mFormat;
    std::string mFilter;
    int mActiveEvery{};
    std::unique_ptr<gpu::ComputePipeline> mPipeline;
};

}  // namespace fovea::passes
