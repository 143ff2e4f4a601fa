// HmdPreview: what the artist sees in seed 003 P3/P4's 360° preview - a perspective HMD view
// (per eye) of the progressively accumulated equirect image, filtered trilinearly from a mip
// chain of it (P4 §4: "trilinear filtering to eliminate flickering near the poles", where a
// screen pixel covers many equirect texels along the longitude).
#pragma once
#include "core/graph/Pass.h"

namespace fovea::passes {

class HmdPreviewPass : public graph::Pass {
public:
    void params(graph::ParamVisitor& v) override;
    void reflect(graph::Reflection& r) const override;
    void compile(graph::CompileContext& ctx) override;
    void execute(graph::ExecuteContext& ctx) override;
    bool usesCamera() const override { return mHead == "gaze"; }

    // Mip levels below level 0 for an equirect image of `height` rows: until a level is one row
    // (at most 12).
    static uint32_t mipLevels(uint32_t width, uint32_t height);

private:
    int mWidth{}, mHeight{};
    int mEyes{};
    float mFovDeg{};
    std::string mHead;
    std::string mFilter;
    std::unique_ptr<gpu::ComputePipeline> mMip, mView;
};

}  // namespace fovea::passes
