// Error metrics (eval/metrics/ImageMetrics.h) on images with known answers, and SSIM against an
// independent direct-window implementation written here from Wang et al. 2004 Eqs. 14-16.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <nlohmann/json.hpp>
#include <random>

#include "core/util/Error.h"
#include "eval/metrics/ImageMetrics.h"

using namespace fovea::image;
using namespace fovea::eval;

namespace {

ImageRGBA constantImage(uint32_t w, uint32_t h, float r, float g, float b, float a = 1.0f) {
    ImageRGBA img;
    img.width = w;
    img.height = h;
    img.pixels.resize(size_t(w) * h * 4);
    for (size_t p = 0; p < size_t(w) * h; ++p) {
        img.pixels[p * 4 + 0] = r;
        img.pixels[p * 4 + 1] = g;
        img.pixels[p * 4 + 2] = b;
        img.pixels[p * 4 + 3] = a;
    }
    return img;
}

ImageRGBA randomImage(uint32_t w, uint32_t h, unsigned seed, float lo = 0.0f, float hi = 1.0f) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> dist(lo, hi);
    ImageRGBA img = constantImage(w, h, 0, 0, 0);
    for (size_t p = 0; p < size_t(w) * h; ++p)
        for (int c = 0; c < 3; ++c) img.pixels[p * 4 + size_t(c)] = dist(rng);
    return img;
}

// Straightforward SSIM: for every window centre with the 11x11 window inside the image, the 2-D
// Gaussian weights are built explicitly and the moments taken as weighted sums of deviations
// (Wang et al. 2004 Eqs. 14-16), then Eq. 13, then the mean (Eq. 17). Channel c of RGBA images.
double referenceSsim(const ImageRGBA& a, const ImageRGBA& b, int c, double range = 1.0) {
    const int n = 11, half = 5;
    double weight[11][11], total = 0;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            double dx = i - half, dy = j - half;
            weight[j][i] = std::exp(-(dx * dx + dy * dy) / (2 * 1.5 * 1.5));
            total += weight[j][i];
        }
    const double c1 = std::pow(0.01 * range, 2), c2 = std::pow(0.03 * range, 2);
    auto at = [&](const ImageRGBA& img, int x, int y) {
        return double(img.pixels[(size_t(y) * img.width + size_t(x)) * 4 + size_t(c)]);
    };
    double sum = 0;
    int count = 0;
    for (int y = half; y + half < int(a.height); ++y)
        for (int x = half; x + half < int(a.width); ++x) {
            double mx = 0, my = 0;
            for (int j = 0; j < n; ++j)
                for (int i = 0; i < n; ++i) {
                    double w = weight[j][i] / total;
                    mx += w * at(a, x - half + i, y - half + j);
                    my += w * at(b, x - half + i, y - half + j);
                }
            double vx = 0, vy = 0, cxy = 0;
            for (int j = 0; j < n; ++j)
                for (int i = 0; i < n; ++i) {
                    double w = weight[j][i] / total;
                    double dx = at(a, x - half + i, y - half + j) - mx;
                    double dy = at(b, x - half + i, y - half + j) - my;
                    vx += w * dx * dx;
                    vy += w * dy * dy;
                    cxy += w * dx * dy;
                }
            sum +=
                (2 * mx * my + c1) * (2 * cxy + c2) / ((mx * mx + my * my + c1) * (vx + vy + c2));
            ++count;
        }
    return sum / count;
}

double referenceSsimRgb(const ImageRGBA& a, const ImageRGBA& b, double range = 1.0) {
    return (referenceSsim(a, b, 0, range) + referenceSsim(a, b, 1, range) +
            referenceSsim(a, b, 2, range)) /
           3.0;
}

