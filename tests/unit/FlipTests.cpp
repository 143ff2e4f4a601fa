// ꟻLIP (eval/flip) on hand-worked cases: the colour spaces against published CIELAB values, the
// separable filters against FLIP's 2D kernels built here from the paper's formulas, uniform
// images whose error is the colour term alone (worked out from CIELAB constants), and the
// properties each stage must have (zero for identical images, symmetry of LDR-ꟻLIP, [0,1], the
// effect of the viewing distance, HDR-ꟻLIP's exposure range and its invariance to exposure).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "core/util/Error.h"
#include "eval/flip/Flip.h"
#include "eval/flip/FlipColor.h"
#include "eval/flip/FlipFilters.h"
#include "eval/metrics/EccentricityBands.h"

using namespace fovea;
using namespace fovea::eval;

namespace {

image::ImageRGBA flatImage(uint32_t w, uint32_t h, float r, float g, float b) {
    image::ImageRGBA img{w, h, std::vector<float>(size_t(w) * h * 4, 1.0f)};
    for (size_t p = 0; p < size_t(w) * h; ++p) {
        img.pixels[p * 4 + 0] = r;
        img.pixels[p * 4 + 1] = g;
        img.pixels[p * 4 + 2] = b;
    }
    return img;
}

image::ImageRGBA noisyImage(uint32_t w, uint32_t h, unsigned seed, float hi) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> dist(0.0f, hi);
    image::ImageRGBA img = flatImage(w, h, 0, 0, 0);
    for (size_t p = 0; p < size_t(w) * h; ++p)
        for (int c = 0; c < 3; ++c) img.pixels[p * 4 + size_t(c)] = dist(rng);
    return img;
}

FlipOptions ldr(double ppd = 0) {
    return {FlipMode::Ldr, ppd, {}, {}};
}
FlipOptions hdr(double ppd = 0) {
    return {FlipMode::Hdr, ppd, {}, {}};
}

// Clamp-to-edge 2D convolution with an explicit (2r+1)^2 kernel, the way FLIP writes it.
flip::Plane convolve2d(const flip::Plane& in, const std::vector<double>& kernel, int r) {
    flip::Plane out(in.width, in.height);
    const int w = int(in.width), h = int(in.height), n = 2 * r + 1;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            double sum = 0;
            for (int j = -r; j <= r; ++j)
                for (int i = -r; i <= r; ++i)
                    sum += kernel[size_t((j + r) * n + i + r)] *
                           in.at(uint32_t(std::clamp(x + i, 0, w - 1)),
                                 uint32_t(std::clamp(y + j, 0, h - 1)));
            out.at(uint32_t(x), uint32_t(y)) = float(sum);
        }
    return out;
}

flip::Plane randomPlane(uint32_t w, uint32_t h, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> dist(-20.0f, 100.0f);
    flip::Plane p(w, h);
    for (float& v : p.values) v = dist(rng);
    return p;
}

// The radiance ACES (with FLIP's 0.6 pre-scale) maps to 0.85, solved here from the tone curve.
double acesRootOf085() {
    const double a = 0.36 * 2.51 - 0.85 * 0.36 * 2.43, b = 0.6 * 0.03 - 0.85 * 0.6 * 0.59,
                 c = -0.85 * 0.14;
    return (-b + std::sqrt(b * b - 4 * a * c)) / (2 * a);
}

}  // namespace

TEST(Flip, DefaultObserverIs67PixelsPerDegree) {
    // 0.7 m from a 0.7 m wide 3840-pixel monitor: 3840 π / 180.
    EXPECT_NEAR(defaultPixelsPerDegree(), 3840.0 * std::numbers::pi / 180.0, 1e-9);
    EXPECT_NEAR(defaultPixelsPerDegree(), 67.02, 0.01);
    EXPECT_NEAR(pixelsPerDegree(1.4, 0.7, 3840), 2 * defaultPixelsPerDegree(), 1e-9);
}

