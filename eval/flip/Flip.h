// ꟻLIP, the image difference evaluator real-time rendering papers report next to RMSE and SSIM:
// LDR-ꟻLIP (Andersson, Nilsson, Akenine-Möller, Oskarsson, Åström and Fairchild 2020, "FLIP: A
// Difference Evaluator for Alternating Images", HPG) for display-encoded images and HDR-ꟻLIP
// (Andersson, Nilsson, Shirley and Akenine-Möller 2021, "Visualizing Errors in Rendered High
// Dynamic Range Images", Eurographics short papers) for linear ones. Implemented from the papers;
// docs/metrics.md "ꟻLIP" gives the equations, the viewing conditions and where the figures can
// differ from the authors' reference implementation.
#pragma once
#include <cstdint>
#include <filesystem>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/image/ImageIO.h"

namespace fovea::eval {

// Pixels per degree of visual angle of a display `displayWidthPixels` wide and
// `displayWidthMeters` wide, seen from `distanceMeters`: FLIP's viewing condition,
// d · (pixels / width) · π / 180 (the small-angle pixel size at the screen's centre).
double pixelsPerDegree(double distanceMeters, double displayWidthMeters, double displayWidthPixels);

// FLIP's default observer: a 0.7 m wide 3840-pixel monitor seen from 0.7 m, 67.02 ppd.
inline constexpr double kFlipDefaultDistanceMeters = 0.7;
inline constexpr double kFlipDefaultDisplayWidthMeters = 0.7;
inline constexpr double kFlipDefaultDisplayWidthPixels = 3840.0;
double defaultPixelsPerDegree();

enum class FlipMode {
    Ldr,  // LDR-ꟻLIP: values are display-encoded sRGB in [0,1] (PNG, JPEG); clamped to [0,1]
    Hdr,  // HDR-ꟻLIP: values are linear radiance (EXR, HDR); negatives clamped to 0
};
const char* flipModeName(FlipMode mode);  // "ldr" | "hdr"
// The mode the authors' tool picks for a file: HDR for .exr and .hdr, LDR for any other.
FlipMode flipModeForFile(const std::filesystem::path& file);

struct FlipOptions {
    FlipMode mode = FlipMode::Hdr;
    double pixelsPerDegree = 0;  // 0: defaultPixelsPerDegree()
    // HDR-ꟻLIP's exposure range in stops; unset: from the reference image (start: its
    // brightest pixel reaches t = 0.85 after tone mapping, stop: its median does).
    std::optional<double> startExposure, stopExposure;
};

struct FlipResult {
    uint32_t width = 0, height = 0;
    std::vector<float> errors;  // per pixel, row-major, in [0,1]
    double mean = 0;            // mean of errors: "mean ꟻLIP", the figure papers report
    FlipMode mode = FlipMode::Hdr;
    double pixelsPerDegree = 0;
    // HDR only: the exposures evaluated, start + i (stop - start) / (count - 1).
    double startExposure = 0, stopExposure = 0;
    uint32_t exposureCount = 0;
};

// ꟻLIP of `test` against `reference` (RGB; alpha ignored). Throws InputError naming the images
// when their sizes differ, an image is empty or a value is NaN/Inf, and when the options are
// out of range (pixels per degree not finite and positive; start exposure after stop exposure).
FlipResult computeFlip(const image::ImageRGBA& test, const image::ImageRGBA& reference,
                       const FlipOptions& options, const std::string& testName = "test image",
                       const std::string& referenceName = "reference image");

// The error map as an image: the error in R, G and B (grey, 0 = identical, 1 = the largest
// difference ꟻLIP measures), alpha 1, so an EXR map reads back as the per-pixel values.
image::ImageRGBA flipMapImage(const FlipResult& result);

// How ꟻLIP was evaluated: {"mode": "ldr"|"hdr", "pixels_per_degree"} and for HDR
// "start_exposure", "stop_exposure", "exposures" (report.json, bench.json, compare --json).
nlohmann::json flipSettingsToJson(const FlipResult& result);

}  // namespace fovea::eval
