// The explicit list of built-in pass types (ARCHITECTURE "Pass contract"). Adding a pass = one
// line here + passes/<Name>/ + shaders/<name>/ + docs/passes/<Name>.md.
#include "passes/RegisterPasses.h"

#include "core/graph/PassRegistry.h"
#include "passes/ATrousNH/ATrousNHPass.h"
#include "passes/Accumulate/AccumulatePass.h"
#include "passes/BMFR/BMFRPass.h"
#include "passes/Blit/BlitPass.h"
#include "passes/Combine/CombinePass.h"
#include "passes/FoveationMask/FoveationMaskPass.h"
#include "passes/GBuffer/GBufferPass.h"
#include "passes/HistoryFix/HistoryFixPass.h"
#include "passes/HmdPreview/HmdPreviewPass.h"
#include "passes/ImageFile/ImageFilePass.h"
#include "passes/ImageSource/ImageSourcePass.h"
#include "passes/PathTrace/PathTracePass.h"
#include "passes/PreviewSamples/PreviewSamplesPass.h"
#include "passes/RecurrentBlur/RecurrentBlurSpatialPass.h"
#include "passes/RecurrentBlur/RecurrentBlurTemporalPass.h"
#include "passes/Remodulate/RemodulatePass.h"
#include "passes/SVGF/SVGFPass.h"
#include "passes/SampleList/SampleListPass.h"
#include "passes/TAA/TAAPass.h"
#include "passes/Tonemap/TonemapPass.h"
#include "passes/Unwarp/UnwarpPass.h"
#include "passes/VisualPolarWarp/VisualPolarWarpPass.h"

namespace fovea {

namespace {
template <class T>
graph::PassTypeInfo info(const char* type, const char* doc) {
    return {type, doc, [] { return std::make_unique<T>(); }};
}
}  // namespace

void registerBuiltinPasses() {
    auto& r = graph::passRegistry();
    // Idempotent: the registry refuses a type twice, and tests call this once per fixture.
    if (r.find("ImageSource")) return;
    r.add(info<passes::ImageSourcePass>(
        "ImageSource", "Synthetic image: constant, gradient, seeded noise or the frame index."));
    r.add(info<passes::ImageFilePass>(
        "ImageFile", "Your own EXR/PNG image or numbered sequence (frame%04d.exr), by channel."));
    r.add(info<passes::TonemapPass>(
        "Tonemap", "Linear HDR to 8-bit display colour: exposure, clamp/Reinhard/ACES, sRGB."));
    r.add(info<passes::AccumulatePass>(
        "Accumulate",
        "Per-pixel running mean over frames, restarted on reset: converged references."));
    r.add(info<passes::CombinePass>(
        "Combine",
        "Weighted sum of two images (b optional, may be delayed): blends, differences."));
    r.add(info<passes::BlitPass>(
        "Blit", "Resample to a scaled size / other format; optional every-N-th-frame bypass."));
    r.add(info<passes::PathTracePass>(
        "PathTrace",
        "1 spp path tracing (P2 §3.1): primary hit, NEE, BRDF bounce(s) with NEE; MIS."));
    r.add(info<passes::GBufferPass>(
        "GBuffer",
        "Primary visibility by BVH ray casting, full grid or a sample layout, both eyes in one "
        "dispatch: visibility, position, normal, depth, albedo, motion (seed 000 §3.1)."));
    r.add(info<passes::FoveationMaskPass>(
        "FoveationMask",
        "Seed 000's 3-layer foveated distribution (§3.2, Table 1) around each eye's gaze: sample "
        "layout with per-layer spp + mask (B of Eq. 2, layer id)."));
    r.add(info<passes::ATrousNHPass>(
        "ATrousNH",
        "Edge-avoiding à-trous denoiser (Dammertz 2010) made non-homogeneous (seed 000 §3.4, "
        "Eq. 2, Alg. 1): sample mask, per-layer iterations, decreasing steps, stereo, no holes."));
    r.add(info<passes::RemodulatePass>(
        "Remodulate",
        "Undo albedo demodulation after a denoiser: color * albedo' + emission "
        "(PathTrace's rule)."));
    r.add(info<passes::SampleListPass>(
        "SampleList",
        "Sample layout from a pattern (all, checkerboard, every n-th, seeded random fraction) with "
        "a fixed spp per pixel: a stand-in for seed 000's coordinates buffer (§3.2)."));
    r.add(info<passes::PreviewSamplesPass>(
        "PreviewSamples",
        "A frame's sample budget on the 360° sphere (seed 003 P4): uniform (OD), viewport (VP) or "
        "visual acuity around the gaze (FV, Eq. 1-7), as an equirect sample layout."));
    r.add(info<passes::HmdPreviewPass>(
        "HmdPreview",
        "The HMD view of an accumulated equirect image, trilinear from its mips (seed 003 P4 "
        "§4: no flicker near the poles)."));
    r.add(info<passes::TAAPass>(
        "TAA", "Temporal AA (Karis 2014; P2 §3): reprojected history, YCoCg clip, blend."));
    r.add(info<passes::BMFRPass>(
        "BMFR",
        "Blockwise multi-order feature regression (seed 003 P2 §3): accumulation, 32x32 block "
        "QR fit of [1, n, w, w^2], second accumulation, remodulation; numerically guarded."));
    r.add(info<passes::RecurrentBlurTemporalPass>(
        "RecurrentBlurTemporal",
        "ReBLUR (seed 004) first stage, diffuse or specular signal: pre-blur + accumulation "
        "1/(1+N) with the firefly suppressor, on RecurrentBlurSpatial's history (delay 1)."));
    r.add(info<passes::RecurrentBlurSpatialPass>(
        "RecurrentBlurSpatial",
        "ReBLUR (seed 004) second stage: blur shrinking with N + post-blur (the recurrent "
        "history) + luminance stabilization with antilag."));
    r.retire("RecurrentBlur",
             "it was split into two types: \"stage\": \"temporal\" is now RecurrentBlurTemporal "
             "and \"stage\": \"spatial\" RecurrentBlurSpatial (drop the 'stage' parameter; "
             "docs/passes/RecurrentBlur.md)");
    r.add(info<passes::HistoryFixPass>(
        "HistoryFix",
        "Seed 004: rebuild pixels with few accumulated frames from a mip pyramid (or NRD's "
        "strided 5x5); the others pass bit-exactly. Follows any temporal accumulation."));
    r.add(info<passes::SVGFPass>(
        "SVGF",
        "Spatiotemporal variance-guided filtering (Schied et al. 2017): moments, "
        "variance, a-trous with edge stopping, remodulation."));
    r.add(info<passes::VisualPolarWarpPass>(
        "VisualPolarWarp",
        "Visual-Polar space (seed 003 P5 §3.2) per eye around its gaze: screen position of each "
        "(rho, phi) texel's primary ray, fovea clip, the mapping block; cached per gaze/size."));
    r.add(info<passes::UnwarpPass>(
        "Unwarp",
        "Visual-Polar image to the screen (P5 §3.4-3.5): phi-only mips, backward trilinear "
        "mapping (wrap phi, clamp rho), separable foveated Gaussian blur."));
}

}  // namespace fovea
