// Error metrics of a rendered image against a reference (docs/metrics.md): RMSE, RMSE %, relMSE,
// PSNR, SSIM, and the temporal error of consecutive frames. Used by `fovea compare` and by the
// per-frame error figures of `run --reference` / `bench`. compareImages (ImageCompare.h) stays
// the golden-test check; these are the figures the papers report.
#pragma once
#include <limits>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

#include "core/image/ImageIO.h"

namespace fovea::eval {

struct MetricOptions {
    // Signal peak: the PSNR numerator and the SSIM dynamic range L (Wang et al. 2004 Eq. 7).
    // 1.0 for images in [0,1]; HDR values above it are not clamped (docs/metrics.md).
    double peak = 1.0;
    // relMSE = (x - y)^2 / (y^2 + eps): eps keeps dark reference pixels from dominating.
    double relMseEpsilon = 1e-2;
};

// Every figure of `test` against `reference`, over the RGB channels (alpha is ignored).
struct ImageMetrics {
    uint32_t width = 0, height = 0;
    double mse = 0;          // mean over pixels and RGB channels of (x - y)^2
    double rmse = 0;         // sqrt(mse)
    double rmsePercent = 0;  // 100 * rmse / peak (Peres et al. Table 4 "RMSE (%)")
    double relMse = 0;       // mean of (x - y)^2 / (y^2 + eps)
    double psnr = 0;         // dB, 10 log10(peak^2 / mse); +infinity when mse == 0
    double ssim = 0;         // mean SSIM of the R, G and B channels
    // Mean |Y(test) - Y(reference)| (Rec. 709 luminance): the temporal error when the two
    // images are consecutive frames (reference = the earlier one).
    double meanAbsLuminanceDiff = 0;
    // Mean ꟻLIP (eval/flip/Flip.h) when it was computed (computeMetrics does not: the caller
    // chooses LDR or HDR and the viewing distance), NaN otherwise.
    double flipMean = std::numeric_limits<double>::quiet_NaN();
};

// Throws InputError naming the images when their sizes differ or an RGB value is NaN/Inf.
ImageMetrics computeMetrics(const image::ImageRGBA& test, const image::ImageRGBA& reference,
                            const MetricOptions& options = {},
                            const std::string& testName = "test image",
                            const std::string& referenceName = "reference image");

// The metrics as JSON (keys of docs/metrics.md, as `fovea compare --json` prints them):
// mse, rmse, rmse_percent, rel_mse, rel_mse_epsilon, psnr_db (null when infinite), peak, ssim,
// temporal_error, and flip_mean when metrics.flipMean is a number. For report.json / bench.json
// too, so every tool uses the same keys.
nlohmann::json metricsToJson(const ImageMetrics& metrics, const MetricOptions& options);
// The inverse for the figures (a saved result read back, e.g. a bench item's): psnr_db null is
// +infinity, a missing flip_mean NaN; width and height stay 0 (not in the JSON). Throws
// nlohmann's type_error when a figure is not a number.
ImageMetrics metricsFromJson(const nlohmann::json& metrics);

// Throws InputError "<name>: pixel (x, y) channel G is NaN" at the first non-finite RGB value.
void checkFinite(const image::ImageRGBA& image, const std::string& name);
// Throws InputError naming both images and their sizes when they differ.
// The same check on header sizes (image::readImageSize), before anything is decoded.
void checkSameSize(image::ImageSize a, image::ImageSize b, const std::string& nameA,
                   const std::string& nameB);
void checkSameSize(const image::ImageRGBA& a, const image::ImageRGBA& b, const std::string& nameA,
                   const std::string& nameB);

// Rec. 709 / sRGB primaries luminance of linear RGB.
inline double luminance(double r, double g, double b) {
    return 0.2126 * r + 0.7152 * g + 0.0722 * b;
}

// SSIM of one channel plane (width * height values, row-major), Wang et al. 2004: Gaussian
// window 11x11, sigma 1.5, K1 = 0.01, K2 = 0.03, dynamic range `range`; mean over the windows
// that lie entirely inside the image. An axis shorter than 11 px uses the largest odd window
// that fits (same sigma, renormalized). Inputs must be finite (no check here).
double ssimPlane(const std::vector<double>& x, const std::vector<double>& y, uint32_t width,
                 uint32_t height, double range = 1.0);

// Temporal error of two consecutive frames (Schied et al. 2017, as used in seed 003 P2 §7.1):
// mean over pixels of |Y(current) - Y(previous)|. Checks sizes and finiteness like
// computeMetrics.
double temporalError(const image::ImageRGBA& previous, const image::ImageRGBA& current,
                     const std::string& previousName = "previous frame",
                     const std::string& currentName = "current frame");
// Mean of temporalError over the consecutive pairs of `frames` (0 for fewer than two frames).
double temporalError(const std::vector<image::ImageRGBA>& frames);

// The reference's noise floor (docs/benchmarks.md, "the paper's protocol"). Two references R1,
// R2 of one scene rendered with different seeds are truth + n1 and truth + n2 with independent
// noise of equal variance, so E|R2 - R1|^2 = 2 E|n|^2 (`floorMse`, the MSE between them). A test
// image T independent of n1 has E|T - R1|^2 = E|T - truth|^2 + E|n1|^2: its error against the
// truth is sqrt(max(0, mse - floorMse / 2)). 0 when the measured error lies within the
// reference's own noise (the figure cannot be resolved with that reference).
double noiseCorrectedRmse(double mse, double floorMse);

// Pareto-optimal points of (cost, error) pairs, both smaller = better: true where no other point
// is at least as good in both and strictly better in one. Equal points are all optimal. NaN
// points are never optimal and dominate nothing.
std::vector<bool> paretoOptimal(const std::vector<double>& cost, const std::vector<double>& error);

}  // namespace fovea::eval
