// TAA: temporal anti-aliasing after Karis 2014 (the last stage of seed 003's P2 pipeline, §3):
// motion-vector reprojection of its own previous result (a delay-1 edge into `history`), bilinear
// or Catmull-Rom history, 3x3 YCoCg neighbourhood clip (min/max box or Salvi's variance box),
// exponential blend with weight `alpha` for the current frame. Reset / camera cut / invalid
// history -> the current frame alone. Stereo: nothing is read across the eye seam.
#pragma once
#include <string>

#include "core/graph/Pass.h"

namespace fovea::passes {

class TAAPass : public graph::Pass {
public:
    void params(graph::ParamVisitor& v) override;
    void reflect(graph::Reflection& r) const override;
    void compile(graph::CompileContext& ctx) override;
    void execute(graph::ExecuteContext& ctx) override;
    std::string variant() const override { return mVariant; }

private:
    float mAlpha{};
    std::string mClip{};
    float mGamma{};
    std::string mHistoryFilter{};
    int mEyes{};
    bool mUseMotion = false, mUseVp = false;
    std::string mVariant;
    std::unique_ptr<gpu::ComputePipeline> mPipeline;
};

}  // namespace fovea::passes
