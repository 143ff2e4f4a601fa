#include "core/image/ImageIO.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <memory>
#include <vector>

#include "core/util/Error.h"
#include "core/util/UserFile.h"

namespace fovea::image {

namespace {

// Encoded in memory (OpenImageIO's IOProxy), then written with checked stdio: OpenImageIO's own
// file output reports no error when the disk is full (a link to /dev/full "writes" PNG and EXR
// alike; tests/unit/UserFileTests.cpp), so the bytes go through writeFileChecked.
void writeWith(const std::filesystem::path& path, uint32_t w, uint32_t h, OIIO::TypeDesc type,
               const void* data) {
    auto out = OIIO::ImageOutput::create(path.string());
    if (!out) throw RuntimeError(path.string() + ": cannot create image: " + OIIO::geterror());
    if (!out->supports("ioproxy"))
        throw RuntimeError(path.string() + ": cannot write this format (" +
                           std::string(out->format_name()) + ") with checked writes");
    OIIO::ImageSpec spec(int(w), int(h), 4, type);
    // Our pixels carry straight (unassociated) alpha. Without this OIIO assumes premultiplied
    // data and divides colour by alpha when writing a PNG, changing every non-opaque pixel.
    spec.attribute("oiio:UnassociatedAlpha", 1);
    std::vector<unsigned char> bytes;
    OIIO::Filesystem::IOVecOutput memory(bytes);
    OIIO::Filesystem::IOProxy* proxy = &memory;
    spec.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
    if (!out->open(path.string(), spec) || !out->write_image(type, data) || !out->close())
        throw RuntimeError(path.string() + ": cannot encode image: " + out->geterror());
    writeFileChecked(path, bytes.data(), bytes.size());
}

float srgbEncode(float c) {
    c = std::clamp(std::isfinite(c) ? c : 0.0f, 0.0f, 1.0f);
    return c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

}  // namespace

void writeExr(const std::filesystem::path& path, const ImageRGBA& image) {
    writeWith(path, image.width, image.height, OIIO::TypeDesc::FLOAT, image.pixels.data());
}

void writePng(const std::filesystem::path& path, const ImageRGBA& image, PngEncoding encoding) {
    std::vector<uint8_t> bytes(image.pixels.size());
    for (size_t i = 0; i < bytes.size(); ++i) {
        // Alpha is coverage, never sRGB-encoded.
        bool quantizeOnly = i % 4 == 3 || encoding == PngEncoding::AsIs;
        float v = std::isfinite(image.pixels[i]) ? image.pixels[i] : 0.0f;
        v = quantizeOnly ? std::clamp(v, 0.0f, 1.0f) : srgbEncode(v);
        bytes[i] = uint8_t(std::lround(v * 255.0f));
    }
    writeWith(path, image.width, image.height, OIIO::TypeDesc::UINT8, bytes.data());
}

namespace {

// OpenEXR sizes an attribute's value from the int32 in front of it before reading it: a 541-byte
// file whose string attribute claims 842 MB made it allocate and clear 842 MB (found by the image
// fuzz target; tests/fuzz/regressions/image/). Every attribute of every header must fit in the
// file, which costs one pass over the header (names, types and sizes; values are skipped).
void checkExrHeaderSizes(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    char magic[4] = {};
    uint32_t version = 0;
    if (!in.read(magic, 4) || std::memcmp(magic, "\x76\x2f\x31\x01", 4) != 0) return;
    if (!in.read(reinterpret_cast<char*>(&version), 4)) return;  // OpenEXR reports it
    const uint64_t fileSize = std::filesystem::file_size(path);
    const bool multiPart = (version & 0x1000u) != 0;
    auto readName = [&](std::string& name) {  // NUL-terminated, at most 255 bytes in OpenEXR
        name.clear();
        for (char c; in.get(c) && c != '\0';)
            if (name.size() < 256) name.push_back(c);
        return bool(in);
    };
    std::string name, type;
    for (int headers = 0; readName(name);) {
        if (name.empty()) {  // end of a header; a multi-part file ends with an empty header
            if (!multiPart || in.peek() == 0 || ++headers > 1024) return;
            continue;
        }
        int32_t size = 0;
        if (!readName(type) || !in.read(reinterpret_cast<char*>(&size), 4)) return;
        const uint64_t at = uint64_t(in.tellg());
        if (size < 0 || at + uint64_t(size) > fileSize)
            throw InputError(path.string(), "",
                             "OpenEXR header attribute '" + name + "' claims " +
                                 std::to_string(size) + " bytes at offset " + std::to_string(at) +
                                 "; the file has " + std::to_string(fileSize));
        in.seekg(size, std::ios::cur);
    }
}

// Opened for reading with straight alpha kept as stored (OIIO would premultiply a PNG's colour by
// its alpha); an unreadable file or one without pixels is an InputError naming it.
std::unique_ptr<OIIO::ImageInput> openImage(const std::filesystem::path& path) {
    requireRegularFile(path, "image");  // OpenImageIO would block on a FIFO or /dev/zero
    checkExrHeaderSizes(path);
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    auto in = OIIO::ImageInput::open(path.string(), &config);
    if (!in) throw InputError(path.string(), "", "cannot read image: " + OIIO::geterror());
    const OIIO::ImageSpec& spec = in->spec();
    if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0)
        throw InputError(path.string(), "", "image has no pixels");
    return in;
}

// The header's pixel count against the limit (maxPixels 0: kMaxImagePixels).
void checkPixelCount(const std::filesystem::path& path, const OIIO::ImageSpec& spec,
                     uint64_t maxPixels) {
    const uint64_t limit = maxPixels > 0 ? maxPixels : kMaxImagePixels;
    const uint64_t pixels = uint64_t(spec.width) * uint64_t(spec.height);  // both > 0: openImage
    if (pixels > limit)
        throw InputError(path.string(), "",
                         "image is " + std::to_string(spec.width) + "x" +
                             std::to_string(spec.height) + ", more than the " +
                             std::to_string(limit) + " pixels allowed here");
}

}  // namespace

ImageSize readImageSize(const std::filesystem::path& path) {
    const auto in = openImage(path);
    return {uint32_t(in->spec().width), uint32_t(in->spec().height)};  // > 0: openImage
}

ImageRGBA readImage(const std::filesystem::path& path, uint64_t maxPixels) {
    auto in = openImage(path);
    const OIIO::ImageSpec& spec = in->spec();
    checkPixelCount(path, spec, maxPixels);
    ImageRGBA image;
    image.width = uint32_t(spec.width);
    image.height = uint32_t(spec.height);
    const int channels = spec.nchannels;
    std::vector<float> raw(size_t(spec.width) * spec.height * channels);
    if (!in->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, raw.data()))
        throw InputError(path.string(), "", "cannot decode image: " + in->geterror());
    image.pixels.assign(size_t(image.width) * image.height * 4, 0.0f);
    for (size_t p = 0; p < size_t(image.width) * image.height; ++p) {
        for (int c = 0; c < 4; ++c) {
            float v = c < channels ? raw[p * channels + c] : (c == 3 ? 1.0f : 0.0f);
            if (channels == 1 && c < 3) v = raw[p];  // grey: replicate
            image.pixels[p * 4 + c] = v;
        }
    }
    return image;
}

