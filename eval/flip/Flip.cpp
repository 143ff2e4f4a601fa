// ꟻLIP in three steps per exposure: both images to the opponent space YyCxCz, the colour error
// (contrast sensitivity filters, Hunt-adjusted L*a*b*, HyAB, redistribution) and the feature
// error (edges and points of the achromatic channel), combined as ΔE_c^(1 − ΔE_f). HDR-ꟻLIP
// tone-maps both images at a range of exposures and keeps each pixel's largest LDR-ꟻLIP error.
#include "eval/flip/Flip.h"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <numbers>

#include "core/util/Error.h"
#include "eval/flip/FlipColor.h"
#include "eval/flip/FlipFilters.h"
#include "eval/metrics/ImageMetrics.h"

namespace fovea::eval {

using flip::Color;
using flip::Plane;

namespace {

// The colour pipeline's constants (LDR-ꟻLIP): q_c compresses HyAB, then errors below p_c · c_max
// map linearly to [0, p_t] and the rest to [p_t, 1]; q_f compresses the feature difference.
constexpr float kQc = 0.7f, kPc = 0.4f, kPt = 0.95f, kQf = 0.5f;

// HDR-ꟻLIP's tone mapper: Narkowicz's fit of ACES with FLIP's 0.6 pre-exposure folded in,
// y = (k0 x² + k1 x + k2) / (k3 x² + k4 x + k5).
constexpr double kAces[6] = {0.6 * 0.6 * 2.51, 0.6 * 0.03, 0.0, 0.6 * 0.6 * 2.43, 0.6 * 0.59, 0.14};
// HDR-ꟻLIP's exposure rule: the start exposure takes the reference's brightest pixel, the stop
// exposure its median, to this tone-mapped value.
constexpr double kExposureTarget = 0.85;
// More exposures than this are evaluated at this many evenly spaced ones (a reference spanning
// 2^64 in luminance; the range itself is kept).
constexpr uint32_t kMaxExposures = 64;

double acesToneMap(double x) {
    // x >= 0 (clamped by the caller): the denominator is >= k5 = 0.14.
    return std::clamp(
        (kAces[0] * x * x + kAces[1] * x + kAces[2]) / (kAces[3] * x * x + kAces[4] * x + kAces[5]),
        0.0, 1.0);
}

// The radiance the tone mapper takes to kExposureTarget: the positive root of
// (k0 − t k3) x² + (k1 − t k4) x + (k2 − t k5) = 0 (a = 0.160, b = −0.283, c = −0.119).
double acesInverseOfTarget() {
    const double t = kExposureTarget;
    const double a = kAces[0] - t * kAces[3], b = kAces[1] - t * kAces[4],
                 c = kAces[2] - t * kAces[5];
    return (-b + std::sqrt(b * b - 4.0 * a * c)) / (2.0 * a);  // a > 0, c < 0: real, positive
}

struct Opponent {
    Plane y, cx, cz;  // YyCxCz
};

// Display-referred linear RGB in [0,1] of pixel i: LDR decodes sRGB, HDR exposes by `scale`
// and tone-maps.
Color displayLinear(const image::ImageRGBA& image, size_t i, FlipMode mode, double scale) {
    Color c;
    for (int k = 0; k < 3; ++k) {
        const float v = image.pixels[i * 4 + size_t(k)];
        c[size_t(k)] = mode == FlipMode::Ldr ? flip::srgbToLinear(std::clamp(v, 0.0f, 1.0f))
                                             : float(acesToneMap(std::max(0.0, double(v) * scale)));
    }
    return c;
}

Opponent toOpponent(const image::ImageRGBA& image, FlipMode mode, double scale) {
    Opponent o{Plane(image.width, image.height), Plane(image.width, image.height),
               Plane(image.width, image.height)};
    for (size_t i = 0; i < o.y.values.size(); ++i) {
        const Color v =
            flip::xyzToYcxcz(flip::linearRgbToXyz(displayLinear(image, i, mode, scale)));
        o.y.values[i] = v[0];
        o.cx.values[i] = v[1];
        o.cz.values[i] = v[2];
    }
    return o;
}

Plane csfFiltered(const Plane& channel, flip::CsfChannel which, double ppd) {
    Plane out(channel.width, channel.height);
    for (const auto& term : flip::csfTerms(which, ppd)) {
        const Plane filtered = flip::convolveSeparable(channel, term.kernel, term.kernel);
        for (size_t i = 0; i < out.values.size(); ++i)
            out.values[i] += term.weight * filtered.values[i];
    }
    return out;
}

// Per pixel Hunt-adjusted L*a*b* of the CSF-filtered image.
std::vector<Color> filteredHuntLab(const Opponent& o, double ppd) {
    const Plane y = csfFiltered(o.y, flip::CsfChannel::Achromatic, ppd);
    const Plane cx = csfFiltered(o.cx, flip::CsfChannel::RedGreen, ppd);
    const Plane cz = csfFiltered(o.cz, flip::CsfChannel::BlueYellow, ppd);
    std::vector<Color> lab(y.values.size());
    for (size_t i = 0; i < lab.size(); ++i)
        lab[i] = flip::linearRgbToHuntLab(
            flip::xyzToLinearRgb(flip::ycxczToXyz({y.values[i], cx.values[i], cz.values[i]})));
    return lab;
}

// The largest colour difference: HyAB of Hunt-adjusted green and blue, the most distant pair of
// the sRGB gamut, raised to q_c.
float maxColourError() {
    const Color green = flip::linearRgbToHuntLab({0, 1, 0});
    const Color blue = flip::linearRgbToHuntLab({0, 0, 1});
    return std::pow(flip::hyab(green, blue), kQc);
}

// Edge and point strength per pixel of the achromatic channel, normalized to [0,1]:
// y = (Y_y + 16) / 116, i.e. relative luminance.
struct Features {
    std::vector<float> edge, point;
};
Features features(const Plane& opponentY, const flip::FeatureKernels& k) {
    Plane y(opponentY.width, opponentY.height);
    for (size_t i = 0; i < y.values.size(); ++i)
        y.values[i] = (opponentY.values[i] + 16.0f) / 116.0f;
    const Plane ex = flip::convolveSeparable(y, k.edge, k.smooth);
    const Plane ey = flip::convolveSeparable(y, k.smooth, k.edge);
    const Plane px = flip::convolveSeparable(y, k.point, k.smooth);
    const Plane py = flip::convolveSeparable(y, k.smooth, k.point);
    Features f{std::vector<float>(y.values.size()), std::vector<float>(y.values.size())};
    for (size_t i = 0; i < y.values.size(); ++i) {
        f.edge[i] = std::hypot(ex.values[i], ey.values[i]);
        f.point[i] = std::hypot(px.values[i], py.values[i]);
    }
    return f;
}

// LDR-ꟻLIP of two opponent images: per pixel ΔE_c^(1 − ΔE_f), all in [0,1].
std::vector<float> ldrFlip(const Opponent& test, const Opponent& reference, double ppd) {
    const std::vector<Color> labTest = filteredHuntLab(test, ppd);
    const std::vector<Color> labReference = filteredHuntLab(reference, ppd);
    const flip::FeatureKernels kernels = flip::featureKernels(ppd);
    const Features fTest = features(test.y, kernels);
    const Features fReference = features(reference.y, kernels);
    static const float cMax = maxColourError();  // a constant of the colour space
    const float pcCmax = kPc * cMax;
    std::vector<float> error(labTest.size());
    for (size_t i = 0; i < error.size(); ++i) {
        const float dc = std::pow(flip::hyab(labTest[i], labReference[i]), kQc);
        // cMax ≈ 41.3 (a constant), so neither denominator is 0.
        const float colour =
            dc < pcCmax ? kPt / pcCmax * dc : kPt + (dc - pcCmax) / (cMax - pcCmax) * (1.0f - kPt);
        const float featureDiff = std::max(std::abs(fTest.edge[i] - fReference.edge[i]),
                                           std::abs(fTest.point[i] - fReference.point[i]));
        const float feature = std::pow(featureDiff / std::numbers::sqrt2_v<float>, kQf);
        error[i] = std::pow(colour, 1.0f - feature);
    }
    return error;
}

// HDR-ꟻLIP's automatic exposure range from the reference's luminance.
std::pair<double, double> referenceExposures(const image::ImageRGBA& reference) {
    std::vector<double> luminance(size_t(reference.width) * reference.height);
    for (size_t i = 0; i < luminance.size(); ++i) {
        const float* p = &reference.pixels[i * 4];
        luminance[i] = std::max(0.0, eval::luminance(p[0], p[1], p[2]));
    }
    const double yMax = *std::max_element(luminance.begin(), luminance.end());
    // A black reference has no range: one exposure (0) evaluated twice.
    if (yMax <= 0) return {0.0, 0.0};
    // The median of the pixels that are not black: the authors' median is 0, and their stop
    // exposure infinite, once half the reference is black (a render's empty background).
    std::erase_if(luminance, [](double v) { return v <= 0; });
    auto mid = luminance.begin() + std::ptrdiff_t(luminance.size() / 2);
    std::nth_element(luminance.begin(), mid, luminance.end());
    const double x = acesInverseOfTarget();
    return {std::log2(x / yMax), std::log2(x / *mid)};
}

}  // namespace

double pixelsPerDegree(double distanceMeters, double displayWidthMeters,
                       double displayWidthPixels) {
    return distanceMeters * (displayWidthPixels / displayWidthMeters) * std::numbers::pi / 180.0;
}

double defaultPixelsPerDegree() {
    return pixelsPerDegree(kFlipDefaultDistanceMeters, kFlipDefaultDisplayWidthMeters,
                           kFlipDefaultDisplayWidthPixels);
}

const char* flipModeName(FlipMode mode) {
    return mode == FlipMode::Ldr ? "ldr" : "hdr";
}

FlipMode flipModeForFile(const std::filesystem::path& file) {
    std::string ext = file.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return std::tolower(c); });
    return ext == ".exr" || ext == ".hdr" ? FlipMode::Hdr : FlipMode::Ldr;
}

