// A CPU oracle for ꟻLIP (eval/flip): the whole LDR- and HDR-ꟻLIP pipeline written again the way
// the authors' PyTorch code structures it - explicit 2D kernels with replicate padding, the
// colour transforms with FLIP's own matrix constants, double precision - and nothing shared with
// eval/flip but the image type. computeFlip (separable float filters) must agree with it to 1e-6
// in the mean and 1e-5 per pixel. A pure-Python transcription of the same structure agreed with
// fovea to 3e-8 on the images of docs/metrics.md's cross-check.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "eval/flip/Flip.h"

using namespace fovea;

namespace {

using V3 = std::array<double, 3>;
constexpr double kPi = std::numbers::pi;

V3 mul(const double m[3][3], const V3& v) {
    return {m[0][0] * v[0] + m[0][1] * v[1] + m[0][2] * v[2],
            m[1][0] * v[0] + m[1][1] * v[1] + m[1][2] * v[2],
            m[2][0] * v[0] + m[2][1] * v[1] + m[2][2] * v[2]};
}
// FLIP's linear RGB <-> XYZ matrices and D65 white, as its code writes them.
const double kToXyz[3][3] = {{10135552.0 / 24577794, 8788810.0 / 24577794, 4435075.0 / 24577794},
                             {2613072.0 / 12288897, 8788810.0 / 12288897, 887015.0 / 12288897},
                             {1425312.0 / 73733382, 8788810.0 / 73733382, 70074185.0 / 73733382}};
const double kToRgb[3][3] = {{3.241003275, -1.537398934, -0.498615861},
                             {-0.969224334, 1.875930071, 0.041554224},
                             {0.055639423, -0.204011202, 1.057148933}};
const V3 kWhite = {0.950428545, 1.0, 1.088900371};

V3 toYcxcz(V3 xyz) {
    for (int i = 0; i < 3; ++i) xyz[i] /= kWhite[i];
    return {116 * xyz[1] - 16, 500 * (xyz[0] - xyz[1]), 200 * (xyz[1] - xyz[2])};
}
V3 fromYcxcz(const V3& c) {
    const double y = (c[0] + 16) / 116;
    return {(y + c[1] / 500) * kWhite[0], y, (y - c[2] / 200) * kWhite[2]};
}
V3 huntLab(V3 rgb) {
    for (double& v : rgb) v = std::clamp(v, 0.0, 1.0);
    V3 xyz = mul(kToXyz, rgb);
    const double d = 6.0 / 29;
    for (int i = 0; i < 3; ++i) {
        const double t = xyz[i] / kWhite[i];
        xyz[i] = t > d * d * d ? std::cbrt(t) : t / (3 * d * d) + 4.0 / 29;
    }
    const double l = 116 * xyz[1] - 16;
    return {l, 0.01 * l * 500 * (xyz[0] - xyz[1]), 0.01 * l * 200 * (xyz[1] - xyz[2])};
}
double hyab(const V3& a, const V3& b) {
    return std::abs(a[0] - b[0]) + std::hypot(a[1] - b[1], a[2] - b[2]);
}

struct Kernel2d {
    int r = 0;
    std::vector<double> w;  // (2r+1)^2, row-major
};

std::vector<double> convolve(const std::vector<double>& img, int w, int h, const Kernel2d& k) {
    std::vector<double> out(img.size());
    const int n = 2 * k.r + 1;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            double s = 0;
            for (int j = -k.r; j <= k.r; ++j)
                for (int i = -k.r; i <= k.r; ++i)
                    s += k.w[size_t((j + k.r) * n + i + k.r)] *
                         img[size_t(std::clamp(y + j, 0, h - 1) * w + std::clamp(x + i, 0, w - 1))];
            out[size_t(y * w + x)] = s;
        }
    return out;
}

Kernel2d csf(double ppd, int channel) {
    const double p[3][4] = {{1, 0.0047, 0, 1e-5}, {1, 0.0053, 0, 1e-5}, {34.1, 0.04, 13.5, 0.025}};
    Kernel2d k;
    k.r = int(std::ceil(3 * std::sqrt(0.04 / (2 * kPi * kPi)) * ppd));
    double sum = 0;
    for (int j = -k.r; j <= k.r; ++j)
        for (int i = -k.r; i <= k.r; ++i) {
            const double z = (i * i + j * j) / (ppd * ppd);
            const auto& c = p[channel];
            k.w.push_back(c[0] * std::sqrt(kPi / c[1]) * std::exp(-kPi * kPi * z / c[1]) +
                          c[2] * std::sqrt(kPi / c[3]) * std::exp(-kPi * kPi * z / c[3]));
            sum += k.w.back();
        }
    for (double& v : k.w) v /= sum;
    return k;
}