TEST(FlipColor, RoundTripsAndPublishedCielabValues) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> dist(0.0f, 1.0f);
    for (int i = 0; i < 100; ++i) {
        const flip::Color c = {dist(rng), dist(rng), dist(rng)};
        const flip::Color back =
            flip::xyzToLinearRgb(flip::ycxczToXyz(flip::xyzToYcxcz(flip::linearRgbToXyz(c))));
        for (int k = 0; k < 3; ++k) EXPECT_NEAR(back[size_t(k)], c[size_t(k)], 2e-5);
    }
    // White is the reference white: YyCxCz and L*a*b* (100, 0, 0).
    const flip::Color white = flip::xyzToYcxcz(flip::linearRgbToXyz({1, 1, 1}));
    EXPECT_NEAR(white[0], 100.0f, 1e-3);
    EXPECT_NEAR(white[1], 0.0f, 1e-3);
    EXPECT_NEAR(white[2], 0.0f, 1e-3);
    // CIELAB of the sRGB primaries green and blue (D65): (87.737, -86.185, 83.181) and
    // (32.303, 79.197, -107.864), the values colour tables publish.
    const flip::Color green = flip::xyzToLab(flip::linearRgbToXyz({0, 1, 0}));
    const flip::Color blue = flip::xyzToLab(flip::linearRgbToXyz({0, 0, 1}));
    const float expected[2][3] = {{87.737f, -86.185f, 83.181f}, {32.303f, 79.197f, -107.864f}};
    for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(green[size_t(k)], expected[0][k], 0.02f) << k;
        EXPECT_NEAR(blue[size_t(k)], expected[1][k], 0.02f) << k;
    }
    EXPECT_NEAR(flip::srgbToLinear(0.5f), 0.214041f, 1e-5f);
    EXPECT_NEAR(flip::srgbToLinear(0.02f), 0.02f / 12.92f, 1e-7f);
}

TEST(FlipColor, HuntAdjustmentAndHyab) {
    const flip::Color h = flip::huntAdjust({50, 20, -10});
    EXPECT_FLOAT_EQ(h[0], 50);
    EXPECT_FLOAT_EQ(h[1], 10);  // 0.01 L a
    EXPECT_FLOAT_EQ(h[2], -5);
    EXPECT_FLOAT_EQ(flip::hyab({10, 3, 4}, {0, 0, 0}), 15);  // |ΔL| + ||(3, 4)||
    EXPECT_FLOAT_EQ(flip::hyab({0, 3, 4}, {10, 0, 0}), 15);
}

TEST(FlipFilters, CsfSeparableTermsEqualFlipsTwoDimensionalKernel) {
    const double ppd = 30;  // radius 5: a small 2D kernel
    const int r = flip::csfRadius(ppd);
    EXPECT_EQ(
        r, int(std::ceil(3 * std::sqrt(0.04 / (2 * std::numbers::pi * std::numbers::pi)) * ppd)));
    EXPECT_EQ(flip::csfRadius(defaultPixelsPerDegree()), 10);
    const double abab[3][4] = {
        {1, 0.0047, 0, 1e-5}, {1, 0.0053, 0, 1e-5}, {34.1, 0.04, 13.5, 0.025}};
    const flip::CsfChannel channels[3] = {flip::CsfChannel::Achromatic, flip::CsfChannel::RedGreen,
                                          flip::CsfChannel::BlueYellow};
    const flip::Plane in = randomPlane(23, 17, 7);
    for (int c = 0; c < 3; ++c) {
        // FLIP: g(x, y) = a1 √(π/b1) e^(−π² z / b1) + a2 √(π/b2) e^(−π² z / b2), z = |(x, y) /
        // ppd|², normalized to sum 1.
        const double pi = std::numbers::pi;
        std::vector<double> kernel;
        double sum = 0;
        for (int j = -r; j <= r; ++j)
            for (int i = -r; i <= r; ++i) {
                const double z = (i * i + j * j) / (ppd * ppd);
                const auto [a1, b1, a2, b2] = abab[c];
                kernel.push_back(a1 * std::sqrt(pi / b1) * std::exp(-pi * pi * z / b1) +
                                 a2 * std::sqrt(pi / b2) * std::exp(-pi * pi * z / b2));
                sum += kernel.back();
            }
        for (double& k : kernel) k /= sum;
        const flip::Plane expected = convolve2d(in, kernel, r);
        flip::Plane separable(in.width, in.height);
        const auto terms = flip::csfTerms(channels[c], ppd);
        EXPECT_EQ(terms.size(), c == 2 ? 2u : 1u);
        for (const auto& t : terms) {
            const flip::Plane part = flip::convolveSeparable(in, t.kernel, t.kernel);
            for (size_t i = 0; i < part.values.size(); ++i)
                separable.values[i] += t.weight * part.values[i];
        }
        for (size_t i = 0; i < expected.values.size(); ++i)
            ASSERT_NEAR(separable.values[i], expected.values[i], 2e-4)
                << "channel " << c << " i " << i;
    }
}

