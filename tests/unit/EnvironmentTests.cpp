// CPU tests of the environment light (core/scene/Environment.h): the direction convention, the
// importance-sampling distribution (its pdf integrates to 1 over the sphere, the alias tables
// draw each texel with its probability), the power used to choose it against other lights, and
// loadEnvironment's handling of bad files (missing, empty, not an image, NaN / Inf texels,
// bad options) and of files that are odd but usable (not 2:1, all black, too large, negative
// texels: warnings).
// Part of the sanitizer suite (Makefile SANITIZE_TESTS).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "core/image/ImageIO.h"
#include "core/scene/Environment.h"
#include "core/util/Error.h"
#include "tests/unit/InputErrorOf.h"

using namespace fovea;
using namespace fovea::scene;
namespace fs = std::filesystem;

using fovea::test::inputErrorOf;

namespace {

constexpr double kPi = std::numbers::pi;

// A sky for tests: a vertical gradient, a dim ground, and a bright "sun" block of texels.
EnvironmentMap skyMap(uint32_t width = 32, uint32_t height = 16, float rotationDegrees = 0.0f) {
    EnvironmentMap map = constantEnvironment(glm::vec3(0.0f), width, height);
    map.rotation = float(rotationDegrees * kPi / 180.0);
    for (uint32_t j = 0; j < height; ++j)
        for (uint32_t i = 0; i < width; ++i) {
            const float v = (j + 0.5f) / height;
            glm::vec3 c =
                v < 0.5f ? glm::vec3(0.3f, 0.5f, 1.0f) * (1.2f - v) : glm::vec3(0.1f, 0.08f, 0.05f);
            if (i >= width / 4 && i < width / 4 + 2 && j >= height / 4 && j < height / 4 + 1)
                c = glm::vec3(200.0f, 180.0f, 150.0f);
            map.radiance[size_t(j) * width + i] = c;
        }
    return map;
}

class TempFolder {
public:
    TempFolder() {
        std::random_device random;
        mPath = fs::temp_directory_path() /
                ("fovea_env_" + std::to_string(random()) + "_" + std::to_string(random()));
        fs::create_directories(mPath);
    }
    ~TempFolder() {
        std::error_code ignored;
        fs::remove_all(mPath, ignored);
    }
    fs::path operator/(const std::string& name) const { return mPath / name; }

private:
    fs::path mPath;
};

fs::path writeMap(const TempFolder& dir, const std::string& name, uint32_t width, uint32_t height,
                  const std::vector<glm::vec3>& texels) {
    image::ImageRGBA img;
    img.width = width;
    img.height = height;
    img.pixels.resize(size_t(width) * height * 4);
    for (size_t i = 0; i < size_t(width) * height; ++i) {
        img.pixels[4 * i] = texels[i].r;
        img.pixels[4 * i + 1] = texels[i].g;
        img.pixels[4 * i + 2] = texels[i].b;
        img.pixels[4 * i + 3] = 1.0f;
    }
    const fs::path path = dir / name;
    image::writeExr(path, img);
    return path;
}

bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

}  // namespace

// --- the mapping -------------------------------------------------------------------------------

// The convention of Environment.h: +X is the image centre, +Y the top row, rotation r turns the
// centre to (cos r, 0, -sin r).
TEST(Environment, ConventionOfTheHeader) {
    glm::vec2 uv = environmentUv({1, 0, 0}, 0.0f);
    EXPECT_NEAR(uv.x, 0.5f, 1e-6f);
    EXPECT_NEAR(uv.y, 0.5f, 1e-6f);
    EXPECT_NEAR(environmentUv({0, 1, 0}, 0.0f).y, 0.0f, 1e-6f);
    EXPECT_GT(environmentUv({0, -1, 0}, 0.0f).y, 0.9999f);
    EXPECT_NEAR(environmentUv({0, 0, 1}, 0.0f).x, 0.75f, 1e-6f);  // phi = +90 degrees
    const float r = float(kPi / 2.0);
    const glm::vec3 centre = environmentDirection({0.5f, 0.5f}, r);
    EXPECT_NEAR(centre.x, std::cos(r), 1e-6f);
    EXPECT_NEAR(centre.z, -std::sin(r), 1e-6f);
    EXPECT_NEAR(environmentUv(glm::vec3(0.0f), 0.0f).y, 0.0f, 0.0f);  // zero: the zenith
}