// Edge (point = false) or point detector in x (transposed = false) or y.
Kernel2d feature(double ppd, bool point, bool transposed) {
    const double sd = 0.5 * 0.082 * ppd;
    Kernel2d k;
    k.r = int(std::ceil(3 * sd));
    double positive = 0, negative = 0;
    for (int y = -k.r; y <= k.r; ++y)
        for (int x = -k.r; x <= k.r; ++x) {
            const int a = transposed ? y : x;
            const double g = std::exp(-(x * x + y * y) / (2 * sd * sd));
            k.w.push_back(point ? (a * a / (sd * sd) - 1) * g : -a * g);
            (k.w.back() < 0 ? negative : positive) += k.w.back();
        }
    for (double& v : k.w) v = v < 0 ? v / -negative : v / positive;
    return k;
}

// LDR-ꟻLIP of two images given per pixel in YCxCz.
std::vector<double> oracleLdr(const std::vector<V3>& test, const std::vector<V3>& ref, int w, int h,
                              double ppd) {
    auto filtered = [&](const std::vector<V3>& img) {
        std::array<std::vector<double>, 3> ch;
        for (int c = 0; c < 3; ++c) {
            std::vector<double> plane;
            for (const V3& p : img) plane.push_back(p[size_t(c)]);
            ch[size_t(c)] = convolve(plane, w, h, csf(ppd, c));
        }
        std::vector<V3> lab;
        for (size_t i = 0; i < img.size(); ++i)
            lab.push_back(huntLab(mul(kToRgb, fromYcxcz({ch[0][i], ch[1][i], ch[2][i]}))));
        return lab;
    };
    auto features = [&](const std::vector<V3>& img, bool point) {
        std::vector<double> y;
        for (const V3& p : img) y.push_back((p[0] + 16) / 116);
        const auto gx = convolve(y, w, h, feature(ppd, point, false));
        const auto gy = convolve(y, w, h, feature(ppd, point, true));
        std::vector<double> m;
        for (size_t i = 0; i < y.size(); ++i) m.push_back(std::hypot(gx[i], gy[i]));
        return m;
    };
    const auto lt = filtered(test), lr = filtered(ref);
    const auto et = features(test, false), er = features(ref, false);
    const auto pt = features(test, true), pr = features(ref, true);
    const double cmax = std::pow(hyab(huntLab({0, 1, 0}), huntLab({0, 0, 1})), 0.7);
    std::vector<double> out;
    for (size_t i = 0; i < test.size(); ++i) {
        const double e = std::pow(hyab(lr[i], lt[i]), 0.7);
        const double dc = e < 0.4 * cmax ? 0.95 / (0.4 * cmax) * e
                                         : 0.95 + (e - 0.4 * cmax) / (cmax - 0.4 * cmax) * 0.05;
        const double df = std::max(std::abs(er[i] - et[i]), std::abs(pt[i] - pr[i]));
        out.push_back(std::pow(dc, 1 - std::pow(df / std::sqrt(2.0), 0.5)));
    }
    return out;
}

double srgbToLinear(double c) {
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}
double aces(double x) {
    const double k[6] = {0.36 * 2.51, 0.6 * 0.03, 0, 0.36 * 2.43, 0.6 * 0.59, 0.14};
    return std::clamp((k[0] * x * x + k[1] * x + k[2]) / (k[3] * x * x + k[4] * x + k[5]), 0.0,
                      1.0);
}

std::vector<V3> opponent(const image::ImageRGBA& img, bool hdr, double scale) {
    std::vector<V3> out;
    for (size_t i = 0; i < size_t(img.width) * img.height; ++i) {
        V3 c;
        for (int k = 0; k < 3; ++k) {
            const double v = img.pixels[i * 4 + size_t(k)];
            c[size_t(k)] =
                hdr ? aces(std::max(v, 0.0) * scale) : srgbToLinear(std::clamp(v, 0.0, 1.0));
        }
        out.push_back(toYcxcz(mul(kToXyz, c)));
    }
    return out;
}

