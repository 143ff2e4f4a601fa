// The preview of one graph field: its RGBA float content turned into display bytes on the CPU
// (exposure, channel, false colour), fitted into the preview rectangle of the window. Debian's
// ImGui 1.86 Vulkan backend cannot draw user textures, so the inspector copies these bytes into
// the swapchain image under the UI (docs/inspector.md, "How the preview is drawn").
#pragma once
#include <array>
#include <cstdint>
#include <optional>
#include <string>

#include "core/image/ImageIO.h"
#include "editor/VulkanWindow.h"

namespace fovea::editor {

enum class PreviewChannel { Rgb, R, G, B, A, Luminance };
const char* previewChannelName(PreviewChannel c);
std::optional<PreviewChannel> parsePreviewChannel(const std::string& name);

// Zoom and pan, shared by both panes of a comparison: `zoom` is relative to the fitted size (1 =
// the whole image fits the pane), the centre of the pane shows (centerX, centerY) in [0,1]^2.
struct PreviewView {
    float zoom = 1.0f;
    float centerX = 0.5f, centerY = 0.5f;
};
constexpr float kMinZoom = 1.0f, kMaxZoom = 64.0f;

struct PreviewSettings {
    float exposure = 0.0f;  // stops: values are scaled by 2^exposure
    PreviewChannel channel = PreviewChannel::Rgb;
    // A scalar (the channel, or luminance for RGB) mapped to a colour ramp between the image's
    // finite min and max: for masks, ids, depth and variances.
    bool falseColour = false;
    // 8-bit UNORM fields (Tonemap's ldr) are display-encoded already: no sRGB encoding again.
    bool displayEncoded = false;
    PreviewView view;
};

// Where the image landed in the blit (aspect kept, nearest sampling; letterboxed at zoom 1).
struct PreviewFit {
    int offsetX = 0, offsetY = 0;              // image's top-left, blit pixels (< 0 when zoomed)
    float scale = 1.0f;                        // blit pixels per image pixel
    uint32_t width = 0, height = 0;            // of the scaled image
    uint32_t imageWidth = 0, imageHeight = 0;  // of the source image
    int paneX = 0;                             // the pane inside the blit (two in a comparison)
    uint32_t paneWidth = 0;
};

// Display bytes for a `width` x `height` rectangle at (x, y) of the window, one pane; non-finite
// pixels show magenta, the letterbox dark grey. `bgra`: the swapchain's channel order.
PreviewBlit makePreview(const image::ImageRGBA& source, int x, int y, uint32_t width,
                        uint32_t height, const PreviewSettings& settings, bool bgra,
                        PreviewFit* fit = nullptr);
// Draws `source` into the columns [paneX, paneX + paneWidth) of an existing blit.
void drawPreviewPane(const image::ImageRGBA& source, const PreviewSettings& settings, bool bgra,
                     PreviewBlit& blit, int paneX, uint32_t paneWidth, PreviewFit* fit = nullptr);

// Image pixel under window position (px, py), or nullopt outside the image or its pane.
std::optional<std::pair<uint32_t, uint32_t>> previewPixelAt(const PreviewBlit& blit,
                                                            const PreviewFit& fit, float px,
                                                            float py);
// The visible part of the image in window pixels: x, y, width, height.
std::array<int, 4> visibleImageRect(const PreviewBlit& blit, const PreviewFit& fit);

// |a - b| per channel (alpha 1): the comparison's difference view. Non-finite inputs give
// non-finite differences (shown magenta). Empty when the sizes differ.
image::ImageRGBA differenceImage(const image::ImageRGBA& a, const image::ImageRGBA& b);
// The image as the preview shows it (exposure, channel, false colour, sRGB), at its own size,
// values display-encoded in [0,1]: the preview's PNG screenshot.
image::ImageRGBA displayImage(const image::ImageRGBA& source, const PreviewSettings& settings);

// Zoom by `factor` keeping the image point under blit column/row (px, py) of `fit` in place.
void zoomAround(PreviewView& view, const PreviewFit& fit, float factor, float px, float py);
// Pan by (dx, dy) window pixels.
void panBy(PreviewView& view, const PreviewFit& fit, float dx, float dy);

}  // namespace fovea::editor
