// SampleList: produces a sample layout (docs/sample-layouts.md) from a simple pattern - all
// pixels, a checkerboard, every n-th pixel, or a seeded random fraction - with a fixed sample
// count per entry. A stand-in for seed 000's foveated coordinates buffer (§3.2) in tests and
// demos; deterministic for a given seed (and frame, when animated).
#pragma once
#include "core/graph/Pass.h"
#include "core/sampling/SampleLayout.h"

namespace fovea::passes {

class SampleListPass : public graph::Pass {
public:
    void params(graph::ParamVisitor& v) override;
    void reflect(graph::Reflection& r) const override;
    void validate(const graph::ValidateContext& ctx) const override;
    void compile(graph::CompileContext& ctx) override;
    void execute(graph::ExecuteContext& ctx) override;
    // Everything it writes follows from the parameters, the graph seed (in the cache key) and the
    // size; only an animated random pattern also depends on the frame index.
    bool cacheable() const override { return !(mPattern == "random" && mAnimate); }

    // The options the shader runs with (also what tests rebuild on the CPU).
    sampling::SamplePatternOptions options(const graph::FrameInfo& frame) const;

private:
    std::string mPattern;
    int mN{};
    float mFraction{};
    int mSeed{};
    bool mAnimate{};
    int mSpp{};
    std::unique_ptr<gpu::ComputePipeline> mPipeline;
};

}  // namespace fovea::passes