FlipResult computeFlip(const image::ImageRGBA& test, const image::ImageRGBA& reference,
                       const FlipOptions& options, const std::string& testName,
                       const std::string& referenceName) {
    checkSameSize(test, reference, testName, referenceName);
    checkFinite(test, testName);
    checkFinite(reference, referenceName);
    FlipResult r;
    r.width = test.width;
    r.height = test.height;
    r.mode = options.mode;
    r.pixelsPerDegree =
        options.pixelsPerDegree > 0 ? options.pixelsPerDegree : defaultPixelsPerDegree();
    if (!std::isfinite(r.pixelsPerDegree) || options.pixelsPerDegree < 0)
        throw InputError("ꟻLIP: pixels per degree must be a finite positive number, got " +
                         std::to_string(options.pixelsPerDegree));
    if (options.mode == FlipMode::Ldr) {
        r.errors = ldrFlip(toOpponent(test, FlipMode::Ldr, 1.0),
                           toOpponent(reference, FlipMode::Ldr, 1.0), r.pixelsPerDegree);
    } else {
        auto [start, stop] = referenceExposures(reference);
        r.startExposure = options.startExposure.value_or(start);
        r.stopExposure = options.stopExposure.value_or(stop);
        if (!std::isfinite(r.startExposure) || !std::isfinite(r.stopExposure) ||
            r.startExposure > r.stopExposure)
            throw InputError("HDR-ꟻLIP: the start exposure (" + std::to_string(r.startExposure) +
                             ") must be finite and at most the stop exposure (" +
                             std::to_string(r.stopExposure) + ")");
        r.exposureCount = uint32_t(
            std::clamp(std::ceil(r.stopExposure - r.startExposure), 2.0, double(kMaxExposures)));
        const double step = (r.stopExposure - r.startExposure) / (r.exposureCount - 1);
        r.errors.assign(size_t(test.width) * test.height, 0.0f);
        for (uint32_t e = 0; e < r.exposureCount; ++e) {
            const double scale = std::exp2(r.startExposure + e * step);
            const std::vector<float> ldr =
                ldrFlip(toOpponent(test, FlipMode::Hdr, scale),
                        toOpponent(reference, FlipMode::Hdr, scale), r.pixelsPerDegree);
            for (size_t i = 0; i < ldr.size(); ++i) r.errors[i] = std::max(r.errors[i], ldr[i]);
        }
    }
    double sum = 0;
    for (float e : r.errors) sum += e;
    r.mean = r.errors.empty() ? 0.0 : sum / double(r.errors.size());
    return r;
}

image::ImageRGBA flipMapImage(const FlipResult& result) {
    image::ImageRGBA out{result.width, result.height, std::vector<float>(result.errors.size() * 4)};
    for (size_t i = 0; i < result.errors.size(); ++i) {
        for (int c = 0; c < 3; ++c) out.pixels[i * 4 + size_t(c)] = result.errors[i];
        out.pixels[i * 4 + 3] = 1.0f;
    }
    return out;
}

nlohmann::json flipSettingsToJson(const FlipResult& result) {
    nlohmann::json j = {{"mode", flipModeName(result.mode)},
                        {"pixels_per_degree", result.pixelsPerDegree}};
    if (result.mode == FlipMode::Hdr) {
        j["start_exposure"] = result.startExposure;
        j["stop_exposure"] = result.stopExposure;
        j["exposures"] = result.exposureCount;
    }
    return j;
}

}  // namespace fovea::eval