TEST(Environment, UvAndDirectionAreInverse) {
    for (float rotation : {0.0f, 1.0f, -2.5f})
        for (float u = 0.03f; u < 1.0f; u += 0.097f)
            for (float v = 0.02f; v < 1.0f; v += 0.083f) {
                const glm::vec3 d = environmentDirection({u, v}, rotation);
                EXPECT_NEAR(glm::length(d), 1.0f, 1e-5f);
                const glm::vec2 back = environmentUv(d, rotation);
                EXPECT_NEAR(back.x, u, 1e-4f) << rotation << " " << u << " " << v;
                EXPECT_NEAR(back.y, v, 1e-4f);
            }
}

// --- the distribution --------------------------------------------------------------------------

// p(w) integrates to 1 over the sphere: a midpoint sum over a grid 4x finer than the texels,
// dw = 2 pi^2 sin(theta) du dv.
TEST(Environment, PdfIntegratesToOne) {
    for (float rotation : {0.0f, 37.0f}) {
        const EnvironmentMap map = skyMap(32, 16, rotation);
        const EnvironmentDistribution d(map);
        ASSERT_FALSE(d.empty());
        const int nu = 128, nv = 64;
        double sum = 0.0;
        for (int j = 0; j < nv; ++j)
            for (int i = 0; i < nu; ++i) {
                const glm::vec2 uv((i + 0.5f) / nu, (j + 0.5f) / nv);
                const glm::vec3 w = environmentDirection(uv, map.rotation);
                sum += d.pdf(w) * 2.0 * kPi * kPi * std::sin(kPi * uv.y) / (double(nu) * nv);
            }
        EXPECT_NEAR(sum, 1.0, 2e-3) << "rotation " << rotation;
    }
}

// The alias tables draw texel k with probability P_k: 400k draws, every texel within 5 standard
// deviations of its expected count (a swapped alias or keep probability moves whole texels).
TEST(Environment, AliasTablesDrawEachTexelWithItsProbability) {
    const EnvironmentMap map = skyMap(16, 8);
    const EnvironmentDistribution d(map);
    const size_t n = map.radiance.size();
    std::vector<double> counts(n, 0.0);
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
    const int draws = 400000;
    for (int s = 0; s < draws; ++s) {
        const glm::vec4 u(uniform(rng), uniform(rng), uniform(rng), uniform(rng));
        const uint32_t k = d.sampleTexel(glm::min(u, glm::vec4(0.99999994f)));
        ASSERT_LT(k, n);
        counts[k] += 1.0;
    }
    for (size_t k = 0; k < n; ++k) {
        const double p = d.texelProbability()[k];
        const double expected = p * draws, sigma = std::sqrt(draws * p * (1.0 - p));
        EXPECT_NEAR(counts[k], expected, 5.0 * sigma + 1.0) << "texel " << k;
    }
    double total = 0.0;
    for (double p : d.texelProbability()) total += p;
    EXPECT_NEAR(total, 1.0, 1e-9);
}

// A constant map: the luminance integral is 4 pi L, the pdf uniform 1 / (4 pi) up to the
// sin(theta) at the row centre the weights use (exact at the equator rows' centres).
TEST(Environment, ConstantMapIsNearlyUniform) {
    const EnvironmentMap map = constantEnvironment(glm::vec3(2.0f), 64, 32);
    const EnvironmentDistribution d(map);
    EXPECT_NEAR(d.luminanceIntegral(), 4.0 * kPi * 2.0, 1e-9);
    const glm::vec3 equator = environmentDirection({0.3f, 15.5f / 32.0f}, 0.0f);
    EXPECT_NEAR(d.pdf(equator), 1.0 / (4.0 * kPi), 2e-3 / (4.0 * kPi));
    // Selection power: the map as directional lights, pi r^2 * integral.
    EXPECT_NEAR(d.power(2.0), kPi * 4.0 * d.luminanceIntegral(), 1e-9);
    EXPECT_NEAR(d.power(std::numeric_limits<double>::quiet_NaN()), kPi * d.luminanceIntegral(),
                1e-9);
}

TEST(Environment, BlackMapHasNoDistribution) {
    const EnvironmentDistribution d(constantEnvironment(glm::vec3(0.0f)));
    EXPECT_TRUE(d.empty());
    EXPECT_EQ(d.pdf({0, 1, 0}), 0.0);
    EXPECT_EQ(d.luminanceIntegral(), 0.0);
}

