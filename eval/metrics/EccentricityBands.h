// Error per eccentricity band (seed 003 P5 §5 compares the fovea and the periphery separately):
// every pixel's eccentricity in degrees - the angle between its view ray and its eye's gaze ray,
// from the camera's vertical field of view (as FoveationMask's `degrees`) - and the RMSE of a
// test image against a reference over the pixels of each band, 0-5, 5-20 and 20+ degrees.
#pragma once
#include <cstdint>
#include <limits>
#include <nlohmann/json.hpp>
#include <vector>

#include "core/graph/PassFacts.h"
#include "core/image/ImageIO.h"
#include "core/scene/Camera.h"

namespace fovea::eval {

struct BandError {
    double fromDegrees = 0, toDegrees = 0;  // [from, to); to = +inf for the last band
    uint64_t pixels = 0;
    double rmse = 0;  // sqrt(mean over the band's pixels and R, G, B of the squared difference)
    // Mean of a per-pixel ꟻLIP map over the band's pixels, when one was given; NaN otherwise.
    double flipMean = std::numeric_limits<double>::quiet_NaN();
};

// The bands' lower edges: 0, 5 and 20 degrees (the last band is open).
inline constexpr double kEccentricityBandEdges[] = {0.0, 5.0, 20.0};
// With an equirect (360°) camera: seed 003 P4's foveal region split finer (0-5, 5-10, 10-20
// degrees, issue 27), 20-80 and what lies beyond 80 degrees, where P4's acuity CDF (Eq. 6) puts no
// sample.
inline constexpr double kEquirectBandEdges[] = {0.0, 5.0, 10.0, 20.0, 80.0};

// Eccentricity in degrees of pixel (x, y) of a width x height side-by-side image (eye width =
// width / eyeCount), from `camera`'s yfov and each eye's gaze; with an equirect camera the angle
// on the sphere between the pixel's direction and the gaze direction.
double pixelEccentricityDegrees(const scene::FrameCamera& camera, uint32_t width, uint32_t height,
                                uint32_t x, uint32_t y);

// Pixels per degree of visual angle at the centre of a width x height image (of one eye's part
// of a side-by-side image) seen through `camera`: (height / 2) / tan(yfov / 2) · π / 180 for a
// pinhole, width / 360 for an equirect image. The viewing condition of ꟻLIP for an HMD bench.
double cameraPixelsPerDegree(const scene::FrameCamera& camera, uint32_t width, uint32_t height);

// Per-band RMSE of `test` against `reference` (same size; the caller checks). A band without
// pixels has rmse 0. With `flipMap` (width * height ꟻLIP values): also each band's mean ꟻLIP.
std::vector<BandError> eccentricityBandErrors(const image::ImageRGBA& test,
                                              const image::ImageRGBA& reference,
                                              const scene::FrameCamera& camera,
                                              const std::vector<float>* flipMap = nullptr);

// [{"from", "to" (null = open), "pixels", "rmse", "flip_mean" (when computed)}]
nlohmann::json bandErrorsToJson(const std::vector<BandError>& bands);

// The layers of seed 000 §3.2 (core/graph/PassFacts.h; Peres et al. 2023, Table 1): fovea
// d <= r0, middle r0 < d <= r1, outer d > r1, with d the distance of a pixel centre to its eye's
// gaze point in pixels of the eye image or its eccentricity in degrees - FoveationMask's rule
// (foveation_mask.comp layerOf), so the split of an error into layers is the split the mask
// made. Seed 000 §5 reads the fovea (must match Base) and the periphery (where the loss may be)
// apart.
using LayerRadii = graph::LayerRadii;

inline constexpr const char* kLayerNames[] = {"fovea", "middle", "outer"};

// 0 fovea, 1 middle, 2 outer for pixel (x, y) of a width x height side-by-side image.
uint32_t foveationLayerOf(const scene::FrameCamera& camera, uint32_t width, uint32_t height,
                          uint32_t x, uint32_t y, const LayerRadii& radii);

// Per-layer RMSE of `test` against `reference` (same size; the caller checks): three entries,
// fromDegrees/toDegrees holding the layer's radii in the radii's unit (r1's `to` = +inf). A layer
// without pixels has rmse 0.
std::vector<BandError> foveationLayerErrors(const image::ImageRGBA& test,
                                            const image::ImageRGBA& reference,
                                            const scene::FrameCamera& camera,
                                            const LayerRadii& radii,
                                            const std::vector<float>* flipMap = nullptr);

// [{"layer": "fovea"|"middle"|"outer", "from", "to" (null = open), "unit", "pixels", "rmse",
//   "flip_mean" (when computed)}]
nlohmann::json layerErrorsToJson(const std::vector<BandError>& layers, const LayerRadii& radii);

}  // namespace fovea::eval
