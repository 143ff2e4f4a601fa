#include "core/image/ImageIO.h"

#include <algorithm>
#include <cmath>

#include "core/image/ImageCodecs.h"
#include "core/util/Error.h"
#include "core/util/UserFile.h"

namespace fovea::image {

namespace {

float srgbEncode(float c) {
    c = std::clamp(std::isfinite(c) ? c : 0.0f, 0.0f, 1.0f);
    return c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

// A regular file (a decoder would block on a FIFO or read /dev/zero forever), by format.
codec::Decoded decodeFile(const std::filesystem::path& path, bool pixels, uint64_t maxPixels) {
    requireRegularFile(path, "image");
    const bool exr = codec::isExr(path);
    if (!pixels) return exr ? codec::probeExr(path) : codec::probeStb(path);
    return exr ? codec::decodeExr(path, maxPixels) : codec::decodeStb(path, maxPixels);
}

int indexOf(const codec::Decoded& d, const std::string& name) {
    auto it = std::find(d.channels.begin(), d.channels.end(), name);
    return it == d.channels.end() ? -1 : int(it - d.channels.begin());
}

// Which file channels become r, g, b, a when the caller names none: R, G, B (missing ones 0)
// and A; else a grey Y replicated; else the first channels in the file's order.
std::vector<int> defaultChannels(const codec::Decoded& d) {
    const int r = indexOf(d, "R"), g = indexOf(d, "G"), b = indexOf(d, "B"), a = indexOf(d, "A");
    if (r >= 0 || g >= 0 || b >= 0) return {r, g, b, a};
    if (int y = indexOf(d, "Y"); y >= 0) return {y, y, y, a};
    if (d.channels.size() == 1) return {0, 0, 0, -1};
    std::vector<int> first;
    for (int c = 0; c < 4; ++c) first.push_back(c < int(d.channels.size()) ? c : -1);
    return first;
}

// RGBA from the decoded channels: index -1 is 0 for colour and 1 for alpha.
ImageRGBA gather(const codec::Decoded& d, const std::vector<int>& index) {
    ImageRGBA image;
    image.width = d.width;
    image.height = d.height;
    const size_t count = size_t(d.width) * d.height, n = d.channels.size();
    image.pixels.resize(count * 4);
    for (size_t p = 0; p < count; ++p)
        for (size_t c = 0; c < 4; ++c)
            image.pixels[p * 4 + c] =
                index[c] >= 0 ? d.pixels[p * n + size_t(index[c])] : (c == 3 ? 1.0f : 0.0f);
    return image;
}

}  // namespace

void writeExr(const std::filesystem::path& path, const ImageRGBA& image) {
    const auto bytes = codec::encodeExr(image.width, image.height, image.pixels.data());
    writeFileChecked(path, bytes.data(), bytes.size());
}

void writePng(const std::filesystem::path& path, const ImageRGBA& image, PngEncoding encoding) {
    std::vector<uint8_t> rgba(image.pixels.size());
    for (size_t i = 0; i < rgba.size(); ++i) {
        // Alpha is coverage, never sRGB-encoded.
        bool quantizeOnly = i % 4 == 3 || encoding == PngEncoding::AsIs;
        float v = std::isfinite(image.pixels[i]) ? image.pixels[i] : 0.0f;
        v = quantizeOnly ? std::clamp(v, 0.0f, 1.0f) : srgbEncode(v);
        rgba[i] = uint8_t(std::lround(v * 255.0f));
    }
    const auto bytes = codec::encodePng(image.width, image.height, rgba.data());
    writeFileChecked(path, bytes.data(), bytes.size());
}

void codec::checkPixelCount(const std::filesystem::path& path, uint64_t width, uint64_t height,
                            uint64_t maxPixels) {
    const uint64_t limit = maxPixels > 0 ? maxPixels : kMaxImagePixels;
    if (width * height > limit)  // both < 2^32: no overflow in 64 bits
        throw InputError(path.string(), "",
                         "image is " + std::to_string(width) + "x" + std::to_string(height) +
                             ", more than the " + std::to_string(limit) + " pixels allowed here");
}

ImageSize readImageSize(const std::filesystem::path& path) {
    const codec::Decoded d = decodeFile(path, false, 0);
    return {d.width, d.height};
}

ImageRGBA readImage(const std::filesystem::path& path, uint64_t maxPixels) {
    const codec::Decoded d = decodeFile(path, true, maxPixels);
    return gather(d, defaultChannels(d));
}

ImageRGBA readImageChannels(const std::filesystem::path& path,
                            const std::vector<std::string>& channels) {
    if (channels.empty()) return readImage(path);
    if (channels.size() > 4)
        throw InputError(path.string(), "", "at most 4 channels can be selected");
    // One open and decode (ImageFile reads a file per frame); the pixel cap is checked on the
    // header inside the decode, and a wrong name only costs a decode on the way to its error.
    const codec::Decoded decoded = decodeFile(path, true, 0);
    std::vector<int> index;
    for (const std::string& name : channels) {
        const int found = indexOf(decoded, name);
        if (found < 0) {
            std::string list;
            for (const auto& n : decoded.channels) list += (list.empty() ? "" : ", ") + n;
            throw InputError(path.string(), "",
                             "no channel '" + name + "' (channels: " + list + ")");
        }
        index.push_back(found);
    }
    if (index.size() == 1) index = {index[0], index[0], index[0], -1};  // one channel: grey
    index.resize(4, -1);
    return gather(decoded, index);
}

}  // namespace fovea::image
