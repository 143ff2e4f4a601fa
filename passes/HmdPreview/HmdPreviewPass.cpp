#include "passes/HmdPreview/HmdPreviewPass.h"

#include <algorithm>
#include <cmath>

#include "core/vk/ComputePipeline.h"
#include "core/vk/Resources.h"

namespace fovea::passes {

namespace {
const std::vector<std::string> kFilters = {"nearest", "bilinear", "trilinear"};
}  // namespace

uint32_t HmdPreviewPass::mipLevels(uint32_t width, uint32_t height) {
    uint32_t levels = 0;
    while (levels < 12 && (height >> (levels + 1)) >= 1 && (width >> (levels + 1)) >= 1) ++levels;
    return levels;
}

void HmdPreviewPass::params(graph::ParamVisitor& v) {
    v.add("width", mWidth, 640, "HMD image width per eye, pixels", {1, 8192});
    v.add("height", mHeight, 720, "HMD image height, pixels", {1, 8192});
    v.add("eyes", mEyes, 1,
          "1, or 2 side-by-side panels (360° mono content: both eyes see the same image)", {1, 2});
    v.add("fovDeg", mFovDeg, 100.0f,
          "vertical field of view in degrees (match PreviewSamples' fovDeg for the viewport "
          "method)",
          {1.0f, 179.0f});
    v.add("head", mHead, "forward",
          "where the HMD looks: forward = the camera's forward direction (the equirect image's "
          "centre), gaze = turned to the gaze (as PreviewSamples' head)",
          {"forward", "gaze"});
    v.add("filter", mFilter, "trilinear",
          "nearest texel, bilinear on level 0, or trilinear between the two mip levels of the "
          "pixel's footprint (P4 §4: against flicker near the poles)",
          kFilters);
}

void HmdPreviewPass::reflect(graph::Reflection& r) const {
    r.input("equirect")
        .floatOnly()
        .doc(
            "the 2:1 equirect image, any float or normalized format: Accumulate's mean (a = 0 "
            "where no sample landed, shown black: P4 does not reconstruct them) or its "
            "tone-mapped display colour");
    r.output("view", vk::Format::eR32G32B32A32Sfloat)
        .fixed(uint32_t(mWidth * mEyes), uint32_t(mHeight))
        .doc("the HMD view, eyes side by side; a = filtered coverage");
    r.internal("mips", vk::Format::eR32G32B32A32Sfloat)
        .sameAs("equirect")
        .doc(
            "mip levels 1.. of the equirect image side by side in the top half (box 2x2, the "
            "longitude wrapping)");
}

void HmdPreviewPass::compile(graph::CompileContext& ctx) {
    mMip = ctx.createPipeline("hmd_preview/mip.comp");
    mView = ctx.createPipeline("hmd_preview/view.comp");
}

void HmdPreviewPass::execute(graph::ExecuteContext& ctx) {
    const auto& src = ctx.image("equirect");
    const glm::ivec2 size(int(src.width()), int(src.height()));
    const bool trilinear = mFilter == "trilinear";
    const uint32_t levels = trilinear ? mipLevels(src.width(), src.height()) : 0;
    // Level l >= 1 sits at x = the widths of levels 1..l-1 (< width in all), y = 0.
    int offset = 0;
    for (uint32_t l = 1; l <= levels; ++l) {
        const glm::ivec2 dst(std::max(size.x >> l, 1), std::max(size.y >> l, 1));
        const glm::ivec2 from(std::max(size.x >> (l - 1), 1), std::max(size.y >> (l - 1), 1));
        const int fromOffset = l == 1 ? 0 : offset - from.x;
        ctx.bindFields(*mMip);
        mMip->set("dstSize", dst)
            .set("srcSize", from)
            .set("dstOffset", offset)
            .set("srcOffset", fromOffset)
            .set("fromInput", int(l == 1));
        ctx.dispatch(*mMip, uint32_t(dst.x), uint32_t(dst.y));
        offset += dst.x;
    }
    const auto& out = ctx.image("view");
    ctx.bindFields(*mView);
    mView->set("size", glm::ivec2(out.width(), out.height()))
        .set("eyeWidth", mWidth)
        .set("srcSize", size)
        .set("levels", int(levels))
        .set("filterMode",
             int(std::find(kFilters.begin(), kFilters.end(), mFilter) - kFilters.begin()))
        .set("headFollowsGaze", int(mHead == "gaze"))
        .set("tanHalfFov", std::tan(0.5f * glm::radians(mFovDeg)))
        .set("aspect", float(mWidth) / float(mHeight));
    ctx.dispatch(*mView, out.width(), out.height());
}

}  // namespace fovea::passes