TEST(Environment, RadianceIsTheNearestTexel) {
    const EnvironmentMap map = skyMap(32, 16, 25.0f);
    for (uint32_t k = 0; k < map.radiance.size(); k += 7) {
        const glm::vec2 centre((k % 32 + 0.5f) / 32.0f, (k / 32 + 0.5f) / 16.0f);
        EXPECT_EQ(environmentRadiance(map, environmentDirection(centre, map.rotation)),
                  map.radiance[k])
            << k;
    }
}

// --- loading -----------------------------------------------------------------------------------

TEST(EnvironmentLoad, ReadsAnExrAndAppliesIntensityAndRotation) {
    TempFolder dir;
    const EnvironmentMap sky = skyMap(16, 8);
    const fs::path file = writeMap(dir, "sky.exr", 16, 8, sky.radiance);
    std::vector<std::string> warnings;
    const EnvironmentMap map = loadEnvironment(file, 2.0f, 90.0f, warnings);
    EXPECT_TRUE(warnings.empty()) << warnings.front();
    ASSERT_EQ(map.width, 16u);
    ASSERT_EQ(map.height, 8u);
    EXPECT_NEAR(map.rotation, kPi / 2.0, 1e-6);
    for (size_t k = 0; k < sky.radiance.size(); ++k)
        EXPECT_EQ(map.radiance[k], sky.radiance[k] * 2.0f) << k;
}

TEST(EnvironmentLoad, OddButUsableMapsWarn) {
    TempFolder dir;
    std::vector<std::string> warnings;
    loadEnvironment(writeMap(dir, "square.exr", 8, 8, std::vector<glm::vec3>(64, glm::vec3(1))),
                    1.0f, 0.0f, warnings);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_TRUE(contains(warnings[0], "square.exr") && contains(warnings[0], "not 2:1"))
        << warnings[0];
    warnings.clear();
    loadEnvironment(writeMap(dir, "black.exr", 8, 4, std::vector<glm::vec3>(32, glm::vec3(0))),
                    1.0f, 0.0f, warnings);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_TRUE(contains(warnings[0], "black everywhere")) << warnings[0];
    warnings.clear();
    loadEnvironment(writeMap(dir, "lit.exr", 8, 4, std::vector<glm::vec3>(32, glm::vec3(1))), 0.0f,
                    0.0f, warnings);  // intensity 0 blackens it too
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_TRUE(contains(warnings[0], "--env-intensity 0")) << warnings[0];
}

// Wider than kMaxEnvironmentSide: halved (box filter) with a warning; the mean is kept.
TEST(EnvironmentLoad, LargeMapsAreDownsampledKeepingTheirPower) {
    TempFolder dir;
    const uint32_t w = kMaxEnvironmentSide + 2, h = 2;
    std::vector<glm::vec3> texels(size_t(w) * h);
    double sum = 0.0;
    for (size_t k = 0; k < texels.size(); ++k) {
        texels[k] = glm::vec3(float(k % 5));
        sum += k % 5;
    }
    std::vector<std::string> warnings;
    const EnvironmentMap map =
        loadEnvironment(writeMap(dir, "wide.exr", w, h, texels), 1.0f, 0.0f, warnings);
    EXPECT_EQ(map.width, w / 2);
    EXPECT_EQ(map.height, 1u);
    double after = 0.0;
    for (const glm::vec3& c : map.radiance) after += c.r;
    EXPECT_NEAR(after / map.radiance.size(), sum / texels.size(), 1e-4);
    bool named = false;
    for (const auto& warning : warnings) named = named || contains(warning, "downsampled");
    EXPECT_TRUE(named);
}