TEST(FlipFilters, FeatureKernelsAreSignNormalizedAndSeparable) {
    const flip::FeatureKernels k = flip::featureKernels(defaultPixelsPerDegree());
    EXPECT_NEAR(k.sigma, 0.5 * 0.082 * defaultPixelsPerDegree(), 1e-5);
    EXPECT_EQ(k.radius, int(std::ceil(3 * k.sigma)));
    for (const flip::Kernel* kernel : {&k.edge, &k.point}) {
        double positive = 0, negative = 0;
        for (float v : *kernel) (v > 0 ? positive : negative) += v;
        EXPECT_NEAR(positive, 1.0, 1e-5);
        EXPECT_NEAR(negative, -1.0, 1e-5);
    }
    double smooth = 0;
    for (float v : k.smooth) smooth += v;
    EXPECT_NEAR(smooth, 1.0, 1e-6);
    // FLIP's 2D edge detector in x: −x e^(−(x²+y²)/(2σ²)), positive weights scaled to 1 and
    // negative ones to −1; the point detector (x²/σ² − 1) e^(...) likewise.
    const int r = k.radius;
    const double s2 = double(k.sigma) * k.sigma;
    for (int which = 0; which < 2; ++which) {
        std::vector<double> kernel;
        double positive = 0, negative = 0;
        for (int y = -r; y <= r; ++y)
            for (int x = -r; x <= r; ++x) {
                const double g = std::exp(-(x * x + y * y) / (2 * s2));
                kernel.push_back(which == 0 ? -x * g : (x * x / s2 - 1) * g);
                (kernel.back() > 0 ? positive : negative) += kernel.back();
            }
        for (double& v : kernel) v = v > 0 ? v / positive : v / -negative;
        const flip::Kernel& rows = which == 0 ? k.edge : k.point;
        for (int y = -r; y <= r; ++y)
            for (int x = -r; x <= r; ++x)
                ASSERT_NEAR(rows[size_t(x + r)] * k.smooth[size_t(y + r)],
                            kernel[size_t((y + r) * (2 * r + 1) + x + r)], 1e-6);
    }
}

TEST(Flip, IdenticalImagesScoreZero) {
    const image::ImageRGBA ldrImage = noisyImage(40, 30, 1, 1.0f);
    const image::ImageRGBA hdrImage = noisyImage(40, 30, 2, 20.0f);
    for (const auto& [img, options] : {std::pair{&ldrImage, ldr()}, std::pair{&hdrImage, hdr()}}) {
        const FlipResult r = computeFlip(*img, *img, options);
        EXPECT_EQ(r.mean, 0.0);
        for (float e : r.errors) ASSERT_EQ(e, 0.0f);
    }
}

