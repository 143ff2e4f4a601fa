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

namespace {

// The scalar range false colour maps onto the ramp: the image's finite min and max.
std::pair<float, float> finiteRange(const image::ImageRGBA& src, PreviewChannel channel) {
    float lo = std::numeric_limits<float>::max(), hi = std::numeric_limits<float>::lowest();
    for (size_t p = 0; p < size_t(src.width) * src.height; ++p) {
        const float v = scalarOf(&src.pixels[p * 4], channel);
        if (!std::isfinite(v)) continue;
        lo = std::min(lo, v);
        hi = std::max(hi, v);
    }
    return {lo, hi};
}

// One pixel as displayed, 0..255 RGB.
std::array<uint8_t, 3> displayPixel(const float* p, const PreviewSettings& s, float gain, float lo,
                                    float span) {
    const bool finite =
        std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]) && std::isfinite(p[3]);
    const bool srgb = !s.displayEncoded;
    if (!finite) return {255, 0, 255};
    if (s.falseColour) {
        const auto c = ramp((scalarOf(p, s.channel) - lo) / span);
        return {encode(c[0], false), encode(c[1], false), encode(c[2], false)};
    }
    if (s.channel == PreviewChannel::Rgb)
        return {encode(p[0] * gain, srgb), encode(p[1] * gain, srgb), encode(p[2] * gain, srgb)};
    const uint8_t v = encode(scalarOf(p, s.channel) * gain, srgb);
    return {v, v, v};
}

}  // namespace

PreviewBlit makePreview(const image::ImageRGBA& src, int x, int y, uint32_t width, uint32_t height,
                        const PreviewSettings& s, bool bgra, PreviewFit* fitOut) {
    PreviewBlit blit{x, y, width, height, std::vector<uint8_t>(size_t(width) * height * 4, 0)};
    drawPreviewPane(src, s, bgra, blit, 0, width, fitOut);
    return blit;
}

void drawPreviewPane(const image::ImageRGBA& src, const PreviewSettings& s, bool bgra,
                     PreviewBlit& blit, int paneX, uint32_t paneWidth, PreviewFit* fitOut) {
    PreviewFit fit;
    fit.paneX = paneX;
    fit.paneWidth = paneWidth;
    const uint32_t height = blit.height;
    if (fitOut) *fitOut = fit;
    if (paneWidth == 0 || height == 0 || paneX < 0 || uint32_t(paneX) + paneWidth > blit.width)
        return;
    const bool empty = src.width == 0 || src.height == 0;
    if (!empty) {
        const float zoom = std::clamp(s.view.zoom, kMinZoom, kMaxZoom);
        fit.scale =
            std::min(float(paneWidth) / float(src.width), float(height) / float(src.height)) * zoom;
        fit.width = std::max(1u, uint32_t(float(src.width) * fit.scale));
        fit.height = std::max(1u, uint32_t(float(src.height) * fit.scale));
        // Centred as before zooming existed ((pane - image) / 2), shifted by the pan.
        fit.offsetX = paneX + (int(paneWidth) - int(fit.width)) / 2 +
                      int(std::lround((0.5f - s.view.centerX) * float(fit.width)));
        fit.offsetY = (int(height) - int(fit.height)) / 2 +
                      int(std::lround((0.5f - s.view.centerY) * float(fit.height)));
        fit.imageWidth = src.width;
        fit.imageHeight = src.height;
    }
    const float gain = std::exp2(s.exposure);
    auto [lo, hi] = s.falseColour && !empty ? finiteRange(src, s.channel) : std::pair{0.0f, 1.0f};
    const float span = hi > lo ? hi - lo : 1.0f;  // a constant image maps to the ramp's start
    for (uint32_t ry = 0; ry < height; ++ry) {
        for (uint32_t rx = uint32_t(paneX); rx < uint32_t(paneX) + paneWidth; ++rx) {
            uint8_t* out = &blit.bytes[(size_t(ry) * blit.width + rx) * 4];
            std::array<uint8_t, 3> rgb{24, 24, 28};  // letterbox
            if (!empty) {
                // fit.scale > 0: the image and the pane are not empty.
                const int ix = int(std::floor(float(int(rx) - fit.offsetX) / fit.scale));
                const int iy = int(std::floor(float(int(ry) - fit.offsetY) / fit.scale));
                if (int(rx) >= fit.offsetX && int(ry) >= fit.offsetY && ix >= 0 && iy >= 0 &&
                    ix < int(src.width) && iy < int(src.height))
                    rgb = displayPixel(&src.pixels[(size_t(iy) * src.width + size_t(ix)) * 4], s,
                                       gain, lo, span);
            }
            out[0] = bgra ? rgb[2] : rgb[0];
            out[1] = rgb[1];
            out[2] = bgra ? rgb[0] : rgb[2];
            out[3] = 255;
        }
    }
    if (fitOut) *fitOut = fit;
}

