#include "eval/metrics/ImageMetrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>

#include "core/util/Error.h"

namespace fovea::eval {

namespace {

// Wang et al. 2004 §III-C: 11x11 circular-symmetric Gaussian, sigma 1.5, K1 = 0.01, K2 = 0.03.
constexpr int kSsimWindow = 11;
constexpr double kSsimSigma = 1.5;
constexpr double kSsimK1 = 0.01;
constexpr double kSsimK2 = 0.03;

std::string sizeText(const image::ImageRGBA& image) {
    return std::to_string(image.width) + "x" + std::to_string(image.height);
}

void checkPixelCount(const image::ImageRGBA& image, const std::string& name) {
    if (image.pixels.size() != size_t(image.width) * image.height * 4)
        throw InputError(name + ": holds " + std::to_string(image.pixels.size()) +
                         " values, expected " + sizeText(image) + " x 4");
}

void checkPair(const image::ImageRGBA& a, const image::ImageRGBA& b, const std::string& nameA,
               const std::string& nameB) {
    checkPixelCount(a, nameA);
    checkPixelCount(b, nameB);
    checkSameSize(a, b, nameA, nameB);
    if (a.width == 0 || a.height == 0)
        throw InputError(nameA + " and " + nameB + ": the images are empty (" + sizeText(a) + ")");
    checkFinite(a, nameA);
    checkFinite(b, nameB);
}

// Normalized 1-D Gaussian of odd length n (the 2-D window is its outer product: separable).
std::vector<double> gaussianWindow(int n) {
    std::vector<double> w(static_cast<size_t>(n));
    double sum = 0;
    for (int i = 0; i < n; ++i) {
        double d = i - (n - 1) / 2.0;
        w[size_t(i)] = std::exp(-d * d / (2 * kSsimSigma * kSsimSigma));
        sum += w[size_t(i)];
    }
    for (double& v : w) v /= sum;  // sum >= 1 (the centre tap is exp(0) = 1)
    return w;
}

// The largest odd window <= 11 that fits in `extent` (>= 1) pixels.
int windowFor(uint32_t extent) {
    int n = int(std::min<uint32_t>(extent, kSsimWindow));
    return n % 2 ? n : n - 1;
}

}  // namespace

void checkFinite(const image::ImageRGBA& image, const std::string& name) {
    static const char* kChannel[3] = {"R", "G", "B"};
    for (uint32_t y = 0; y < image.height; ++y)
        for (uint32_t x = 0; x < image.width; ++x)
            for (int c = 0; c < 3; ++c) {
                float v = image.pixels[(size_t(y) * image.width + x) * 4 + size_t(c)];
                if (!std::isfinite(v))
                    throw InputError(name + ": pixel (" + std::to_string(x) + ", " +
                                     std::to_string(y) + ") channel " + kChannel[c] + " is " +
                                     (std::isnan(v) ? "NaN"
                                      : v > 0       ? "+Inf"
                                                    : "-Inf") +
                                     " (error metrics need finite values)");
            }
}

void checkSameSize(image::ImageSize a, image::ImageSize b, const std::string& nameA,
                   const std::string& nameB) {
    auto text = [](image::ImageSize s) {
        return std::to_string(s.width) + "x" + std::to_string(s.height);
    };
    if (a.width != b.width || a.height != b.height)
        throw InputError(nameA + " is " + text(a) + " but " + nameB + " is " + text(b) +
                         ": images of different sizes cannot be compared");
}

void checkSameSize(const image::ImageRGBA& a, const image::ImageRGBA& b, const std::string& nameA,
                   const std::string& nameB) {
    checkSameSize(image::ImageSize{a.width, a.height}, image::ImageSize{b.width, b.height}, nameA,
                  nameB);
}

double ssimPlane(const std::vector<double>& x, const std::vector<double>& y, uint32_t width,
                 uint32_t height, double range) {
    if (width == 0 || height == 0) return 1.0;
    const int nx = windowFor(width), ny = windowFor(height);
    const std::vector<double> wx = gaussianWindow(nx), wy = gaussianWindow(ny);
    const size_t outW = width - uint32_t(nx) + 1, outH = height - uint32_t(ny) + 1;
    const double c1 = (kSsimK1 * range) * (kSsimK1 * range);
    const double c2 = (kSsimK2 * range) * (kSsimK2 * range);

    // Horizontal pass: windowed sums of x, y, x^2, y^2, xy for every row ('valid' columns).
    enum { kX, kY, kXX, kYY, kXY, kMoments };
    std::vector<double> rows[kMoments];
    for (auto& r : rows) r.assign(outW * height, 0.0);
    for (size_t row = 0; row < height; ++row)
        for (size_t col = 0; col < outW; ++col) {
            double s[kMoments] = {};
            for (int k = 0; k < nx; ++k) {
                const size_t i = row * width + col + size_t(k);
                const double w = wx[size_t(k)], a = x[i], b = y[i];
                s[kX] += w * a;
                s[kY] += w * b;
                s[kXX] += w * a * a;
                s[kYY] += w * b * b;
                s[kXY] += w * a * b;
            }
            for (int m = 0; m < kMoments; ++m) rows[m][row * outW + col] = s[m];
        }
    // Vertical pass, one output row at a time (row-wise sums vectorize), then Eq. 13 per window.
    double sum = 0;
    std::vector<double> acc[kMoments];
    for (auto& a : acc) a.resize(outW);
    for (size_t row = 0; row < outH; ++row) {
        for (auto& a : acc) std::fill(a.begin(), a.end(), 0.0);
        for (int k = 0; k < ny; ++k) {
            const double w = wy[size_t(k)];
            for (int m = 0; m < kMoments; ++m) {
                const double* src = &rows[m][(row + size_t(k)) * outW];
                double* dst = acc[m].data();
                for (size_t col = 0; col < outW; ++col) dst[col] += w * src[col];
            }
        }
        for (size_t col = 0; col < outW; ++col) {
            const double mx = acc[kX][col], my = acc[kY][col];
            // E[x^2] - mu^2 can round slightly below 0 on flat windows: clamp the variances.
            const double vx = std::max(0.0, acc[kXX][col] - mx * mx);
            const double vy = std::max(0.0, acc[kYY][col] - my * my);
            const double cxy = acc[kXY][col] - mx * my;
            // Denominator >= c1 * c2 > 0 for range > 0.
            sum +=
                (2 * mx * my + c1) * (2 * cxy + c2) / ((mx * mx + my * my + c1) * (vx + vy + c2));
        }
    }
    return sum / double(outW * outH);  // outW, outH >= 1
}

ImageMetrics computeMetrics(const image::ImageRGBA& test, const image::ImageRGBA& reference,
                            const MetricOptions& options, const std::string& testName,
                            const std::string& referenceName) {
    if (!(options.peak > 0) || !std::isfinite(options.peak))
        throw InputError("metric peak must be a positive number");
    if (!(options.relMseEpsilon > 0) || !std::isfinite(options.relMseEpsilon))
        throw InputError("relMSE epsilon must be a positive number");
    checkPair(test, reference, testName, referenceName);

    ImageMetrics m;
    m.width = test.width;
    m.height = test.height;
    const size_t pixels = size_t(test.width) * test.height;
    std::vector<double> planeX[3], planeY[3];
    for (int c = 0; c < 3; ++c) {
        planeX[c].resize(pixels);
        planeY[c].resize(pixels);
    }
    double sumSq = 0, sumRel = 0, sumLum = 0;
    for (size_t p = 0; p < pixels; ++p) {
        double a[3], b[3];
        for (int c = 0; c < 3; ++c) {
            a[c] = planeX[c][p] = test.pixels[p * 4 + size_t(c)];
            b[c] = planeY[c][p] = reference.pixels[p * 4 + size_t(c)];
            const double d = a[c] - b[c];
            sumSq += d * d;
            sumRel += d * d / (b[c] * b[c] + options.relMseEpsilon);  // eps > 0 (checked)
        }
        sumLum += std::abs(luminance(a[0], a[1], a[2]) - luminance(b[0], b[1], b[2]));
    }
    const double samples = double(pixels) * 3;  // pixels >= 1 (checkPair)
    m.mse = sumSq / samples;
    m.rmse = std::sqrt(m.mse);
    m.rmsePercent = 100.0 * m.rmse / options.peak;
    m.relMse = sumRel / samples;
    m.psnr = m.mse > 0 ? 10.0 * std::log10(options.peak * options.peak / m.mse)
                       : std::numeric_limits<double>::infinity();
    m.meanAbsLuminanceDiff = sumLum / double(pixels);
    double ssim = 0;
    for (int c = 0; c < 3; ++c)
        ssim += ssimPlane(planeX[c], planeY[c], test.width, test.height, options.peak);
    m.ssim = ssim / 3.0;
    return m;
}

nlohmann::json metricsToJson(const ImageMetrics& m, const MetricOptions& options) {
    nlohmann::json j;
    j["mse"] = m.mse;
    j["rmse"] = m.rmse;
    j["rmse_percent"] = m.rmsePercent;
    j["rel_mse"] = m.relMse;
    j["rel_mse_epsilon"] = options.relMseEpsilon;
    // JSON has no infinity: identical images (PSNR = +inf) give null.
    j["psnr_db"] = std::isfinite(m.psnr) ? nlohmann::json(m.psnr) : nlohmann::json(nullptr);
    j["peak"] = options.peak;
    j["ssim"] = m.ssim;
    j["temporal_error"] = m.meanAbsLuminanceDiff;
    if (!std::isnan(m.flipMean)) j["flip_mean"] = m.flipMean;
    return j;
}

ImageMetrics metricsFromJson(const nlohmann::json& j) {
    ImageMetrics m;
    m.mse = j.at("mse").get<double>();
    m.rmse = j.at("rmse").get<double>();
    m.rmsePercent = j.at("rmse_percent").get<double>();
    m.relMse = j.at("rel_mse").get<double>();
    const auto& psnr = j.at("psnr_db");
    m.psnr = psnr.is_null() ? std::numeric_limits<double>::infinity() : psnr.get<double>();
    m.ssim = j.at("ssim").get<double>();
    m.meanAbsLuminanceDiff = j.at("temporal_error").get<double>();
    if (j.contains("flip_mean")) m.flipMean = j["flip_mean"].get<double>();
    return m;
}

double temporalError(const image::ImageRGBA& previous, const image::ImageRGBA& current,
                     const std::string& previousName, const std::string& currentName) {
    checkPair(previous, current, previousName, currentName);
    const size_t pixels = size_t(current.width) * current.height;
    double sum = 0;
    for (size_t p = 0; p < pixels; ++p) {
        const float* a = &current.pixels[p * 4];
        const float* b = &previous.pixels[p * 4];
        sum += std::abs(luminance(a[0], a[1], a[2]) - luminance(b[0], b[1], b[2]));
    }
    return sum / double(pixels);  // pixels >= 1 (checkPair)
}

double temporalError(const std::vector<image::ImageRGBA>& frames) {
    if (frames.size() < 2) return 0.0;
    double sum = 0;
    for (size_t i = 1; i < frames.size(); ++i)
        sum += temporalError(frames[i - 1], frames[i], "frame " + std::to_string(i - 1),
                             "frame " + std::to_string(i));
    return sum / double(frames.size() - 1);
}

double noiseCorrectedRmse(double mse, double floorMse) {
    return std::sqrt(std::max(0.0, mse - 0.5 * floorMse));
}

std::vector<bool> paretoOptimal(const std::vector<double>& cost, const std::vector<double>& error) {
    const size_t n = std::min(cost.size(), error.size());
    std::vector<bool> optimal(n, false);
    auto valid = [&](size_t i) { return !std::isnan(cost[i]) && !std::isnan(error[i]); };
    for (size_t i = 0; i < n; ++i) {
        if (!valid(i)) continue;
        bool dominated = false;
        for (size_t j = 0; j < n && !dominated; ++j)
            dominated = j != i && valid(j) && cost[j] <= cost[i] && error[j] <= error[i] &&
                        (cost[j] < cost[i] || error[j] < error[i]);
        optimal[i] = !dominated;
    }
    return optimal;
}

}  // namespace fovea::eval