TEST(EnvironmentLoad, BadFilesNameTheFile) {
    TempFolder dir;
    std::vector<std::string> warnings;
    const fs::path missing = dir / "missing.exr";
    std::string e = inputErrorOf([&] { loadEnvironment(missing, 1.0f, 0.0f, warnings); });
    EXPECT_TRUE(contains(e, missing.string()) && contains(e, "not found")) << e;

    const fs::path empty = dir / "empty.exr";
    std::ofstream(empty).close();
    e = inputErrorOf([&] { loadEnvironment(empty, 1.0f, 0.0f, warnings); });
    EXPECT_TRUE(contains(e, "empty.exr") && contains(e, "empty file")) << e;

    const fs::path text = dir / "notes.exr";
    std::ofstream(text) << "not an image at all\n";
    e = inputErrorOf([&] { loadEnvironment(text, 1.0f, 0.0f, warnings); });
    EXPECT_TRUE(contains(e, "notes.exr")) << e;

    e = inputErrorOf([&] { loadEnvironment(dir / "", 1.0f, 0.0f, warnings); });
    EXPECT_TRUE(contains(e, "not a regular file")) << e;

    std::vector<glm::vec3> texels(32, glm::vec3(1.0f));
    texels[9] = glm::vec3(1.0f, std::numeric_limits<float>::quiet_NaN(), 1.0f);
    e = inputErrorOf(
        [&] { loadEnvironment(writeMap(dir, "nan.exr", 8, 4, texels), 1.0f, 0.0f, warnings); });
    EXPECT_TRUE(contains(e, "nan.exr") && contains(e, "texel (1, 1)")) << e;
    texels[9] = glm::vec3(std::numeric_limits<float>::infinity());
    e = inputErrorOf(
        [&] { loadEnvironment(writeMap(dir, "inf.exr", 8, 4, texels), 1.0f, 0.0f, warnings); });
    EXPECT_TRUE(contains(e, "texel (1, 1)")) << e;
}

// Negative texels (lossy EXRs hold tiny ones): clamped to 0, with a warning naming the lowest.
TEST(EnvironmentLoad, NegativeTexelsAreClampedWithAWarning) {
    TempFolder dir;
    std::vector<glm::vec3> texels(32, glm::vec3(1.0f));
    texels[9] = glm::vec3(0.5f, -0.25f, 0.5f);
    texels[20] = glm::vec3(-1e-6f);
    std::vector<std::string> warnings;
    const EnvironmentMap map =
        loadEnvironment(writeMap(dir, "neg.exr", 8, 4, texels), 2.0f, 0.0f, warnings);
    EXPECT_EQ(map.radiance[9], glm::vec3(1.0f, 0.0f, 1.0f));
    EXPECT_EQ(map.radiance[20], glm::vec3(0.0f));
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_TRUE(contains(warnings[0], "neg.exr") && contains(warnings[0], "2 texel(s)") &&
                contains(warnings[0], "-0.25") && contains(warnings[0], "(1, 1)"))
        << warnings[0];
}

TEST(EnvironmentLoad, BadOptionsNameTheOption) {
    TempFolder dir;
    const fs::path file = writeMap(dir, "sky.exr", 8, 4, std::vector<glm::vec3>(32, glm::vec3(1)));
    std::vector<std::string> warnings;
    std::string e = inputErrorOf([&] { loadEnvironment(file, -1.0f, 0.0f, warnings); });
    EXPECT_TRUE(contains(e, "--env-intensity")) << e;
    e = inputErrorOf(
        [&] { loadEnvironment(file, std::numeric_limits<float>::quiet_NaN(), 0.0f, warnings); });
    EXPECT_TRUE(contains(e, "--env-intensity")) << e;
    e = inputErrorOf(
        [&] { loadEnvironment(file, 1.0f, std::numeric_limits<float>::infinity(), warnings); });
    EXPECT_TRUE(contains(e, "--env-rotation")) << e;
    // A finite intensity that overflows a texel to Inf.
    e = inputErrorOf([&] { loadEnvironment(file, 3e38f, 0.0f, warnings); });
    EXPECT_TRUE(contains(e, "--env-intensity")) << e;
    EXPECT_NO_THROW(loadEnvironment(file, 1.0f, 0.0f, warnings));
}

// readImage refuses images above a pixel budget from the header alone.
TEST(EnvironmentLoad, PixelLimitIsCheckedBeforeReading) {
    TempFolder dir;
    const fs::path file = writeMap(dir, "sky.exr", 8, 4, std::vector<glm::vec3>(32, glm::vec3(1)));
    const std::string e = inputErrorOf([&] { image::readImage(file, 31); });
    EXPECT_TRUE(contains(e, "sky.exr") && contains(e, "8x4")) << e;
    EXPECT_EQ(image::readImage(file, 32).width, 8u);
}
