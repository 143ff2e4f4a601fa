// PNG, JPEG, Radiance HDR, TGA, BMP, PSD, GIF and PNM through stb_image, PNG out through
// stb_image_write (Debian's libstb-dev). Values as stored: 8-bit k -> k/255, 16-bit k -> k/65535,
// HDR as linear floats; no gamma or colour-profile conversion, and alpha is never premultiplied.
#include <cstdio>
#include <cstring>
#include <memory>

#include "core/image/ImageCodecs.h"
#include "core/util/Error.h"
#include "core/util/UserFile.h"

// Compiled here with static linkage, like core/scene/gltf/GltfTextures.cpp's copy, so no other
// library's stb can clash with it.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wall"
#pragma GCC diagnostic ignored "-Wextra"
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#define STBI_FAILURE_USERMSG
#include <stb/stb_image.h>
#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>
#pragma GCC diagnostic pop

namespace fovea::image::codec {

namespace {

std::string reason() {
    const char* r = stbi_failure_reason();
    return r ? r : "unknown reason";
}

std::vector<std::string> channelNames(int components) {
    switch (components) {
        case 1:
            return {"Y"};
        case 2:
            return {"Y", "A"};
        case 3:
            return {"R", "G", "B"};
        default:
            return {"R", "G", "B", "A"};
    }
}

// A PNG's size and channel count from its IHDR chunk (signature, length, "IHDR", width, height,
// bit depth, colour type; big-endian). stb refuses a PNG of 2^30 bytes of pixels or more already
// in stbi_info, so that its size could not be reported or compared before the decode refuses it.
bool pngHeader(const unsigned char* b, size_t size, uint64_t& width, uint64_t& height,
               int& components) {
    if (size < 26 || std::memcmp(b, "\x89PNG\r\n\x1a\n", 8) != 0 ||
        std::memcmp(b + 12, "IHDR", 4) != 0)
        return false;
    auto be32 = [&](int at) {
        return uint64_t(b[at]) << 24 | uint64_t(b[at + 1]) << 16 | uint64_t(b[at + 2]) << 8 |
               uint64_t(b[at + 3]);
    };
    width = be32(16);
    height = be32(20);
    const int byColourType[7] = {1, 0, 3, 3, 2, 0, 4};  // grey, -, RGB, palette, grey+A, -, RGBA
    components = b[25] < 7 ? byColourType[b[25]] : 0;
    return width > 0 && height > 0 && components > 0;
}

// The header stbi_info found (`known`), or, when it refused the file, the size of a PNG too large
// for stb from its IHDR (`head`: the file's first bytes); else an InputError naming the file.
Decoded header(const std::filesystem::path& path, bool known, int w, int h, int components,
               const unsigned char* head, size_t headSize) {
    if (!known) {
        const std::string why = reason();
        uint64_t pngWidth = 0, pngHeight = 0;
        int pngComponents = 0;
        if (pngHeader(head, headSize, pngWidth, pngHeight, pngComponents) &&
            pngWidth * pngHeight * uint64_t(pngComponents) >= (uint64_t(1) << 30) &&
            pngWidth <= UINT32_MAX && pngHeight <= UINT32_MAX) {
            // Too large for stb, not damaged: its size, for the callers' size checks and the
            // pixel limit (decodeStb refuses it before any decode).
            Decoded d;
            d.width = uint32_t(pngWidth);
            d.height = uint32_t(pngHeight);
            d.channels = channelNames(pngComponents);
            return d;
        }
        throw InputError(path.string(), "",
                         "cannot read image: not an EXR, PNG, JPEG, HDR, TGA, BMP, PSD, GIF or "
                         "PNM file, or a damaged one (" +
                             why + ")");
    }
    if (w <= 0 || h <= 0 || components < 1 || components > 4)
        throw InputError(path.string(), "", "image has no pixels");
    Decoded d;
    d.width = uint32_t(w);
    d.height = uint32_t(h);
    d.channels = channelNames(components);
    return d;
}

template <class T>
void convert(const std::filesystem::path& path, const Decoded& expected, T* data, int w, int h,
             int components, float divisor, Decoded& out) {
    std::unique_ptr<T, void (*)(void*)> owned(data, &stbi_image_free);
    if (!data) throw InputError(path.string(), "", "cannot decode image: " + reason());
    if (uint32_t(w) != expected.width || uint32_t(h) != expected.height ||
        size_t(components) != expected.channels.size())
        throw InputError(path.string(), "", "cannot decode image: header and data disagree");
    const size_t n = size_t(w) * size_t(h) * size_t(components);
    out.pixels.resize(n);
    for (size_t i = 0; i < n; ++i)
        out.pixels[i] = float(data[i]) / divisor;  // divisor 1, 255 or 65535
}

}  // namespace

// The header only: stb reads as little of the file as it needs (the caller has checked it is a
// regular file).
Decoded probeStb(const std::filesystem::path& path) {
    int w = 0, h = 0, components = 0;
    const bool known = stbi_info(path.c_str(), &w, &h, &components);
    unsigned char head[26] = {};
    size_t headSize = 0;
    if (!known) {
        if (FILE* f = std::fopen(path.c_str(), "rb")) {
            headSize = std::fread(head, 1, sizeof head, f);
            std::fclose(f);
        }
    }
    return header(path, known, w, h, components, head, headSize);
}

// The file is read once; header, format and pixels all come from those bytes.
Decoded decodeStb(const std::filesystem::path& path, uint64_t maxPixels) {
    std::vector<uint8_t> bytes;
    std::string error;
    if (!readRegularFile(path, uint64_t(INT32_MAX), bytes, error))
        throw InputError(path.string(), "", "cannot read image: " + error);
    const stbi_uc* data = bytes.data();
    const int size = int(bytes.size());  // <= INT32_MAX: readRegularFile's limit
    int w = 0, h = 0, components = 0;
    const bool known = stbi_info_from_memory(data, size, &w, &h, &components);
    Decoded d = header(path, known, w, h, components, data, bytes.size());
    checkPixelCount(path, d.width, d.height, maxPixels);
    // Decoded first, then converted: the sizes are outputs of the load.
    if (stbi_is_hdr_from_memory(data, size)) {
        float* pixels = stbi_loadf_from_memory(data, size, &w, &h, &components, 0);
        convert(path, d, pixels, w, h, components, 1.0f, d);
    } else if (stbi_is_16_bit_from_memory(data, size)) {
        stbi_us* pixels = stbi_load_16_from_memory(data, size, &w, &h, &components, 0);
        convert(path, d, pixels, w, h, components, 65535.0f, d);
    } else {
        stbi_uc* pixels = stbi_load_from_memory(data, size, &w, &h, &components, 0);
        convert(path, d, pixels, w, h, components, 255.0f, d);
    }
    return d;
}

std::vector<unsigned char> encodePng(uint32_t width, uint32_t height, const uint8_t* rgba) {
    std::vector<unsigned char> bytes;
    auto append = [](void* context, void* data, int size) {
        auto* out = static_cast<std::vector<unsigned char>*>(context);
        const auto* p = static_cast<const unsigned char*>(data);
        out->insert(out->end(), p, p + size);
    };
    if (!stbi_write_png_to_func(append, &bytes, int(width), int(height), 4, rgba, int(width) * 4))
        throw RuntimeError("cannot encode a " + std::to_string(width) + "x" +
                           std::to_string(height) + " PNG");
    return bytes;
}

}  // namespace fovea::image::codec
