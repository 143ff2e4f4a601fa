// Shared inputs of the ATrousNH GPU tests (ATrousNHTests, ATrousTileTests): the Feed registry that
// declares the denoiser's inputs, and a synthetic G-buffer with concentric foveation layers per eye
// (FoveationMask's mask word: bit 0 sampled, bits 1-2 layer, bits 16-31 spp), random colours on the
// sampled pixels, unit normals from three planes and positions with jumps, so that every weight of
// the filter matters.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "core/graph/PassRegistry.h"
#include "passes/ATrousNH/ATrousNHPass.h"
#include "tests/passes/FeedPass.h"

namespace fovea::test {

// Feed (tests/passes/FeedPass.h) -> ATrousNH; normals in GBuffer's format (fp16).
inline const graph::PassRegistry& atrousFeedRegistry() {
    static graph::PassRegistry r = feedRegistry<passes::ATrousNHPass>(
        "ATrousNH", {{"color", vk::Format::eR32G32B32A32Sfloat},
                     {"normal", vk::Format::eR16G16B16A16Sfloat},
                     {"position", vk::Format::eR32G32B32A32Sfloat},
                     {"mask", vk::Format::eR32Uint}});
    return r;
}

struct ATrousInputs {
    int width = 0, height = 0;
    std::vector<float> color, normal, position;
    std::vector<uint32_t> mask;
};

// Where the layers lie in each eye: centre as fractions of the eye width / image height, radii as
// fractions of the height; the middle and outer layers are sampled with these probabilities (the
// fovea always).
struct ATrousLayerShape {
    float centreX = 0.5f, centreY = 0.5f;
    float r0 = 0.2f, r1 = 0.4f;
    float pMiddle = 1.0f, pOuter = 1.0f;
};

inline ATrousInputs layeredATrousInputs(int width, int height, int eyes, const ATrousLayerShape& s,
                                        uint32_t seed) {
    ATrousInputs in;
    in.width = width;
    in.height = height;
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    const size_t n = size_t(width) * height;
    in.color.resize(n * 4);
    in.normal.resize(n * 4);
    in.position.resize(n * 4);
    in.mask.resize(n);
    const int eyeWidth = width / eyes;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const size_t i = size_t(y) * width + x;
            const int eye = std::min(x / eyeWidth, eyes - 1);
            const float cx = eye * eyeWidth + s.centreX * eyeWidth, cy = s.centreY * height;
            const float r = std::hypot(x + 0.5f - cx, y + 0.5f - cy) / float(height);
            const uint32_t layer = r < s.r0 ? 0u : (r < s.r1 ? 1u : 2u);
            const float p = layer == 0 ? 1.0f : (layer == 1 ? s.pMiddle : s.pOuter);
            const bool sampled = u(rng) < p;
            in.mask[i] = (layer << 1) | (sampled ? (1u | (2u << 16)) : 0u);
            for (int c = 0; c < 3; ++c) in.color[i * 4 + c] = sampled ? 2.0f * u(rng) : 0.0f;
            in.color[i * 4 + 3] = sampled ? 2.0f : 0.0f;
            const int plane = (x / 7 + y / 5) % 3;
            for (int c = 0; c < 3; ++c) in.normal[i * 4 + c] = plane == c ? 1.0f : 0.0f;
            in.normal[i * 4 + 3] = 1.0f;
            in.position[i * 4 + 0] = 0.05f * x + (plane == 1 ? 1.0f : 0.0f);
            in.position[i * 4 + 1] = 0.05f * y;
            in.position[i * 4 + 2] = 0.3f * u(rng);
            in.position[i * 4 + 3] = 1.0f;
        }
    return in;
}

}  // namespace fovea::test