image::ImageRGBA scene(int w, int h, unsigned seed, bool hdr) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> noise(-0.15f, 0.15f);
    image::ImageRGBA img{uint32_t(w), uint32_t(h), std::vector<float>(size_t(w * h) * 4, 1.0f)};
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const bool disc = std::hypot(x - w / 2.0, y - h / 2.0) < h / 4.0;
            const float base[3] = {float(x) / w, float(y) / h, disc ? 0.9f : 0.4f};
            for (int c = 0; c < 3; ++c) {
                const float v = base[c] + (seed ? noise(rng) : 0.0f);
                img.pixels[size_t((y * w + x) * 4 + c)] =
                    hdr ? (disc ? 8.0f : 1.0f) * std::max(v, 0.0f) : std::clamp(v, 0.0f, 1.0f);
            }
        }
    return img;
}

}  // namespace

TEST(FlipOracle, LdrMatchesTheTwoDimensionalOracle) {
    const int w = 30, h = 22;
    const image::ImageRGBA ref = scene(w, h, 0, false), test = scene(w, h, 5, false);
    for (double ppd : {eval::defaultPixelsPerDegree(), 20.0}) {
        const auto expected =
            oracleLdr(opponent(test, false, 1), opponent(ref, false, 1), w, h, ppd);
        const eval::FlipResult r = eval::computeFlip(test, ref, {eval::FlipMode::Ldr, ppd, {}, {}});
        double mean = 0;
        for (size_t i = 0; i < expected.size(); ++i) {
            mean += expected[i];
            ASSERT_NEAR(r.errors[i], expected[i], 1e-5) << "ppd " << ppd << " pixel " << i;
        }
        EXPECT_NEAR(r.mean, mean / double(expected.size()), 1e-6) << ppd;
        EXPECT_GT(r.mean, 0.05);
    }
}

TEST(FlipOracle, HdrMatchesTheOracleOverItsExposures) {
    const int w = 26, h = 20;
    const double ppd = 30;
    const image::ImageRGBA ref = scene(w, h, 0, true), test = scene(w, h, 9, true);
    const eval::FlipResult r = eval::computeFlip(test, ref, {eval::FlipMode::Hdr, ppd, {}, {}});
    // HDR-ꟻLIP's exposure range from the reference: max and median luminance to 0.85.
    std::vector<double> lum;
    for (size_t i = 0; i < size_t(w * h); ++i)
        lum.push_back(0.2126 * ref.pixels[i * 4] + 0.7152 * ref.pixels[i * 4 + 1] +
                      0.0722 * ref.pixels[i * 4 + 2]);
    const double k[6] = {0.36 * 2.51, 0.6 * 0.03, 0, 0.36 * 2.43, 0.6 * 0.59, 0.14};
    const double c0 = (k[1] - k[4] * 0.85) / (k[0] - k[3] * 0.85);
    const double c1 = (k[2] - k[5] * 0.85) / (k[0] - k[3] * 0.85);
    const double xMax = -0.5 * c0 + std::sqrt(0.25 * c0 * c0 - c1);
    std::vector<double> sorted = lum;
    std::sort(sorted.begin(), sorted.end());
    const double start = std::log2(xMax / sorted.back());
    const double stop = std::log2(xMax / sorted[sorted.size() / 2]);
    const int n = std::max(2, int(std::ceil(stop - start)));
    EXPECT_NEAR(r.startExposure, start, 1e-6);
    EXPECT_NEAR(r.stopExposure, stop, 1e-6);
    EXPECT_EQ(r.exposureCount, uint32_t(n));
    std::vector<double> expected(size_t(w * h), 0.0);
    for (int e = 0; e < n; ++e) {
        const double scale = std::exp2(start + e * (stop - start) / (n - 1));
        const auto ldr =
            oracleLdr(opponent(test, true, scale), opponent(ref, true, scale), w, h, ppd);
        for (size_t i = 0; i < ldr.size(); ++i) expected[i] = std::max(expected[i], ldr[i]);
    }
    double mean = 0;
    for (size_t i = 0; i < expected.size(); ++i) {
        mean += expected[i];
        ASSERT_NEAR(r.errors[i], expected[i], 1e-5) << "pixel " << i;
    }
    EXPECT_NEAR(r.mean, mean / double(expected.size()), 1e-6);
    EXPECT_GT(n, 2);
}
