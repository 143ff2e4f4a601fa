#include "core/scene/Environment.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "core/image/ImageIO.h"
#include "core/util/Error.h"
#include "core/util/UserFile.h"

namespace fovea::scene {
namespace {

constexpr double kPi = std::numbers::pi;

std::string formatFloat(double v) {
    char buffer[32];
    std::snprintf(buffer, sizeof(buffer), "%g", v);
    return buffer;
}

// Halves the map (2x2 box; an odd last row or column is averaged with fewer texels) until both
// sides fit kMaxEnvironmentSide. The mean over each block keeps the map's power.
void downsampleToFit(EnvironmentMap& map) {
    while (map.width > kMaxEnvironmentSide || map.height > kMaxEnvironmentSide) {
        const uint32_t w = (map.width + 1) / 2, h = (map.height + 1) / 2;
        std::vector<glm::vec3> out(size_t(w) * h);
        for (uint32_t y = 0; y < h; ++y)
            for (uint32_t x = 0; x < w; ++x) {
                glm::vec3 sum(0.0f);
                int count = 0;
                for (uint32_t dy = 0; dy < 2; ++dy)
                    for (uint32_t dx = 0; dx < 2; ++dx) {
                        const uint32_t sx = 2 * x + dx, sy = 2 * y + dy;
                        if (sx >= map.width || sy >= map.height) continue;
                        sum += map.radiance[size_t(sy) * map.width + sx];
                        ++count;
                    }
                out[size_t(y) * w + x] = sum / float(count);  // count >= 1: (2x, 2y) is inside
            }
        map.radiance = std::move(out);
        map.width = w;
        map.height = h;
    }
}

}  // namespace

EnvironmentMap loadEnvironment(const std::filesystem::path& path, float intensity,
                               float rotationDegrees, std::vector<std::string>& warnings) {
    const std::string file = path.string();
    if (!std::isfinite(intensity) || intensity < 0.0f)
        throw InputError("--env-intensity", "",
                         "must be a finite number >= 0, got " + formatFloat(intensity));
    if (!std::isfinite(rotationDegrees))
        throw InputError("--env-rotation", "", "must be a finite number of degrees");
    if (const std::string problem = regularFileProblem(path); !problem.empty())
        throw InputError(file, "",
                         problem == "file not found"
                             ? "environment map not found"
                             : "environment map is not a regular file (" + problem + ")");
    std::error_code ec;
    if (std::filesystem::file_size(path, ec) == 0)
        throw InputError(file, "", "environment map is an empty file");
    // readImage: InputError naming the file for anything it cannot read or decode, and
    // for more than kMaxEnvironmentPixels before any pixel is allocated.
    const image::ImageRGBA image = image::readImage(path, kMaxEnvironmentPixels);

    EnvironmentMap map;
    map.source = file;
    map.width = image.width;
    map.height = image.height;
    map.intensity = intensity;
    map.rotation = float(rotationDegrees * kPi / 180.0);
    map.radiance.resize(size_t(image.width) * image.height);
    bool anyLight = false;
    // Real HDRIs hold tiny negative values (lossy EXR compression, e.g. -4.5e-6 in blender-data's
    // forest.exr): clamped to 0 with a warning, as the picture is still defined. NaN and Inf are
    // not: an error naming the first such texel.
    size_t negatives = 0;
    float lowest = 0.0f;
    size_t lowestAt = 0;
    for (size_t i = 0; i < map.radiance.size(); ++i) {
        glm::vec3 c(image.pixels[4 * i], image.pixels[4 * i + 1], image.pixels[4 * i + 2]);
        const auto texel = [&] {
            return "texel (" + std::to_string(i % image.width) + ", " +
                   std::to_string(i / image.width) + ")";
        };
        if (!std::isfinite(c.r) || !std::isfinite(c.g) || !std::isfinite(c.b))
            throw InputError(file, "",
                             texel() + " is " + formatFloat(c.r) + ", " + formatFloat(c.g) + ", " +
                                 formatFloat(c.b) + ": environment radiance must be finite");
        const float low = std::min(c.r, std::min(c.g, c.b));
        if (low < 0.0f) {
            if (low < lowest) lowest = low, lowestAt = i;
            ++negatives;
            c = glm::max(c, glm::vec3(0.0f));
        }
        map.radiance[i] = c * intensity;
        // A finite texel times a finite intensity can still overflow to Inf.
        if (!std::isfinite(map.radiance[i].r + map.radiance[i].g + map.radiance[i].b))
            throw InputError("--env-intensity", "",
                             formatFloat(intensity) + " times " + texel() + " of " + file +
                                 " overflows a float");
        anyLight = anyLight || map.radiance[i] != glm::vec3(0.0f);
    }
    if (negatives > 0)
        warnings.push_back(file + ": " + std::to_string(negatives) +
                           " texel(s) with negative values (lowest " + formatFloat(lowest) +
                           " at texel (" + std::to_string(lowestAt % image.width) + ", " +
                           std::to_string(lowestAt / image.width) + ")) clamped to 0");
    const std::string ext = path.extension().string();
    if (ext != ".exr" && ext != ".EXR" && ext != ".hdr" && ext != ".HDR")
        warnings.push_back(file +
                           ": not an EXR or Radiance .hdr file; its values are read as linear "
                           "radiance (an 8-bit sRGB image is not decoded)");
    if (image.width != 2 * image.height)
        warnings.push_back(file + ": environment map is " + std::to_string(image.width) + "x" +
                           std::to_string(image.height) +
                           ", not 2:1; it is stretched over the sphere as an equirectangular "
                           "(latitude-longitude) map");
    downsampleToFit(map);
    if (map.width != image.width)
        warnings.push_back(file + ": environment map downsampled from " +
                           std::to_string(image.width) + "x" + std::to_string(image.height) +
                           " to " + std::to_string(map.width) + "x" + std::to_string(map.height) +
                           " (at most " + std::to_string(kMaxEnvironmentSide) + " texels a side)");
    if (!anyLight)
        warnings.push_back(file + ": environment map" +
                           (intensity == 0.0f ? " (with --env-intensity 0)" : "") +
                           " is black everywhere: it lights nothing and the background stays "
                           "black");
    return map;
}

EnvironmentMap constantEnvironment(const glm::vec3& radiance, uint32_t width, uint32_t height) {
    EnvironmentMap map;
    map.source = "constant";
    map.width = std::max(width, 1u);
    map.height = std::max(height, 1u);
    map.radiance.assign(size_t(map.width) * map.height, radiance);
    return map;
}

glm::vec2 environmentUv(const glm::vec3& dir, float rotation) {
    const float len = glm::length(dir);
    if (!(len > 0.0f) || !std::isfinite(len)) return {0.5f, 0.0f};
    const glm::vec3 d = dir / len;  // len > 0
    const float theta = std::acos(std::clamp(d.y, -1.0f, 1.0f));
    const float phi = d.x == 0.0f && d.z == 0.0f ? 0.0f : std::atan2(d.z, d.x);
    float u = 0.5f + (phi + rotation) / float(2.0 * kPi);
    u -= std::floor(u);
    return {std::min(u, 0.99999994f), std::min(theta / float(kPi), 0.99999994f)};
}

glm::vec3 environmentDirection(const glm::vec2& uv, float rotation) {
    const double phi = 2.0 * kPi * (double(uv.x) - 0.5) - rotation;
    const double theta = kPi * double(uv.y);
    return glm::vec3(float(std::sin(theta) * std::cos(phi)), float(std::cos(theta)),
                     float(std::sin(theta) * std::sin(phi)));
}

glm::vec3 environmentRadiance(const EnvironmentMap& map, const glm::vec3& dir) {
    if (map.width == 0 || map.height == 0) return glm::vec3(0.0f);
    const glm::vec2 uv = environmentUv(dir, map.rotation);
    const uint32_t i = std::min(uint32_t(uv.x * float(map.width)), map.width - 1);
    const uint32_t j = std::min(uint32_t(uv.y * float(map.height)), map.height - 1);
    return map.radiance[size_t(j) * map.width + i];
}

EnvironmentDistribution::EnvironmentDistribution(const EnvironmentMap& map)
    : mWidth(map.width), mHeight(map.height), mRotation(map.rotation) {
    const size_t n = size_t(map.width) * map.height;
    if (n == 0 || map.radiance.size() != n) return;
    std::vector<double> weights(n), rowWeights(map.height, 0.0);
    for (uint32_t j = 0; j < map.height; ++j) {
        // sin theta at the row centre: the row's share of the sphere (pbrt-v3 §14.2.4).
        const double sinTheta = std::sin(kPi * (j + 0.5) / map.height);
        // The row's exact solid angle per texel: (2 pi / W) (cos theta_top - cos theta_bottom).
        const double texelSolidAngle =
            2.0 * kPi / map.width *
            (std::cos(kPi * j / map.height) - std::cos(kPi * (j + 1.0) / map.height));
        for (uint32_t i = 0; i < map.width; ++i) {
            const size_t k = size_t(j) * map.width + i;
            const double lum = std::max(0.0, LightTable::luminance(glm::dvec3(map.radiance[k])));
            weights[k] = lum * sinTheta;
            rowWeights[j] += weights[k];
            mLuminanceIntegral += lum * texelSolidAngle;
        }
    }
    mRows = buildAliasTable(rowWeights);
    if (mRows.empty()) {  // black (or every texel at a pole row of sin 0: impossible, j + 0.5)
        mLuminanceIntegral = 0.0;
        return;
    }
    double sum = 0.0;
    for (double w : rowWeights) sum += w;
    mTexelProbability.resize(n);
    for (size_t k = 0; k < n; ++k) mTexelProbability[k] = weights[k] / sum;  // sum > 0: alias
    mColumns.resize(n);
    for (uint32_t j = 0; j < map.height; ++j) {
        const auto first = weights.begin() + ptrdiff_t(size_t(j) * map.width);
        std::vector<AliasSlot> row = buildAliasTable(std::vector<double>(first, first + map.width));
        if (row.empty()) row.assign(map.width, AliasSlot{});  // never drawn: P(row) = 0
        std::copy(row.begin(), row.end(), mColumns.begin() + ptrdiff_t(size_t(j) * map.width));
    }
}

uint32_t EnvironmentDistribution::sampleTexel(const glm::vec4& u) const {
    if (empty()) return 0;
    auto draw = [](const AliasSlot* table, uint32_t n, float slot, float coin) {
        const uint32_t s = std::min(uint32_t(slot * float(n)), n - 1);
        return coin < float(table[s].prob) ? s : table[s].alias;
    };
    const uint32_t j = draw(mRows.data(), mHeight, u.x, u.y);
    const uint32_t i = draw(mColumns.data() + size_t(j) * mWidth, mWidth, u.z, u.w);
    return j * mWidth + i;
}

double EnvironmentDistribution::pdf(const glm::vec3& dir) const {
    if (empty()) return 0.0;
    const glm::vec2 uv = environmentUv(dir, mRotation);
    const uint32_t i = std::min(uint32_t(uv.x * mWidth), mWidth - 1);
    const uint32_t j = std::min(uint32_t(uv.y * mHeight), mHeight - 1);
    const double sinTheta = std::sin(kPi * double(uv.y));
    if (!(sinTheta > 0.0)) return 0.0;
    return mTexelProbability[size_t(j) * mWidth + i] * mWidth * mHeight /
           (2.0 * kPi * kPi * sinTheta);
}

double EnvironmentDistribution::power(double sceneRadius) const {
    const double r = std::isfinite(sceneRadius) && sceneRadius > 0.0 ? sceneRadius : 1.0;
    return kPi * r * r * mLuminanceIntegral;
}

}  // namespace fovea::scene
