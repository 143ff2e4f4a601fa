#include "eval/metrics/EccentricityBands.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "core/util/Error.h"

namespace fovea::eval {

namespace {
// View-space direction through a point of an eye image (camera.glsl's cameraRay convention).
glm::dvec3 viewDirection(glm::dvec2 local, glm::dvec2 eyeSize, double tanHalf, double aspect) {
    glm::dvec2 ndc(2.0 * local.x / eyeSize.x - 1.0, 1.0 - 2.0 * local.y / eyeSize.y);
    return {ndc.x * tanHalf * aspect, ndc.y * tanHalf, -1.0};
}
}  // namespace

double pixelEccentricityDegrees(const scene::FrameCamera& camera, uint32_t width, uint32_t height,
                                uint32_t x, uint32_t y) {
    if (camera.model == scene::CameraModel::Equirect) {
        const glm::vec2 size(float(std::max(width, 1u)), float(std::max(height, 1u)));
        const glm::dvec3 a = scene::equirectDirection((glm::vec2(x, y) + 0.5f) / size);
        const glm::dvec3 b = scene::equirectDirection(camera.eyes[0].gaze);
        return glm::degrees(std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b)));
    }
    const uint32_t eyes = std::clamp(camera.eyeCount, 1u, scene::kMaxEyes);
    const uint32_t eyeWidth = std::max(width / eyes, 1u);
    const uint32_t eye = std::min(x / eyeWidth, eyes - 1);
    const glm::dvec2 eyeSize(eyeWidth, std::max(height, 1u));
    const double tanHalf = std::tan(0.5 * double(camera.yfov));
    const double aspect = eyeSize.x / eyeSize.y;
    glm::dvec2 local(x + 0.5 - double(eye) * eyeWidth, y + 0.5);
    glm::dvec2 gaze = glm::dvec2(camera.eyes[eye].gaze) * eyeSize;
    glm::dvec3 a = viewDirection(local, eyeSize, tanHalf, aspect);
    glm::dvec3 b = viewDirection(gaze, eyeSize, tanHalf, aspect);
    // atan(|a x b|, a . b): accurate for small angles; a . b >= 1 (z = -1 each).
    return glm::degrees(std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b)));
}

namespace {

// Per-region RMSE (and mean ꟻLIP with a map) over the pixels `regionOf(x, y)` assigns to each of
// `count` regions.
template <class RegionOf>
std::vector<BandError> regionErrors(const image::ImageRGBA& test, const image::ImageRGBA& reference,
                                    const std::vector<float>* flipMap, size_t count,
                                    RegionOf regionOf) {
    std::vector<BandError> regions(count);
    std::vector<double> sum(count, 0.0), flipSum(count, 0.0);
    const uint32_t w = std::min(test.width, reference.width);
    const uint32_t h = std::min(test.height, reference.height);
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            const size_t b = std::min<size_t>(regionOf(x, y), count - 1);
            const float* t = &test.pixels[(size_t(y) * test.width + x) * 4];
            const float* r = &reference.pixels[(size_t(y) * reference.width + x) * 4];
            for (int c = 0; c < 3; ++c) sum[b] += double(t[c] - r[c]) * double(t[c] - r[c]);
            if (flipMap) flipSum[b] += (*flipMap)[size_t(y) * test.width + x];
            ++regions[b].pixels;
        }
    for (size_t b = 0; b < count; ++b) {
        if (regions[b].pixels == 0) continue;  // rmse 0, flipMean NaN: nothing to average
        regions[b].rmse = std::sqrt(sum[b] / (3.0 * regions[b].pixels));
        if (flipMap) regions[b].flipMean = flipSum[b] / double(regions[b].pixels);
    }
    return regions;
}

// The map indexes pixels of the test image: it must hold one value per pixel of both images.
void checkFlipMap(const image::ImageRGBA& test, const image::ImageRGBA& reference,
                  const std::vector<float>* flipMap) {
    if (flipMap && (test.width != reference.width || test.height != reference.height ||
                    flipMap->size() != size_t(test.width) * test.height))
        throw RuntimeError("band errors: the ꟻLIP map does not match the images' size");
}

// {"flip_mean": v} merged into a band's JSON when it was computed.
void addFlip(nlohmann::json& j, const BandError& b) {
    if (!std::isnan(b.flipMean)) j["flip_mean"] = b.flipMean;
}

}  // namespace

double cameraPixelsPerDegree(const scene::FrameCamera& camera, uint32_t width, uint32_t height) {
    if (camera.model == scene::CameraModel::Equirect) return double(std::max(width, 1u)) / 360.0;
    // yfov in (0, π) (the camera is validated): tan > 0.
    const double halfHeight = 0.5 * double(std::max(height, 1u));
    return halfHeight / std::tan(0.5 * double(camera.yfov)) * std::numbers::pi / 180.0;
}