TEST(Flip, UniformImagesScoreTheRedistributedColourErrorAlone) {
    // Black against white: no edges or points (uniform images), the filters keep uniform images
    // as they are, so every pixel's error is the colour term: HyAB = |0 − 100| = 100, raised to
    // 0.7, against c_max = HyAB(Hunt(green), Hunt(blue))^0.7 from the CIELAB values above.
    const double green[3] = {87.737, -86.185 * 0.87737, 83.181 * 0.87737};
    const double blue[3] = {32.303, 79.197 * 0.32303, -107.864 * 0.32303};
    const double cMax = std::pow(
        std::abs(green[0] - blue[0]) + std::hypot(green[1] - blue[1], green[2] - blue[2]), 0.7);
    auto redistribute = [&](double e) {
        return e < 0.4 * cMax ? 0.95 / (0.4 * cMax) * e
                              : 0.95 + (e - 0.4 * cMax) / (cMax - 0.4 * cMax) * 0.05;
    };
    const FlipResult r = computeFlip(flatImage(24, 20, 0, 0, 0), flatImage(24, 20, 1, 1, 1), ldr());
    const double expected = redistribute(std::pow(100.0, 0.7));
    EXPECT_NEAR(r.mean, expected, 2e-4);
    for (float e : r.errors) ASSERT_NEAR(e, expected, 2e-4);
    // Mid grey against white: L* of sRGB 0.5 is 53.389; below p_c c_max, the linear part.
    const FlipResult grey =
        computeFlip(flatImage(24, 20, 0.5f, 0.5f, 0.5f), flatImage(24, 20, 1, 1, 1), ldr());
    EXPECT_NEAR(grey.mean, redistribute(std::pow(100.0 - 53.389, 0.7)), 2e-4);
    EXPECT_LT(grey.mean, r.mean);
}

TEST(Flip, LdrIsSymmetricAndEveryErrorLiesInTheUnitInterval) {
    const image::ImageRGBA a = noisyImage(33, 27, 5, 1.0f), b = noisyImage(33, 27, 6, 1.0f);
    const FlipResult ab = computeFlip(a, b, ldr()), ba = computeFlip(b, a, ldr());
    for (size_t i = 0; i < ab.errors.size(); ++i) {
        ASSERT_NEAR(ab.errors[i], ba.errors[i], 1e-6);
        ASSERT_GE(ab.errors[i], 0.0f);
        ASSERT_LE(ab.errors[i], 1.0f);
    }
    const FlipResult h =
        computeFlip(noisyImage(33, 27, 7, 50.0f), noisyImage(33, 27, 8, 50.0f), hdr());
    for (float e : h.errors) {
        ASSERT_GE(e, 0.0f);
        ASSERT_LE(e, 1.0f);
    }
    EXPECT_GT(h.mean, 0.0);
}

TEST(Flip, ErrorStaysWhereTheImagesDiffer) {
    // A one-pixel line: pixels farther than both filters reach (CSF radius 10, feature radius 9
    // at 67 ppd) see identical neighbourhoods and score exactly 0.
    image::ImageRGBA test = flatImage(64, 8, 0.5f, 0.5f, 0.5f);
    const image::ImageRGBA reference = test;
    for (uint32_t y = 0; y < 8; ++y)
        for (int c = 0; c < 3; ++c) test.pixels[(size_t(y) * 64 + 20) * 4 + size_t(c)] = 0.6f;
    const FlipResult r = computeFlip(test, reference, ldr());
    EXPECT_GT(r.errors[4 * 64 + 20], 0.05f);
    EXPECT_EQ(r.errors[4 * 64 + 20 + 11], 0.0f);
    EXPECT_EQ(r.errors[4 * 64 + 63], 0.0f);
    EXPECT_GT(r.errors[4 * 64 + 22], 0.0f);  // the filters spread the line
}

TEST(Flip, FartherViewersSeeLessFineNoise) {
    // Pixel noise around grey: more pixels per degree (a farther viewer, a denser display) puts
    // the noise at frequencies the CSFs filter out.
    const image::ImageRGBA flat = flatImage(48, 48, 0.5f, 0.5f, 0.5f);
    image::ImageRGBA noisy = noisyImage(48, 48, 9, 0.2f);
    for (size_t p = 0; p < size_t(48) * 48; ++p)
        for (int c = 0; c < 3; ++c) noisy.pixels[p * 4 + size_t(c)] += 0.4f;
    const double near = computeFlip(noisy, flat, ldr(20)).mean;
    const double paper = computeFlip(noisy, flat, ldr()).mean;
    const double far = computeFlip(noisy, flat, ldr(200)).mean;
    EXPECT_GT(near, paper);
    EXPECT_GT(paper, far);
    EXPECT_GT(far, 0.0);
}