std::optional<std::pair<uint32_t, uint32_t>> previewPixelAt(const PreviewBlit& blit,
                                                            const PreviewFit& fit, float px,
                                                            float py) {
    if (fit.width == 0 || fit.scale <= 0) return std::nullopt;  // scale > 0 guards the division
    const float bx = px - float(blit.x), by = py - float(blit.y);
    if (bx < float(fit.paneX) || bx >= float(fit.paneX) + float(fit.paneWidth) || by < 0 ||
        by >= float(blit.height))
        return std::nullopt;
    const float lx = bx - float(fit.offsetX), ly = by - float(fit.offsetY);
    if (lx < 0 || ly < 0) return std::nullopt;
    const uint32_t ix = uint32_t(lx / fit.scale), iy = uint32_t(ly / fit.scale);
    if (ix >= fit.imageWidth || iy >= fit.imageHeight) return std::nullopt;
    return std::make_pair(ix, iy);
}

std::array<int, 4> visibleImageRect(const PreviewBlit& blit, const PreviewFit& fit) {
    const int x0 = std::max(fit.paneX, fit.offsetX), y0 = std::max(0, fit.offsetY);
    const int x1 = std::min(fit.paneX + int(fit.paneWidth), fit.offsetX + int(fit.width));
    const int y1 = std::min(int(blit.height), fit.offsetY + int(fit.height));
    if (fit.width == 0 || x1 <= x0 || y1 <= y0) return {blit.x, blit.y, 0, 0};
    return {blit.x + x0, blit.y + y0, x1 - x0, y1 - y0};
}

image::ImageRGBA differenceImage(const image::ImageRGBA& a, const image::ImageRGBA& b) {
    if (a.width != b.width || a.height != b.height || a.pixels.size() != b.pixels.size()) return {};
    image::ImageRGBA d{a.width, a.height, std::vector<float>(a.pixels.size())};
    for (size_t i = 0; i < a.pixels.size(); ++i)
        d.pixels[i] = i % 4 == 3 ? 1.0f : std::abs(a.pixels[i] - b.pixels[i]);
    return d;
}

image::ImageRGBA displayImage(const image::ImageRGBA& src, const PreviewSettings& s) {
    image::ImageRGBA out{src.width, src.height, std::vector<float>(src.pixels.size())};
    const float gain = std::exp2(s.exposure);
    auto [lo, hi] = s.falseColour ? finiteRange(src, s.channel) : std::pair{0.0f, 1.0f};
    const float span = hi > lo ? hi - lo : 1.0f;
    for (size_t p = 0; p < size_t(src.width) * src.height; ++p) {
        const auto rgb = displayPixel(&src.pixels[p * 4], s, gain, lo, span);
        for (int c = 0; c < 3; ++c) out.pixels[p * 4 + size_t(c)] = float(rgb[size_t(c)]) / 255.0f;
        out.pixels[p * 4 + 3] = 1.0f;
    }
    return out;
}

void zoomAround(PreviewView& view, const PreviewFit& fit, float factor, float px, float py) {
    if (fit.width == 0 || fit.height == 0 || !(factor > 0)) return;
    // The image point under (px, py) before, in [0,1]^2 (fit.width/height >= 1).
    const float u = (px - float(fit.offsetX)) / float(fit.width);
    const float v = (py - float(fit.offsetY)) / float(fit.height);
    const float old = std::clamp(view.zoom, kMinZoom, kMaxZoom);
    view.zoom = std::clamp(old * factor, kMinZoom, kMaxZoom);
    const float ratio = view.zoom / old;
    // Keep (u, v) under the pointer: the centre moves towards it as the zoom grows.
    view.centerX = u + (view.centerX - u) / ratio;
    view.centerY = v + (view.centerY - v) / ratio;
    if (view.zoom <= kMinZoom) view.centerX = view.centerY = 0.5f;
}

void panBy(PreviewView& view, const PreviewFit& fit, float dx, float dy) {
    if (fit.width == 0 || fit.height == 0) return;
    view.centerX = std::clamp(view.centerX - dx / float(fit.width), 0.0f, 1.0f);
    view.centerY = std::clamp(view.centerY - dy / float(fit.height), 0.0f, 1.0f);
}

}  // namespace fovea::editor
