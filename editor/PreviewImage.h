// The preview of one graph field: its RGBA float content turned into display bytes on the CPU
// (exposure, channel, false colour), fitted into the preview rectangle of the window. Debian's
// ImGui 1.86 Vulkan backend cannot draw user textures, so the inspector copies these bytes into
// the swapchain image under the UI (docs/inspector.md, "How the preview is drawn").
#pragma once
#include <cstdint>
#include <optional>
#include <string>

#include "core/image/ImageIO.h"
#include "editor/VulkanWindow.h"

namespace fovea::editor {

enum class PreviewChannel { Rgb, R, G, B, A, Luminance };
const char* previewChannelName(PreviewChannel c);
std::optional<PreviewChannel> parsePreviewChannel(const std::string& name);

struct PreviewSettings {
    float exposure = 0.0f;  // stops: values are scaled by 2^exposure
    PreviewChannel channel = PreviewChannel::Rgb;
    // A scalar (the channel, or luminance for RGB) mapped to a colour ramp between the image's
    // finite min and max: for masks, ids, depth and variances.
    bool falseColour = false;
    // 8-bit UNORM fields (Tonemap's ldr) are display-encoded already: no sRGB encoding again.
    bool displayEncoded = false;
};

// Where the image landed inside the rectangle (letterboxed, aspect kept, nearest sampling).
struct PreviewFit {
    int offsetX = 0, offsetY = 0;              // of the image inside the rectangle
    float scale = 1.0f;                        // rectangle pixels per image pixel
    uint32_t width = 0, height = 0;            // of the image inside the rectangle
    uint32_t imageWidth = 0, imageHeight = 0;  // of the source image
};

// Display bytes for a `width` x `height` rectangle at (x, y) of the window; non-finite pixels
// show magenta, the letterbox dark grey. `bgra`: the swapchain's channel order.
PreviewBlit makePreview(const image::ImageRGBA& source, int x, int y, uint32_t width,
                        uint32_t height, const PreviewSettings& settings, bool bgra,
                        PreviewFit* fit = nullptr);

// Image pixel under window position (px, py), or nullopt outside the image.
std::optional<std::pair<uint32_t, uint32_t>> previewPixelAt(const PreviewBlit& blit,
                                                            const PreviewFit& fit, float px,
                                                            float py);

}  // namespace fovea::editor
