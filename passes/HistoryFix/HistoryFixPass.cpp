#include "passes/HistoryFix/HistoryFixPass.h"

#include <algorithm>
#include <cmath>
#include <glm/trigonometric.hpp>

#include "core/scene/Camera.h"
#include "core/vk/ComputePipeline.h"

namespace fovea::passes {

namespace {
constexpr int kLevels = 4;  // seed 004: "mips 1..4"
}

void HistoryFixPass::params(graph::ParamVisitor& v) {
    v.add("historyFixFrames", mFixFrames, 3,
          "pixels with N < this are rebuilt, the others pass bit-exactly (NRD 3; the talk's "
          "code uses 4); 0 = pass everything through",
          {0, 8});
    v.add("method", mMethod, "mips",
          "mips = the talk's mip pyramid, level ceil(4(1 - N/historyFixFrames)) -> 4, 3, 2 with a "
          "depth-aware upsample; stride = NRD's strided 5x5 (stride floor(basePixelStride/(2+N)))",
          {"mips", "stride"});
    v.add("countOffset", mCountOffset, 0.0f,
          "N = (count or color).a - countOffset: 0 for RecurrentBlur (a = N), 1 for BMFR's "
          "accumulated "
          "(a = samples = N + 1)",
          {0.0, 16.0});
    v.add("basePixelStride", mBasePixelStride, 14.0f, "stride method: px at N = -2 (NRD 14)",
          {1.0, 64.0});
    v.add("depthSensitivity", mDepthSensitivity, 0.05f,
          "relative view-depth difference at which a coarse sample's weight reaches 0 (ours: the "
          "talk names UPSAMPLING_VIEWZ_SENSITIVITY without a value)",
          {1e-4, 10.0});
    v.add("referenceHeight", mReferenceHeight, 1080.0f,
          "image rows at which the talk's levels (4, 3, 2) and NRD's stride hold; at H rows the "
          "level is shifted by round(log2(H / referenceHeight)) (a level <= 0 leaves the pixel "
          "to the spatial blur) and the stride scaled by H / referenceHeight, so a rebuilt pixel "
          "covers the same fraction of the view at any size (seed 004's figures are 720p-1440p). "
          "0 = no scaling (pixel values as given)",
          {0.0, 16384.0});
    v.add("normalAngle", mNormalAngle, 10.0f,
          "with `normal` connected: a coarse texel's weight is saturate((n . n_L - cos a) / "
          "(1 - cos a)) with n_L its mean normal, not renormalized, so a texel that points away "
          "by more than this angle or mixes two faces (|n_L| < 1) is not used; a stride tap is "
          "tested with its own normal (ours; the talk's upsample is depth-aware only, which "
          "averages across a box's edge where both faces have the same depth). 10 deg: under a "
          "sun n.L changes by up to 17 % at 10 deg but 50 % at 30 deg, and 30 deg averaged "
          "normal-mapped shading away (FlightHelmet, issue 13); flat faces are unaffected",
          {1.0, 180.0});
    v.add("clampToNeighbours", mClampToNeighbours, true,
          "the rebuilt value is clamped to the min/max of the pixel's 3x3 neighbours with a "
          "surface (in the averaged space): where the few-frame input is already clean (a delta "
          "sun on a normal-mapped textured surface) the rebuild keeps its detail, where it is "
          "noisy the range is wide and the rebuild passes (ours, issue 13; the talk has no clamp)");
    v.add("eyes", mEyes, 0,
          "side-by-side eyes (nothing crosses the seam); 0 = the frame camera's eye count", {0, 2});
}

void HistoryFixPass::reflect(graph::Reflection& r) const {
    const auto rgba32 = vk::Format::eR32G32B32A32Sfloat;
    r.input("color").floatOnly().doc(
        "accumulated colour, a = frame count (see countOffset); NaN/Inf leave as 0");
    r.input("depth").floatOnly().sameAs("color").doc("GBuffer linear view depth; 0 = sky");
    r.input("count").optional().floatOnly().sameAs("color").doc(
        "optional: its alpha is the frame count instead of color.a (e.g. BMFR's accumulated "
        "next to its filtered colour)");
    r.input("albedo").optional().floatOnly().sameAs("color").doc(
        "optional: colour is remodulated (c = y * albedo' + emission, e.g. BMFR's filtered): the "
        "rebuild averages y = (c - emission) / albedo' and multiplies back by the pixel's own "
        "albedo' (albedo' = albedo > 1e-3 ? albedo : 1, as Remodulate)");
    r.input("emission")
        .optional()
        .floatOnly()
        .sameAs("color")
        .doc(
            "optional: emission added to the colour after demodulation (GBuffer's emission): "
            "subtracted before the rebuild and added back, so an emitter never bleeds into its "
            "coplanar surroundings");
    r.input("normal").optional().floatOnly().sameAs("color").doc(
        "optional: GBuffer's shading normal; coarse texels and taps are weighted by the angle to "
        "it (normalAngle)");
    r.input("roughness")
        .optional()
        .floatOnly()
        .sameAs("color")
        .doc(
            "optional, specular signals: GBuffer roughness_metallic; the mips level is multiplied "
            "by the pixel's linear roughness (seed 004: mip level = F(frames, roughness)), so a "
            "mirror is not rebuilt from coarse data");
    r.output("result", rgba32)
        .sameAs("color")
        .doc("colour with few-frame pixels rebuilt; a = color.a");
    // Level 1 at full size: with two eyes of odd width the per-eye blocks need ceil(W/2) + 1
    // columns; levels 2-4 fit into half the size.
    r.internal("mip1", rgba32).sameAs("color").doc("level 1: 2x2 means per eye, a = mean depth");
    for (int l = 2; l <= kLevels; ++l)
        r.internal("mip" + std::to_string(l), rgba32)
            .scaled(0.5f)
            .doc("level " + std::to_string(l) + ": 2^L blocks per eye, a = mean depth");
    const auto rgba16 = vk::Format::eR16G16B16A16Sfloat;
    r.internal("nmip1", rgba16).sameAs("color").doc("level 1 mean normals (normal connected)");
    for (int l = 2; l <= kLevels; ++l)
        r.internal("nmip" + std::to_string(l), rgba16)
            .scaled(0.5f)
            .doc("level " + std::to_string(l) + " mean normals (normal connected)");
}

void HistoryFixPass::compile(graph::CompileContext& ctx) {
    mMipFirst = ctx.createPipeline("history_fix/mip_first.comp");
    mMipDown = ctx.createPipeline("history_fix/mip_down.comp", {}, {"src", "dst", "nsrc", "ndst"});
    // historyFixFrames = 0: a copy-only variant (see fix.comp, HF_PASS_THROUGH).
    mFix = ctx.createPipeline("history_fix/fix.comp",
                              {{"HF_PASS_THROUGH", mFixFrames == 0 ? "1" : "0"}});
}

void HistoryFixPass::execute(graph::ExecuteContext& ctx) {
    const auto& out = ctx.image("result");
    const int width = int(out.width()), height = int(out.height());
    const auto [eyes, eyeWidth] = scene::splitEyes(out.width(), mEyes, ctx.camera().eyeCount);
    const int widest = std::max(eyeWidth, width - (eyes - 1) * eyeWidth);
    glm::ivec4 blocks, rows;
    for (int l = 1; l <= kLevels; ++l) {
        const int s = 1 << l;
        blocks[l - 1] = (widest + s - 1) / s;
        rows[l - 1] = (height + s - 1) / s;
    }

    // Resolution scale (referenceHeight): the talk's 16-px level-4 blocks are 1.5 % of 1080 rows
    // but 11 % of 144; at 144 rows every pixel of a cut took 16-px blocks and the RMSE rose
    // (issue 13). scale = 1 and no shift without a reference height.
    const float scale = mReferenceHeight > 0.0f ? float(height) / mReferenceHeight : 1.0f;
    const int levelShift = int(std::lround(std::log2(scale)));

    const int useAlbedo = int(ctx.connected("albedo"));
    const int useEmission = int(ctx.connected("emission"));
    const int useNormal = int(ctx.connected("normal"));
    // historyFixFrames = 0 rebuilds nothing: the pyramid is not built and only the copy runs
    // (it cost ReBLUR 8.5 ms of lavapipe time at 256x256 for nothing, issue 13).
    if (mMethod == "mips" && mFixFrames > 0) {
        ctx.bindFields(*mMipFirst);
        mMipFirst->set("size", glm::ivec2(width, height))
            .set("eyeWidth", eyeWidth)
            .set("eyes", eyes)
            .set("blocks", blocks[0])
            .set("height", rows[0])
            .set("useAlbedo", useAlbedo)
            .set("useEmission", useEmission)
            .set("useNormal", useNormal);
        ctx.dispatch(*mMipFirst, uint32_t(blocks[0] * eyes), uint32_t(rows[0]));
        for (int l = 2; l <= kLevels; ++l) {
            mMipDown->bind("src", ctx.image("mip" + std::to_string(l - 1)))
                .bind("dst", ctx.image("mip" + std::to_string(l)))
                .bind("nsrc", ctx.image("nmip" + std::to_string(l - 1)))
                .bind("ndst", ctx.image("nmip" + std::to_string(l)));
            mMipDown->set("eyes", eyes)
                .set("blocks", blocks[l - 1])
                .set("height", rows[l - 1])
                .set("srcBlocks", blocks[l - 2])
                .set("srcHeight", rows[l - 2])
                .set("useNormal", useNormal);
            ctx.dispatch(*mMipDown, uint32_t(blocks[l - 1] * eyes), uint32_t(rows[l - 1]));
        }
    }
    ctx.bindFields(*mFix);
    mFix->set("size", glm::ivec2(width, height))
        .set("eyeWidth", eyeWidth)
        .set("eyes", eyes)
        .set("blocks", blocks)
        .set("heights", rows)
        .set("fixFrames", float(mFixFrames))
        .set("countOffset", mCountOffset)
        .set("method", int(mMethod == "stride"))
        .set("baseStride", mBasePixelStride * scale)
        .set("levelShift", levelShift)
        .set("depthSensitivity", mDepthSensitivity)
        .set("useCount", int(ctx.connected("count")))
        .set("useAlbedo", useAlbedo)
        .set("useEmission", useEmission)
        .set("useNormal", useNormal)
        .set("cosNormal", std::cos(glm::radians(mNormalAngle)))
        .set("clampToNeighbours", int(mClampToNeighbours))
        .set("useRoughness", int(ctx.connected("roughness")));
    ctx.dispatch(*mFix, out.width(), out.height());
}

}  // namespace fovea::passes
