// PNG writing (core/image/ImageIO): 8-bit UNORM images (already display-encoded, e.g. Tonemap's
// `ldr`) are written as-is, not sRGB-encoded a second time; linear float images are encoded once
// and alpha stays linear. CPU only.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "core/graph/CompilerStages.h"
#include "core/graph/GraphDesc.h"
#include "core/graph/PassRegistry.h"
#include "core/image/ImageIO.h"
#include "core/util/Error.h"
#include "core/vk/Formats.h"
#include "passes/Blit/BlitPass.h"
#include "passes/Combine/CombinePass.h"
#include "passes/ImageSource/ImageSourcePass.h"
#include "passes/RegisterPasses.h"
#include "passes/Tonemap/TonemapPass.h"

namespace fs = std::filesystem;
using namespace fovea;
using namespace fovea::graph;

namespace {

// --- PNG ------------------------------------------------------------------------------------

fs::path tempFile(const std::string& name) {
    return fs::temp_directory_path() / ("fovea_png_" + std::to_string(::getpid()) + "_" + name);
}

// The bytes as stored: fovea's reader (stb_image, a decoder apart from stb_image_write's
// encoder) gives 8-bit k as k/255 with no premultiplication by alpha or colour conversion.
std::vector<uint8_t> readPngBytes(const fs::path& path, int& width, int& height) {
    const image::ImageRGBA img = image::readImage(path);
    width = int(img.width);
    height = int(img.height);
    std::vector<uint8_t> bytes(img.pixels.size());
    for (size_t i = 0; i < bytes.size(); ++i)
        bytes[i] = uint8_t(std::lround(img.pixels[i] * 255.0f));
    return bytes;
}

// Every byte value 0..255 on every channel, as an rgba8 image reads back (k / 255).
image::ImageRGBA allByteValues(std::vector<uint8_t>& bytes) {
    image::ImageRGBA img{16, 16, {}};
    for (uint32_t p = 0; p < 256; ++p)
        for (uint32_t c = 0; c < 4; ++c) bytes.push_back(uint8_t((p + 67 * c) % 256));
    for (uint8_t b : bytes) img.pixels.push_back(float(b) / 255.0f);
    return img;
}

TEST(PngOutput, Unorm8ImageIsWrittenAsIs) {
    std::vector<uint8_t> expected;
    image::ImageRGBA img = allByteValues(expected);
    const fs::path path = tempFile("asis.png");
    image::writePng(path, img, image::PngEncoding::AsIs);
    int w = 0, h = 0;
    std::vector<uint8_t> got = readPngBytes(path, w, h);
    fs::remove(path);
    ASSERT_EQ(w, 16);
    ASSERT_EQ(h, 16);
    ASSERT_EQ(got.size(), expected.size());
    size_t differ = 0;
    for (size_t i = 0; i < got.size(); ++i) differ += got[i] != expected[i];
    EXPECT_EQ(differ, 0u) << "bytes of a display-encoded image changed on the way to PNG";
}

TEST(PngOutput, LinearImageIsEncodedOnceAndAlphaStaysLinear) {
    // Linear 0.5 -> sRGB 0.7354 -> 188; alpha 0.5 -> 128 (never encoded).
    image::ImageRGBA img{1, 1, {0.5f, 0.0f, 1.0f, 0.5f}};
    const fs::path path = tempFile("srgb.png");
    image::writePng(path, img);  // default: linear input
    int w = 0, h = 0;
    std::vector<uint8_t> got = readPngBytes(path, w, h);
    fs::remove(path);
    ASSERT_EQ(got.size(), 4u);
    EXPECT_EQ(got[0], 188);
    EXPECT_EQ(got[1], 0);
    EXPECT_EQ(got[2], 255);
    EXPECT_EQ(got[3], 128);
}

TEST(PngOutput, Unorm8FormatsAreTheDisplayEncodedOnes) {
    EXPECT_TRUE(gpu::formatIsUnorm8(vk::Format::eR8G8B8A8Unorm));
    EXPECT_TRUE(gpu::formatIsUnorm8(vk::Format::eR8Unorm));
    EXPECT_FALSE(gpu::formatIsUnorm8(vk::Format::eR32G32B32A32Sfloat));
    EXPECT_FALSE(gpu::formatIsUnorm8(vk::Format::eR16G16B16A16Sfloat));
    EXPECT_FALSE(gpu::formatIsUnorm8(vk::Format::eR32Uint));
}

}  // namespace
