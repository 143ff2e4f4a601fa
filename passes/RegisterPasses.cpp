// The explicit list of built-in pass types (ARCHITECTURE "Pass contract"). Adding a pass = one
// line here + passes/<Name>/ + shaders/<name>/ + docs/passes/<Name>.md.
#include "core/graph/PassRegistry.h"
#include "passes/Accumulate/AccumulatePass.h"
#include "passes/Blit/BlitPass.h"
#include "passes/Combine/CombinePass.h"
#include "passes/ImageSource/ImageSourcePass.h"
#include "passes/Tonemap/TonemapPass.h"

namespace fovea {

namespace {
template <class T>
graph::PassTypeInfo info(const char* type, const char* doc) {
    return {type, doc, [] { return std::make_unique<T>(); }};
}
}  // namespace

void registerBuiltinPasses() {
    auto& r = graph::passRegistry();
    r.add(info<passes::ImageSourcePass>(
        "ImageSource", "Synthetic image: constant, gradient, seeded noise or the frame index."));
    r.add(info<passes::TonemapPass>(
        "Tonemap", "Linear HDR to 8-bit display colour: exposure, clamp/Reinhard/ACES, sRGB."));
    r.add(info<passes::AccumulatePass>(
        "Accumulate",
        "Per-pixel running mean over frames, restarted on reset: converged references."));
    r.add(info<passes::CombinePass>(
        "Combine", "Weighted sum of two images (b optional, may be delayed): blends, differences."));
    r.add(info<passes::BlitPass>(
        "Blit", "Resample to a scaled size / other format; optional every-N-th-frame bypass."));
}

}  // namespace fovea
