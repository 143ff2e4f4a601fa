// HistoryFix (seed 004, the ReBLUR talk; specs §2 HistoryFix): after a temporal accumulation,
// pixels with few accumulated frames (just disoccluded, or after a cut) are rebuilt from coarser
// data: the talk's mip pyramid (levels 4, 3, 2 over the first frames, depth-aware upsample) or
// NRD's strided 5x5. Pixels with enough history pass bit-exactly. Takes any colour whose alpha
// is a frame count (RecurrentBlur's accumulated: N; BMFR's accumulated: samples = N + 1, set
// countOffset = 1), so it can follow any temporal accumulation; a remodulated colour (BMFR's
// filtered) is rebuilt demodulated when `albedo` / `emission` are connected, and with `normal`
// connected the rebuild does not cross creases of equal depth.
#pragma once
#include <string>

#include "core/graph/Pass.h"

namespace fovea::passes {

class HistoryFixPass : public graph::Pass {
public:
    void params(graph::ParamVisitor& v) override;
    void reflect(graph::Reflection& r) const override;
    void compile(graph::CompileContext& ctx) override;
    void execute(graph::ExecuteContext& ctx) override;
    std::string variant() const override { return mMethod; }

private:
    int mFixFrames{};
    std::string mMethod{};
    float mCountOffset{};
    float mBasePixelStride{};
    float mDepthSensitivity{};
    float mReferenceHeight{};
    float mNormalAngle{};
    bool mClampToNeighbours{};
    int mEyes{};
    std::unique_ptr<gpu::ComputePipeline> mMipFirst, mMipDown, mFix;
};

}  // namespace fovea::passes
