// ImageSource: a synthetic image (constant, gradient, seeded noise, or the frame index) — the
// input of utility graphs and tests. Cacheable unless the pattern depends on the frame.
#pragma once
#include "core/graph/Pass.h"

namespace fovea::passes {

class ImageSourcePass : public graph::Pass {
public:
    void params(graph::ParamVisitor& v) override;
    void reflect(graph::Reflection& r) const override;
    void compile(graph::CompileContext& ctx) override;
    void execute(graph::ExecuteContext& ctx) override;
    bool cacheable() const override { return mPattern != "frame-index" && !mAnimate; }

private:
    std::string mPattern;
    glm::vec3 mValue{};
    int mSeed{};
    bool mAnimate{};
    std::unique_ptr<gpu::ComputePipeline> mPipeline;
};

}  // namespace fovea::passes