ImageRGBA readImageChannels(const std::filesystem::path& path,
                            const std::vector<std::string>& channels) {
    if (channels.empty()) return readImage(path);
    if (channels.size() > 4)
        throw InputError(path.string(), "", "at most 4 channels can be selected");
    auto in = openImage(path);
    const OIIO::ImageSpec& spec = in->spec();
    checkPixelCount(path, spec, 0);
    std::vector<int> index;
    for (const std::string& name : channels) {
        int found = spec.channelindex(name);
        if (found < 0) {
            std::string list;
            for (const auto& n : spec.channelnames) list += (list.empty() ? "" : ", ") + n;
            throw InputError(path.string(), "",
                             "no channel '" + name + "' (channels: " + list + ")");
        }
        index.push_back(found);
    }
    const int all = spec.nchannels;
    std::vector<float> raw(size_t(spec.width) * spec.height * all);
    if (!in->read_image(0, 0, 0, all, OIIO::TypeDesc::FLOAT, raw.data()))
        throw InputError(path.string(), "", "cannot decode image: " + in->geterror());
    ImageRGBA image;
    image.width = uint32_t(spec.width);
    image.height = uint32_t(spec.height);
    image.pixels.assign(size_t(image.width) * image.height * 4, 0.0f);
    for (size_t p = 0; p < size_t(image.width) * image.height; ++p) {
        for (size_t c = 0; c < 4; ++c) {
            float v = c == 3 ? 1.0f : 0.0f;
            if (index.size() == 1 && c < 3)
                v = raw[p * all + size_t(index[0])];
            else if (c < index.size())
                v = raw[p * all + size_t(index[c])];
            image.pixels[p * 4 + c] = v;
        }
    }
    return image;
}

}  // namespace fovea::image