TEST(Flip, HdrExposureRangeComesFromTheReference) {
    // Luminance 1 everywhere but one pixel at 4: the start exposure takes 4 to 0.85 after tone
    // mapping, the stop exposure the median (1); ceil(2) = 2 exposures.
    image::ImageRGBA reference = flatImage(16, 16, 1, 1, 1);
    for (int c = 0; c < 3; ++c) reference.pixels[size_t(c)] = 4.0f;
    const FlipResult r = computeFlip(flatImage(16, 16, 1.2f, 1, 1), reference, hdr());
    const double x = acesRootOf085();
    const double tone =
        (0.36 * 2.51 * x * x + 0.018 * x) / (0.36 * 2.43 * x * x + 0.354 * x + 0.14);
    EXPECT_NEAR(tone, 0.85, 1e-12);
    EXPECT_NEAR(r.startExposure, std::log2(x / 4.0), 1e-9);
    EXPECT_NEAR(r.stopExposure, std::log2(x / 1.0), 1e-9);
    EXPECT_EQ(r.exposureCount, 2u);
    // Given exposures win, and their count follows the range.
    FlipOptions options = hdr();
    options.startExposure = -3;
    options.stopExposure = 2.5;
    const FlipResult given = computeFlip(flatImage(16, 16, 1.2f, 1, 1), reference, options);
    EXPECT_EQ(given.startExposure, -3);
    EXPECT_EQ(given.exposureCount, 6u);  // ceil(5.5)
}

TEST(Flip, HdrIsInvariantToExposingBothImagesAlike) {
    // Scaling both images by 2^3 shifts the automatic exposure range by −3 stops: every exposure
    // sees the same tone-mapped images, so the map is the same.
    const image::ImageRGBA test = noisyImage(30, 20, 10, 5.0f),
                           reference = noisyImage(30, 20, 11, 5.0f);
    image::ImageRGBA test8 = test, reference8 = reference;
    for (float& v : test8.pixels) v *= 8.0f;
    for (float& v : reference8.pixels) v *= 8.0f;
    const FlipResult a = computeFlip(test, reference, hdr());
    const FlipResult b = computeFlip(test8, reference8, hdr());
    EXPECT_NEAR(b.startExposure, a.startExposure - 3, 1e-6);
    EXPECT_NEAR(b.stopExposure, a.stopExposure - 3, 1e-6);
    EXPECT_EQ(a.exposureCount, b.exposureCount);
    for (size_t i = 0; i < a.errors.size(); ++i) ASSERT_NEAR(a.errors[i], b.errors[i], 1e-4);
}

TEST(Flip, HdrCopesWithBlackReferences) {
    // All black: no range to take, exposure 0 twice; the error is finite.
    const FlipResult black =
        computeFlip(noisyImage(16, 16, 12, 1.0f), flatImage(16, 16, 0, 0, 0), hdr());
    EXPECT_EQ(black.startExposure, 0.0);
    EXPECT_EQ(black.stopExposure, 0.0);
    EXPECT_EQ(black.exposureCount, 2u);
    EXPECT_TRUE(std::isfinite(black.mean));
    EXPECT_GT(black.mean, 0.0);
    // Three quarters black (a render's empty background): the median of the lit pixels (2.0).
    image::ImageRGBA reference = flatImage(16, 16, 0, 0, 0);
    for (size_t p = 0; p < 64; ++p)
        for (int c = 0; c < 3; ++c) reference.pixels[p * 4 + size_t(c)] = 2.0f;
    const FlipResult r = computeFlip(reference, reference, hdr());
    EXPECT_NEAR(r.stopExposure, std::log2(acesRootOf085() / 2.0), 1e-9);
    EXPECT_EQ(r.mean, 0.0);
}