uint32_t foveationLayerOf(const scene::FrameCamera& camera, uint32_t width, uint32_t height,
                          uint32_t x, uint32_t y, const LayerRadii& radii) {
    double d = 0;
    if (radii.degrees) {
        d = pixelEccentricityDegrees(camera, width, height, x, y);
    } else {
        // foveation_mask.comp: local pixel centre against gaze * eye size, in pixels.
        const uint32_t eyes = std::clamp(camera.eyeCount, 1u, scene::kMaxEyes);
        const uint32_t eyeWidth = std::max(width / eyes, 1u);
        const uint32_t eye = std::min(x / eyeWidth, eyes - 1);
        const glm::dvec2 eyeSize(eyeWidth, std::max(height, 1u));
        const glm::dvec2 local(x + 0.5 - double(eye) * eyeWidth, y + 0.5);
        d = glm::length(local - glm::dvec2(camera.eyes[eye].gaze) * eyeSize);
    }
    return d <= radii.r0 ? 0u : (d <= radii.r1 ? 1u : 2u);
}

std::vector<BandError> foveationLayerErrors(const image::ImageRGBA& test,
                                            const image::ImageRGBA& reference,
                                            const scene::FrameCamera& camera,
                                            const LayerRadii& radii,
                                            const std::vector<float>* flipMap) {
    checkFlipMap(test, reference, flipMap);
    const uint32_t w = std::min(test.width, reference.width);
    const uint32_t h = std::min(test.height, reference.height);
    auto layers = regionErrors(test, reference, flipMap, 3, [&](uint32_t x, uint32_t y) {
        return foveationLayerOf(camera, w, h, x, y, radii);
    });
    const double edges[] = {0.0, radii.r0, radii.r1, std::numeric_limits<double>::infinity()};
    for (size_t l = 0; l < layers.size(); ++l) {
        layers[l].fromDegrees = edges[l];
        layers[l].toDegrees = edges[l + 1];
    }
    return layers;
}

std::vector<BandError> eccentricityBandErrors(const image::ImageRGBA& test,
                                              const image::ImageRGBA& reference,
                                              const scene::FrameCamera& camera,
                                              const std::vector<float>* flipMap) {
    checkFlipMap(test, reference, flipMap);
    const bool equirect = camera.model == scene::CameraModel::Equirect;
    const double* edges = equirect ? kEquirectBandEdges : kEccentricityBandEdges;
    const size_t kBands =
        equirect ? std::size(kEquirectBandEdges) : std::size(kEccentricityBandEdges);
    const uint32_t w = std::min(test.width, reference.width);
    const uint32_t h = std::min(test.height, reference.height);
    auto bands = regionErrors(test, reference, flipMap, kBands, [&](uint32_t x, uint32_t y) {
        double e = pixelEccentricityDegrees(camera, w, h, x, y);
        size_t b = kBands - 1;
        while (b > 0 && e < edges[b]) --b;
        return b;
    });
    for (size_t b = 0; b < kBands; ++b) {
        bands[b].fromDegrees = edges[b];
        bands[b].toDegrees =
            b + 1 < kBands ? edges[b + 1] : std::numeric_limits<double>::infinity();
    }
    return bands;
}

nlohmann::json layerErrorsToJson(const std::vector<BandError>& layers, const LayerRadii& radii) {
    nlohmann::json out = nlohmann::json::array();
    for (size_t l = 0; l < layers.size(); ++l)
        out.push_back(
            {{"layer", kLayerNames[std::min<size_t>(l, 2)]},
             {"from", layers[l].fromDegrees},
             {"to", std::isinf(layers[l].toDegrees) ? nlohmann::json(nullptr)
                                                    : nlohmann::json(layers[l].toDegrees)},
             {"unit", radii.degrees ? "degrees" : "pixels"},
             {"pixels", layers[l].pixels},
             {"rmse", layers[l].rmse}});
    for (size_t l = 0; l < layers.size(); ++l) addFlip(out[l], layers[l]);
    return out;
}

nlohmann::json bandErrorsToJson(const std::vector<BandError>& bands) {
    nlohmann::json out = nlohmann::json::array();
    for (const auto& b : bands) {
        out.push_back({{"from", b.fromDegrees},
                       {"to", std::isinf(b.toDegrees) ? nlohmann::json(nullptr)
                                                      : nlohmann::json(b.toDegrees)},
                       {"pixels", b.pixels},
                       {"rmse", b.rmse}});
        addFlip(out.back(), b);
    }
    return out;
}

}  // namespace fovea::eval
