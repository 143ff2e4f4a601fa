#include "editor/PreviewImage.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace fovea::editor {

namespace {

// Stops of a blue-cyan-green-yellow-red ramp (perceptually ordered by hue, readable in print).
constexpr std::array<std::array<float, 3>, 5> kRamp{{{0.05f, 0.05f, 0.55f},
                                                     {0.0f, 0.75f, 0.95f},
                                                     {0.15f, 0.85f, 0.2f},
                                                     {0.98f, 0.9f, 0.1f},
                                                     {0.85f, 0.1f, 0.05f}}};

std::array<float, 3> ramp(float t) {
    t = std::clamp(t, 0.0f, 1.0f) * float(kRamp.size() - 1);
    const size_t i = std::min(size_t(t), kRamp.size() - 2);
    const float f = t - float(i);
    std::array<float, 3> c;
    for (int k = 0; k < 3; ++k)
        c[size_t(k)] = kRamp[i][size_t(k)] * (1 - f) + kRamp[i + 1][size_t(k)] * f;
    return c;
}

float luminance(const float* p) {
    return 0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2];  // Rec. 709
}

float scalarOf(const float* p, PreviewChannel channel) {
    switch (channel) {
        case PreviewChannel::R:
            return p[0];
        case PreviewChannel::G:
            return p[1];
        case PreviewChannel::B:
            return p[2];
        case PreviewChannel::A:
            return p[3];
        default:
            return luminance(p);
    }
}

uint8_t encode(float v, bool srgb) {
    v = std::clamp(std::isfinite(v) ? v : 0.0f, 0.0f, 1.0f);
    if (srgb) v = v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
    return uint8_t(std::lround(v * 255.0f));
}

}  // namespace

const char* previewChannelName(PreviewChannel c) {
    constexpr const char* kNames[] = {"rgb", "r", "g", "b", "a", "luminance"};
    return kNames[int(c)];
}

std::optional<PreviewChannel> parsePreviewChannel(const std::string& name) {
    for (int c = 0; c <= int(PreviewChannel::Luminance); ++c)
        if (name == previewChannelName(PreviewChannel(c))) return PreviewChannel(c);
    return std::nullopt;
}

PreviewBlit makePreview(const image::ImageRGBA& src, int x, int y, uint32_t width, uint32_t height,
                        const PreviewSettings& s, bool bgra, PreviewFit* fitOut) {
    PreviewBlit blit{x, y, width, height, std::vector<uint8_t>(size_t(width) * height * 4, 0)};
    PreviewFit fit;
    if (src.width == 0 || src.height == 0 || width == 0 || height == 0) return blit;
    fit.scale = std::min(float(width) / float(src.width), float(height) / float(src.height));
    fit.width = std::max(1u, uint32_t(float(src.width) * fit.scale));
    fit.height = std::max(1u, uint32_t(float(src.height) * fit.scale));
    fit.offsetX = int(width - fit.width) / 2;
    fit.offsetY = int(height - fit.height) / 2;
    fit.imageWidth = src.width;
    fit.imageHeight = src.height;

    const float gain = std::exp2(s.exposure);
    float lo = std::numeric_limits<float>::max(), hi = std::numeric_limits<float>::lowest();
    if (s.falseColour) {
        for (size_t p = 0; p < size_t(src.width) * src.height; ++p) {
            const float v = scalarOf(&src.pixels[p * 4], s.channel);
            if (!std::isfinite(v)) continue;
            lo = std::min(lo, v);
            hi = std::max(hi, v);
        }
    }
    const float span = hi > lo ? hi - lo : 1.0f;  // a constant image maps to the ramp's start
    const bool srgb = !s.displayEncoded;
    for (uint32_t ry = 0; ry < height; ++ry) {
        for (uint32_t rx = 0; rx < width; ++rx) {
            uint8_t* out = &blit.bytes[(size_t(ry) * width + rx) * 4];
            const int ix = int(std::floor(float(int(rx) - fit.offsetX) / fit.scale));
            const int iy = int(std::floor(float(int(ry) - fit.offsetY) / fit.scale));
            std::array<uint8_t, 3> rgb{24, 24, 28};  // letterbox
            if (int(rx) >= fit.offsetX && int(ry) >= fit.offsetY && ix >= 0 && iy >= 0 &&
                ix < int(src.width) && iy < int(src.height)) {
                const float* p = &src.pixels[(size_t(iy) * src.width + size_t(ix)) * 4];
                const bool finite = std::isfinite(p[0]) && std::isfinite(p[1]) &&
                                    std::isfinite(p[2]) && std::isfinite(p[3]);
                if (!finite) {
                    rgb = {255, 0, 255};
                } else if (s.falseColour) {
                    const auto c = ramp((scalarOf(p, s.channel) - lo) / span);
                    rgb = {encode(c[0], false), encode(c[1], false), encode(c[2], false)};
                } else if (s.channel == PreviewChannel::Rgb) {
                    rgb = {encode(p[0] * gain, srgb), encode(p[1] * gain, srgb),
                           encode(p[2] * gain, srgb)};
                } else {
                    const uint8_t v = encode(scalarOf(p, s.channel) * gain, srgb);
                    rgb = {v, v, v};
                }
            }
            out[0] = bgra ? rgb[2] : rgb[0];
            out[1] = rgb[1];
            out[2] = bgra ? rgb[0] : rgb[2];
            out[3] = 255;
        }
    }
    if (fitOut) *fitOut = fit;
    return blit;
}

std::optional<std::pair<uint32_t, uint32_t>> previewPixelAt(const PreviewBlit& blit,
                                                            const PreviewFit& fit, float px,
                                                            float py) {
    if (fit.width == 0 || fit.scale <= 0) return std::nullopt;  // scale > 0 guards the division
    const float lx = px - float(blit.x + fit.offsetX), ly = py - float(blit.y + fit.offsetY);
    if (lx < 0 || ly < 0 || lx >= float(fit.width) || ly >= float(fit.height)) return std::nullopt;
    return std::make_pair(std::min(uint32_t(lx / fit.scale), fit.imageWidth - 1),
                          std::min(uint32_t(ly / fit.scale), fit.imageHeight - 1));
}

}  // namespace fovea::editor