TEST(Flip, BadInputIsAnInputErrorNamingTheImage) {
    const image::ImageRGBA a = flatImage(8, 8, 0.5f, 0.5f, 0.5f);
    auto message = [](auto f) {
        try {
            f();
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string("no InputError");
    };
    EXPECT_NE(message([&] {
                  computeFlip(a, flatImage(8, 9, 0, 0, 0), ldr(), "t.png", "r.png");
              }).find("r.png"),
              std::string::npos);
    image::ImageRGBA nan = a;
    nan.pixels[5] = std::nanf("");
    EXPECT_NE(message([&] { computeFlip(nan, a, hdr(), "t.exr", "r.exr"); }).find("t.exr"),
              std::string::npos);
    FlipOptions backwards = hdr();
    backwards.startExposure = 2;
    backwards.stopExposure = 1;
    EXPECT_NE(message([&] { computeFlip(a, a, backwards); }).find("start exposure"),
              std::string::npos);
    EXPECT_NE(message([&] { computeFlip(a, a, ldr(-3)); }).find("pixels per degree"),
              std::string::npos);
}

TEST(Flip, ModeFollowsTheFileType) {
    EXPECT_EQ(flipModeForFile("a/ref.exr"), FlipMode::Hdr);
    EXPECT_EQ(flipModeForFile("REF.EXR"), FlipMode::Hdr);
    EXPECT_EQ(flipModeForFile("ref.hdr"), FlipMode::Hdr);
    EXPECT_EQ(flipModeForFile("ref.png"), FlipMode::Ldr);
    EXPECT_EQ(flipModeForFile("ref.jpg"), FlipMode::Ldr);
}

TEST(Flip, MapImageHoldsTheErrorsInGrey) {
    const FlipResult r = computeFlip(noisyImage(6, 5, 13, 1.0f), noisyImage(6, 5, 14, 1.0f), ldr());
    const image::ImageRGBA map = flipMapImage(r);
    ASSERT_EQ(map.width, 6u);
    ASSERT_EQ(map.height, 5u);
    for (size_t i = 0; i < r.errors.size(); ++i) {
        for (int c = 0; c < 3; ++c) EXPECT_EQ(map.pixels[i * 4 + size_t(c)], r.errors[i]);
        EXPECT_EQ(map.pixels[i * 4 + 3], 1.0f);
    }
}

TEST(Flip, BandsAverageTheMapOverTheirPixels) {
    scene::FrameCamera camera;
    camera.yfov = glm::radians(90.0f);
    camera.eyeCount = 1;
    camera.eyes[0].gaze = {0.5f, 0.5f};
    const uint32_t w = 64, h = 64;
    const image::ImageRGBA img = flatImage(w, h, 0.3f, 0.3f, 0.3f);
    // Map value = the pixel's band index: each band's mean is its index.
    std::vector<float> map(size_t(w) * h);
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            const double e = pixelEccentricityDegrees(camera, w, h, x, y);
            map[size_t(y) * w + x] = e < 5 ? 0.0f : (e < 20 ? 1.0f : 2.0f);
        }
    const auto bands = eccentricityBandErrors(img, img, camera, &map);
    ASSERT_EQ(bands.size(), 3u);
    for (size_t b = 0; b < 3; ++b) {
        ASSERT_GT(bands[b].pixels, 0u);
        EXPECT_DOUBLE_EQ(bands[b].flipMean, double(b));
    }
    EXPECT_TRUE(bandErrorsToJson(bands)[1].contains("flip_mean"));
    EXPECT_FALSE(
        bandErrorsToJson(eccentricityBandErrors(img, img, camera))[1].contains("flip_mean"));
    // An HMD's viewing condition: 32 px / tan(45°) per radian at the centre.
    EXPECT_NEAR(cameraPixelsPerDegree(camera, w, h), 32.0 * std::numbers::pi / 180.0, 1e-6);
}
