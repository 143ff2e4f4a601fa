// Image files: linear float EXR for data, tone-mapped sRGB PNG for eyes. EXR through OpenEXR,
// the other formats through stb_image (core/image/ImageCodecs.h); the decoder follows the file's
// content, not its name.
#pragma once
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace fovea::image {

// RGBA float pixels, row-major, top row first.
struct ImageRGBA {
    uint32_t width = 0, height = 0;
    std::vector<float> pixels;  // width * height * 4
};

// Writes linear float RGBA (half-float is not used: goldens compare full precision).
void writeExr(const std::filesystem::path& path, const ImageRGBA& image);
// How writePng turns pixel values into 8-bit codes. An image that is already display-encoded
// (an 8-bit UNORM render target, e.g. Tonemap's `ldr`, which applied sRGB itself) must be
// written as-is: encoding it again would brighten it twice.
enum class PngEncoding {
    Srgb,  // values are linear: clamp to [0,1], apply the sRGB transfer function (alpha linear)
    AsIs,  // values are display-encoded in [0,1]: clamp and quantize only (k/255 -> k exactly)
};
// Writes 8-bit RGBA with straight (unassociated) alpha: colour is never divided by alpha.
void writePng(const std::filesystem::path& path, const ImageRGBA& image,
              PngEncoding encoding = PngEncoding::Srgb);
// The most pixels any reader decodes (16384 x 16384; 4 GiB as RGBA float): a header asking for
// more is an InputError before any pixel is allocated (a 57-byte PNG may claim 100000^2).
constexpr uint64_t kMaxImagePixels = uint64_t(1) << 28;

struct ImageSize {
    uint32_t width = 0, height = 0;
};
// The size in the image's header (for EXR its data window), without decoding a pixel, so a
// caller can refuse a wrong size before paying for the decode. InputError as readImage.
ImageSize readImageSize(const std::filesystem::path& path);

// Reads EXR, PNG, JPEG, Radiance HDR, TGA, BMP, PSD, GIF or PNM as RGBA float: channels R, G, B
// (missing ones 0) and A (missing: 1); a grey image's Y replicated; else the first channels.
// 8/16-bit values k read as k/255, k/65535; alpha as stored (colour is not premultiplied).
// Throws InputError naming the file when it cannot be read, or when the image has more pixels
// than `maxPixels` (0: kMaxImagePixels; checked on the header, before any pixel is allocated).
ImageRGBA readImage(const std::filesystem::path& path, uint64_t maxPixels = 0);
// readImage with channel selection: `channels` (at most 4) name the file's channels read as
// r, g, b, a (missing alpha 1, missing g/b 0; one channel is replicated to r, g, b); empty = as
// readImage. An unknown name is an InputError naming the file and listing its channels.
ImageRGBA readImageChannels(const std::filesystem::path& path,
                            const std::vector<std::string>& channels);

}  // namespace fovea::image
