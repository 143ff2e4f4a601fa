// Image files through OpenImageIO: linear float EXR for data, tone-mapped sRGB PNG for eyes.
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
// Clamps to [0,1] and applies the sRGB transfer function (values are assumed linear).
void writePng(const std::filesystem::path& path, const ImageRGBA& image);
// Reads any format OIIO knows as RGBA float (missing channels: 0, alpha 1).
// Throws InputError naming the file when it cannot be read.
ImageRGBA readImage(const std::filesystem::path& path);

}  // namespace fovea::image