std::string inputErrorMessage(const std::function<void()>& f) {
    try {
        f();
    } catch (const fovea::InputError& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(ImageMetrics, IdenticalImagesHaveZeroErrorInfinitePsnrUnitSsim) {
    ImageRGBA a = randomImage(32, 24, 1);
    ImageMetrics m = computeMetrics(a, a);
    EXPECT_EQ(m.width, 32u);
    EXPECT_EQ(m.height, 24u);
    EXPECT_EQ(m.mse, 0.0);
    EXPECT_EQ(m.rmse, 0.0);
    EXPECT_EQ(m.rmsePercent, 0.0);
    EXPECT_EQ(m.relMse, 0.0);
    EXPECT_TRUE(std::isinf(m.psnr) && m.psnr > 0) << m.psnr;
    EXPECT_NEAR(m.ssim, 1.0, 1e-12);
    EXPECT_EQ(m.meanAbsLuminanceDiff, 0.0);
}

TEST(ImageMetrics, ConstantOffsetGivesKnownRmsePsnrRelMse) {
    const float base = 0.25f, offset = 0.0625f;  // exact in float
    ImageRGBA ref = constantImage(20, 16, base, base, base);
    ImageRGBA test = constantImage(20, 16, base + offset, base + offset, base + offset);
    ImageMetrics m = computeMetrics(test, ref);
    EXPECT_NEAR(m.rmse, offset, 1e-12);
    EXPECT_NEAR(m.mse, offset * offset, 1e-12);
    EXPECT_NEAR(m.rmsePercent, 100.0 * offset, 1e-9);
    EXPECT_NEAR(m.psnr, 20.0 * std::log10(1.0 / offset), 1e-9);  // 24.08 dB
    EXPECT_NEAR(m.relMse, offset * offset / (base * base + 1e-2), 1e-12);
    EXPECT_NEAR(m.meanAbsLuminanceDiff, offset, 1e-9);  // Rec. 709 weights sum to 1

    // Peak 2: PSNR up by 20 log10(2), RMSE % halved; SSIM constants change with L.
    MetricOptions peak2;
    peak2.peak = 2.0;
    ImageMetrics m2 = computeMetrics(test, ref, peak2);
    EXPECT_NEAR(m2.psnr - m.psnr, 20.0 * std::log10(2.0), 1e-9);
    EXPECT_NEAR(m2.rmsePercent, m.rmsePercent / 2, 1e-9);
}

TEST(ImageMetrics, ErrorsPerChannelAverageOverRgb) {
    // Only green differs, by d: MSE = d^2 / 3 over the three channels.
    const float d = 0.5f;
    ImageRGBA ref = constantImage(8, 8, 0.1f, 0.2f, 0.3f);
    ImageRGBA test = constantImage(8, 8, 0.1f, 0.2f + d, 0.3f);
    ImageMetrics m = computeMetrics(test, ref);
    EXPECT_NEAR(m.mse, d * d / 3.0, 1e-7);
    EXPECT_NEAR(m.relMse, d * d / (0.2 * 0.2 + 1e-2) / 3.0, 1e-6);
    EXPECT_NEAR(m.meanAbsLuminanceDiff, 0.7152 * d, 1e-6);
}

TEST(ImageMetrics, AlphaIsIgnored) {
    ImageRGBA a = randomImage(16, 16, 2);
    ImageRGBA b = a;
    for (size_t p = 0; p < size_t(16) * 16; ++p) b.pixels[p * 4 + 3] = 0.0f;
    b.pixels[3] = std::numeric_limits<float>::quiet_NaN();  // not checked: alpha is ignored
    ImageMetrics m = computeMetrics(a, b);
    EXPECT_EQ(m.rmse, 0.0);
    EXPECT_NEAR(m.ssim, 1.0, 1e-12);
}

TEST(ImageMetrics, SsimOfConstantImagesMatchesClosedForm) {
    // Flat windows: sigma = 0, so SSIM = (2ab + C1) / (a^2 + b^2 + C1) (Eq. 13, contrast and
    // structure terms are C2 / C2 = 1).
    const double a = 0.8, b = 0.4, c1 = 1e-4;
    ImageRGBA x = constantImage(16, 16, float(a), float(a), float(a));
    ImageRGBA y = constantImage(16, 16, float(b), float(b), float(b));
    ImageMetrics m = computeMetrics(x, y);
    EXPECT_NEAR(m.ssim, (2 * a * b + c1) / (a * a + b * b + c1), 1e-6);
}

TEST(ImageMetrics, SsimMatchesDirectImplementation) {
    ImageRGBA x = randomImage(40, 30, 3);
    // A scaled copy (luminance change only: SSIM < 1, structure term 1), a noisy copy, and an
    // unrelated image: three different SSIM regimes.
    ImageRGBA scaled = x;
    for (size_t i = 0; i < scaled.pixels.size(); ++i)
        if (i % 4 != 3) scaled.pixels[i] *= 0.5f;
    ImageRGBA noisy = x;
    std::mt19937 rng(4);
    std::normal_distribution<float> noise(0.0f, 0.1f);
    for (size_t i = 0; i < noisy.pixels.size(); ++i)
        if (i % 4 != 3) noisy.pixels[i] += noise(rng);
    ImageRGBA other = randomImage(40, 30, 5);
    for (const ImageRGBA* y : {&scaled, &noisy, &other}) {
        double expected = referenceSsimRgb(x, *y);
        ImageMetrics m = computeMetrics(x, *y);
        EXPECT_NEAR(m.ssim, expected, 1e-9);
        EXPECT_LT(m.ssim, 0.999);
        EXPECT_NEAR(computeMetrics(*y, x).ssim, m.ssim, 1e-12) << "SSIM is symmetric";
    }
    EXPECT_GT(computeMetrics(x, scaled).ssim, computeMetrics(x, other).ssim);
    // HDR values with peak 4: the dynamic range enters C1 and C2.
    ImageRGBA hdrX = randomImage(24, 24, 6, 0.0f, 4.0f), hdrY = randomImage(24, 24, 7, 0.0f, 4.0f);
    MetricOptions peak4;
    peak4.peak = 4.0;
    EXPECT_NEAR(computeMetrics(hdrX, hdrY, peak4).ssim, referenceSsimRgb(hdrX, hdrY, 4.0), 1e-9);
}

TEST(ImageMetrics, SsimOfImagesSmallerThanTheWindowIsDefined) {
    ImageRGBA x = randomImage(5, 3, 8);
    ImageMetrics same = computeMetrics(x, x);
    EXPECT_NEAR(same.ssim, 1.0, 1e-12);
    ImageRGBA y = randomImage(5, 3, 9);
    ImageMetrics m = computeMetrics(x, y);
    EXPECT_TRUE(std::isfinite(m.ssim));
    EXPECT_LT(m.ssim, 1.0);
    // 1x1: a single flat window, the closed form of constant images.
    ImageRGBA p = constantImage(1, 1, 0.5f, 0.5f, 0.5f),
              q = constantImage(1, 1, 0.25f, 0.25f, 0.25f);
    EXPECT_NEAR(computeMetrics(p, q).ssim, (2 * 0.5 * 0.25 + 1e-4) / (0.25 + 0.0625 + 1e-4), 1e-6);
}

TEST(ImageMetrics, TemporalErrorOfConstantFrames) {
    ImageRGBA f0 = constantImage(8, 4, 0.2f, 0.4f, 0.6f);
    ImageRGBA f1 = constantImage(8, 4, 0.3f, 0.1f, 0.6f);
    const double expected = std::abs(0.2126 * 0.1 - 0.7152 * 0.3);
    EXPECT_NEAR(temporalError(f0, f1), expected, 1e-6);
    EXPECT_NEAR(temporalError(f1, f0), expected, 1e-6);
    EXPECT_EQ(temporalError(f0, f0), 0.0);
    // Sequence f0, f1, f1: pairs (f0,f1) and (f1,f1) -> mean expected / 2.
    EXPECT_NEAR(temporalError(std::vector<ImageRGBA>{f0, f1, f1}), expected / 2, 1e-6);
    EXPECT_EQ(temporalError(std::vector<ImageRGBA>{f0}), 0.0);
    // A colour change with equal luminance is no temporal error (luminance-only metric).
    ImageRGBA grey = constantImage(8, 4, 0.5f, 0.5f, 0.5f);
    ImageRGBA tinted = constantImage(8, 4, 0.5f + 0.0722f, 0.5f, 0.5f - 0.2126f);
    EXPECT_NEAR(temporalError(grey, tinted), 0.0, 1e-6);
}

TEST(ImageMetrics, TemporalErrorIsMeanOfPerPixelDifferences) {
    // Half the pixels change by +d in luminance, half by -d: mean |dY| = d (not 0).
    ImageRGBA f0 = constantImage(4, 4, 0.5f, 0.5f, 0.5f), f1 = f0;
    for (size_t p = 0; p < 16; ++p)
        for (int c = 0; c < 3; ++c) f1.pixels[p * 4 + size_t(c)] += (p % 2 ? 0.25f : -0.25f);
    EXPECT_NEAR(temporalError(f0, f1), 0.25, 1e-6);
}

TEST(ImageMetrics, NonFiniteInputIsAnErrorNamingTheImage) {
    ImageRGBA a = randomImage(8, 8, 10), b = a;
    b.pixels[(size_t(2) * 8 + 3) * 4 + 1] = std::numeric_limits<float>::quiet_NaN();
    std::string msg = inputErrorMessage([&] { computeMetrics(a, b, {}, "a.exr", "b.exr"); });
    EXPECT_NE(msg.find("b.exr"), std::string::npos) << msg;
    EXPECT_NE(msg.find("(3, 2)"), std::string::npos) << msg;
    EXPECT_NE(msg.find("NaN"), std::string::npos) << msg;
    a.pixels[0] = std::numeric_limits<float>::infinity();
    msg = inputErrorMessage([&] { computeMetrics(a, a, {}, "first.exr", "second.exr"); });
    EXPECT_NE(msg.find("first.exr"), std::string::npos) << msg;
    EXPECT_NE(msg.find("Inf"), std::string::npos) << msg;
    msg = inputErrorMessage([&] { temporalError(a, randomImage(8, 8, 11), "f7", "f8"); });
    EXPECT_NE(msg.find("f7"), std::string::npos) << msg;
}

TEST(ImageMetrics, SizeMismatchAndBadOptionsAreErrors) {
    ImageRGBA a = randomImage(8, 8, 12), b = randomImage(8, 6, 13);
    std::string msg = inputErrorMessage([&] { computeMetrics(a, b, {}, "a.exr", "b.exr"); });
    EXPECT_NE(msg.find("a.exr is 8x8"), std::string::npos) << msg;
    EXPECT_NE(msg.find("b.exr is 8x6"), std::string::npos) << msg;
    msg = inputErrorMessage([&] { temporalError(a, b); });
    EXPECT_NE(msg.find("8x6"), std::string::npos) << msg;
    msg = inputErrorMessage([&] { computeMetrics(ImageRGBA{}, ImageRGBA{}); });
    EXPECT_NE(msg.find("empty"), std::string::npos) << msg;
    MetricOptions bad;
    bad.peak = 0;
    EXPECT_FALSE(inputErrorMessage([&] { computeMetrics(a, a, bad); }).empty());
    bad = {};
    bad.relMseEpsilon = -1;
    EXPECT_FALSE(inputErrorMessage([&] { computeMetrics(a, a, bad); }).empty());
}

TEST(ImageMetrics, RelMseWeightsDarkPixelsMore) {
    // The same absolute error counts more where the reference is dark.
    ImageRGBA dark = constantImage(4, 4, 0.05f, 0.05f, 0.05f);
    ImageRGBA bright = constantImage(4, 4, 0.9f, 0.9f, 0.9f);
    ImageRGBA darkTest = constantImage(4, 4, 0.15f, 0.15f, 0.15f);
    ImageRGBA brightTest = constantImage(4, 4, 1.0f, 1.0f, 1.0f);
    ImageMetrics md = computeMetrics(darkTest, dark), mb = computeMetrics(brightTest, bright);
    EXPECT_NEAR(md.rmse, mb.rmse, 1e-6);
    EXPECT_GT(md.relMse, 5 * mb.relMse);
    MetricOptions eps;
    eps.relMseEpsilon = 1e-3;
    EXPECT_NEAR(computeMetrics(darkTest, dark, eps).relMse, 0.01 / (0.0025 + 1e-3), 1e-5);
}

TEST(ImageMetrics, JsonHasEveryKeyAndNullForInfinitePsnr) {
    ImageRGBA a = randomImage(12, 12, 14), b = randomImage(12, 12, 15);
    MetricOptions options;
    nlohmann::json same = metricsToJson(computeMetrics(a, a), options);
    EXPECT_TRUE(same.at("psnr_db").is_null()) << same.dump();
    ImageMetrics m = computeMetrics(a, b);
    nlohmann::json j = metricsToJson(m, options);
    EXPECT_EQ(j.at("rmse").get<double>(), m.rmse);
    EXPECT_EQ(j.at("rmse_percent").get<double>(), m.rmsePercent);
    EXPECT_EQ(j.at("rel_mse").get<double>(), m.relMse);
    EXPECT_EQ(j.at("psnr_db").get<double>(), m.psnr);
    EXPECT_EQ(j.at("ssim").get<double>(), m.ssim);
    EXPECT_EQ(j.at("temporal_error").get<double>(), m.meanAbsLuminanceDiff);
    EXPECT_EQ(j.at("peak").get<double>(), 1.0);
    EXPECT_EQ(j.at("rel_mse_epsilon").get<double>(), 1e-2);
}
