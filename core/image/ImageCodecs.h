// The two decoders and encoders behind core/image/ImageIO.h: OpenEXR for EXR, stb_image and
// stb_image_write (Debian's libstb-dev, which also decodes glTF textures) for PNG, JPEG, Radiance
// HDR, TGA, BMP, PSD, GIF and PNM. Internal to core/image; ImageIO.h is the interface.
#pragma once
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace fovea::image::codec {

// A decoded image: `channels.size()` floats per pixel, interleaved, row-major, top row first.
struct Decoded {
    uint32_t width = 0, height = 0;
    std::vector<std::string> channels;  // EXR: the file's names; others: R G B A / Y A
    std::vector<float> pixels;
};

bool isExr(const std::filesystem::path& path);  // by the file's magic number, not its name

// Header only: width, height and channel names, no pixel decoded. InputError naming the file.
Decoded probeExr(const std::filesystem::path& path);
Decoded probeStb(const std::filesystem::path& path);
// Decodes every channel as float. `maxPixels` is checked on the header, before any allocation.
Decoded decodeExr(const std::filesystem::path& path, uint64_t maxPixels);
Decoded decodeStb(const std::filesystem::path& path, uint64_t maxPixels);

// Encoded in memory (the caller writes the bytes with checked I/O). RGBA, 4 values per pixel.
std::vector<unsigned char> encodeExr(uint32_t width, uint32_t height, const float* rgba);
std::vector<unsigned char> encodePng(uint32_t width, uint32_t height, const uint8_t* rgba);

// InputError unless width * height <= maxPixels.
void checkPixelCount(const std::filesystem::path& path, uint64_t width, uint64_t height,
                     uint64_t maxPixels);

}  // namespace fovea::image::codec
