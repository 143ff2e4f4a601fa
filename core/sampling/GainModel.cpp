#include "core/sampling/GainModel.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

#include "core/sampling/VisualPolar.h"
#include "core/util/Error.h"

namespace fovea::sampling {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDegreesPerRadian = 180.0 / kPi;
// Radial pieces: at most this fraction of the largest radius long (<= 1 degree: no FOV point is
// more than 254.6 degrees from the gaze). Beyond the 5.79-degree knee the acuity's pole at
// e = -3.33 is then >= 9 piece lengths away, where 8-point Gauss-Legendre is accurate to
// rounding; inside it, and for the layouts' piecewise polynomials, the rule is exact.
constexpr double kRadialPieces = 256.0;
// P4 §3: FV's distribution is cut at 80 degrees ("the model begins to reach zero").
constexpr double kFvMaxDegrees = kAcuityMaxDegrees;

// 8-point Gauss-Legendre on [-1, 1] (symmetric pairs).
constexpr double kGaussNodes[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267,
                                   0.9602898564975363};
constexpr double kGaussWeights[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745,
                                     0.1012285362903763};

// The radial weight of the area element: dA = w(e) de dphi.
double areaWeight(double e, AreaMeasure measure) {
    // Solid: sin(e) in radians, scaled to square degrees (w ~ e for small e).
    return measure == AreaMeasure::Flat ? e : kDegreesPerRadian * std::sin(e / kDegreesPerRadian);
}

// F(R) = integral over [0, R] of f(e) w(e) de, tabulated at the piece ends up to rMax.
class RadialTable {
public:
    RadialTable(const std::function<double(double)>& f, const std::vector<double>& breaks,
                AreaMeasure measure, double rMax)
        : mF(f), mMeasure(measure) {
        std::vector<double> cuts = {0.0};
        for (double b : breaks)
            if (b > 0.0 && b < rMax) cuts.push_back(b);
        cuts.push_back(rMax);
        std::sort(cuts.begin(), cuts.end());
        cuts.erase(std::unique(cuts.begin(), cuts.end()), cuts.end());
        const double maxPiece = std::max(rMax / kRadialPieces, 1e-300);
        mEnds.push_back(0.0);
        for (size_t k = 1; k < cuts.size(); ++k) {
            const double a = cuts[k - 1], b = cuts[k];
            const auto pieces = std::max<size_t>(1, size_t(std::ceil((b - a) / maxPiece)));
            for (size_t i = 1; i <= pieces; ++i)
                mEnds.push_back(i == pieces ? b : a + (b - a) * double(i) / double(pieces));
        }
        mCumulative.assign(mEnds.size(), 0.0);
        for (size_t k = 1; k < mEnds.size(); ++k)
            mCumulative[k] = mCumulative[k - 1] + gauss(mEnds[k - 1], mEnds[k]);
    }

    double operator()(double r) const {
        if (!(r > 0.0)) return 0.0;
        // The piece [mEnds[k], mEnds[k + 1]) holding r (r <= rMax by construction).
        auto it = std::upper_bound(mEnds.begin(), mEnds.end(), r);
        const size_t k = size_t(std::max<std::ptrdiff_t>(it - mEnds.begin() - 1, 0));
        if (k + 1 >= mEnds.size()) return mCumulative.back();
        return mCumulative[k] + gauss(mEnds[k], r);
    }

private:
    double gauss(double a, double b) const {
        const double mid = 0.5 * (a + b), half = 0.5 * (b - a);
        double sum = 0.0;
        for (int i = 0; i < 4; ++i)
            for (double x : {mid - half * kGaussNodes[i], mid + half * kGaussNodes[i]})
                sum += kGaussWeights[i] * mF(x) * areaWeight(x, mMeasure);
        return sum * half;
    }

    const std::function<double(double)>& mF;
    AreaMeasure mMeasure;
    std::vector<double> mEnds, mCumulative;
};

// Distance from `gaze` (inside the shape) to the shape's boundary along direction `phi`.
double boundaryDistance(FovShape shape, glm::dvec2 half, glm::dvec2 gaze, double phi) {
    const double c = std::cos(phi), s = std::sin(phi);
    if (shape == FovShape::Rectangle) {
        double t = std::numeric_limits<double>::max();
        if (c > 0.0) t = std::min(t, (half.x - gaze.x) / c);
        if (c < 0.0) t = std::min(t, (-half.x - gaze.x) / c);
        if (s > 0.0) t = std::min(t, (half.y - gaze.y) / s);
        if (s < 0.0) t = std::min(t, (-half.y - gaze.y) / s);
        return std::max(t, 0.0);
    }
    // (gx + t c)^2 / a^2 + (gy + t s)^2 / b^2 = 1: the positive root, in the form without
    // cancellation (C < 0 for a gaze inside).
    const double ia = 1.0 / (half.x * half.x), ib = 1.0 / (half.y * half.y);
    const double A = c * c * ia + s * s * ib;
    const double B = 2.0 * (gaze.x * c * ia + gaze.y * s * ib);
    const double C = gaze.x * gaze.x * ia + gaze.y * gaze.y * ib - 1.0;
    const double root = std::sqrt(std::max(B * B - 4.0 * A * C, 0.0));
    const double t = B >= 0.0 ? -2.0 * C / std::max(B + root, 1e-300) : (root - B) / (2.0 * A);
    return std::max(t, 0.0);
}

struct PolarSums {
    double full = 0, half = 0, quarter = 0;  // trapezoid with N, N / 2 and N / 4 nodes
};

// The boundary distances of the N angular nodes phi_i = 2 pi i / N.
std::vector<double> boundaryDistances(FovShape shape, glm::dvec2 half, glm::dvec2 gaze,
                                      uint32_t steps) {
    std::vector<double> radii(steps);
    for (uint32_t i = 0; i < steps; ++i)
        radii[i] = boundaryDistance(shape, half, gaze, 2.0 * kPi * double(i) / double(steps));
    return radii;
}

PolarSums integrate(const std::vector<double>& radii, const std::function<double(double)>& f,
                    const std::vector<double>& breaks, AreaMeasure measure) {
    const double rMax = *std::max_element(radii.begin(), radii.end());
    const RadialTable table(f, breaks, measure, rMax);
    PolarSums s;
    for (size_t i = 0; i < radii.size(); ++i) {
        const double v = table(radii[i]);
        s.full += v;
        if (i % 2 == 0) s.half += v;
        if (i % 4 == 0) s.quarter += v;
    }
    const double h = 2.0 * kPi / double(radii.size());
    s.full *= h;
    s.half *= 2.0 * h;
    s.quarter *= 4.0 * h;
    return s;
}

uint32_t checkedSteps(uint32_t steps) {
    return std::max<uint32_t>(16, (steps + 3u) & ~3u);  // N / 2 and N / 4 rules are subsets
}

// The farthest boundary point from the gaze: a corner of a rectangle; for an oval the best of
// the angular nodes refined by a golden-section search between its neighbours.
double maxEccentricity(FovShape shape, glm::dvec2 half, glm::dvec2 gaze,
                       const std::vector<double>& radii) {
    if (shape == FovShape::Rectangle) {
        const double dx = half.x + std::abs(gaze.x), dy = half.y + std::abs(gaze.y);
        return std::sqrt(dx * dx + dy * dy);
    }
    const auto best = std::max_element(radii.begin(), radii.end());
    const double step = 2.0 * kPi / double(radii.size());
    double a = (double(best - radii.begin()) - 1.0) * step, b = a + 2.0 * step;
    const double ratio = (std::sqrt(5.0) - 1.0) / 2.0;
    for (int k = 0; k < 80; ++k) {
        const double c = b - ratio * (b - a), d = a + ratio * (b - a);
        if (boundaryDistance(shape, half, gaze, c) > boundaryDistance(shape, half, gaze, d))
            b = d;
        else
            a = c;
    }
    return std::max(*best, boundaryDistance(shape, half, gaze, 0.5 * (a + b)));
}

// The eccentricity beyond which M(e) < cpd.
double cutoffOf(double cpd) {
    if (cpd > kAcuityPeakCpd) return 0.0;
    if (cpd >= acuityCpd(std::nextafter(kAcuityKneeDegrees, 1e9))) return kAcuityKneeDegrees;
    return (std::sqrt(kAcuityTailNumerator / cpd) - 1.0) / 0.3;
}

glm::dvec2 halfFov(const DisplayModel& d) {
    return {0.5 * d.hfovDeg, 0.5 * d.vfovDeg};
}

std::string number(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", v);
    return text;
}

}  // namespace

double acuityCpd(double e) {
    if (e <= kAcuityKneeDegrees) return kAcuityPeakCpd;
    const double a = 0.3 * e + 1.0;
    return kAcuityTailNumerator / (a * a);
}

const char* toString(FovShape shape) {
    switch (shape) {
        case FovShape::Oval:
            return "oval";
        case FovShape::Rectangle:
            return "rectangle";
        case FovShape::Circle:
            return "circle";
    }
    return "?";
}

const char* toString(AreaMeasure measure) {
    return measure == AreaMeasure::Flat ? "flat" : "solid";
}

const char* toString(DetailDensity density) {
    return density == DetailDensity::Linear ? "linear" : "squared";
}

double nyquistCpd(uint32_t pixels, double fovDeg) {
    return double(pixels) / fovDeg / 2.0;
}

uint32_t nyquistPixels(double cpd, double fovDeg) {
    return uint32_t(std::max(std::round(2.0 * cpd * fovDeg), 1.0));
}

const std::vector<DisplayPreset>& displayPresets() {
    static const std::vector<DisplayPreset> presets = {
        {"perfect-hmd",
         "P1 §4: 60 c/deg (the eye's limit), oval FOV 160 x 135 degrees",
         {160.0, 135.0, FovShape::Oval, 60.0, 0, 0, {0.0, 0.0}},
         0.94},
        // 110 degrees as the diameter: P1's 70 % needs it (radius 110 gives 89 %).
        {"vive",
         "P1 §4: HTC Vive, 15.3 c/deg (P1 ref. 32), a circle of 110 degrees (P1: 'radius', read "
         "as the diameter), 2160 x 1200 pixels (1080 x 1200 per eye)",
         {110.0, 110.0, FovShape::Circle, 15.3, 1080, 1200, {0.0, 0.0}},
         0.70},
    };
    return presets;
}

const DisplayPreset* findDisplayPreset(const std::string& name) {
    for (const auto& p : displayPresets())
        if (name == p.name) return &p;
    return nullptr;
}

void checkDisplay(const DisplayModel& d, AreaMeasure measure) {
    auto fov = [](double v, const char* name) {
        if (!std::isfinite(v) || !(v > 0.0) || v > kMaxFovDegrees)
            throw InputError(std::string(name) + ": expected a FOV in (0, 360] degrees, got " +
                             number(v));
    };
    fov(d.hfovDeg, "horizontal FOV");
    fov(d.vfovDeg, "vertical FOV");
    if (d.shape == FovShape::Circle && d.hfovDeg != d.vfovDeg)
        throw InputError("circle FOV: horizontal " + number(d.hfovDeg) + " and vertical " +
                         number(d.vfovDeg) + " degrees differ");
    if (!std::isfinite(d.cpd) || !(d.cpd > 0.0) || d.cpd > kMaxDisplayCpd)
        throw InputError("cycles per degree: expected a number in (0, 1000], got " + number(d.cpd));
    const glm::dvec2 g = d.gazeDeg, h = halfFov(d);
    const bool inside = d.shape == FovShape::Rectangle
                            ? std::abs(g.x) < h.x && std::abs(g.y) < h.y
                            : (g.x / h.x) * (g.x / h.x) + (g.y / h.y) * (g.y / h.y) < 1.0;
    if (!std::isfinite(g.x) || !std::isfinite(g.y) || !inside)
        throw InputError("gaze (" + number(g.x) + ", " + number(g.y) +
                         ") degrees: not inside the " + toString(d.shape) + " FOV");
    if (measure == AreaMeasure::Solid) {
        const double e =
            maxEccentricity(d.shape, h, g, boundaryDistances(d.shape, h, g, kGainAngularSteps));
        if (e > 180.0 + 1e-9)
            throw InputError("solid-angle measure: a FOV point is " + number(e) +
                             " degrees from the gaze (at most 180)");
    }
}

glm::dvec2 integrateAroundGaze(FovShape shape, glm::dvec2 half, glm::dvec2 gaze,
                               const std::function<double(double)>& f,
                               const std::vector<double>& breaks, AreaMeasure measure,
                               uint32_t steps) {
    const auto radii = boundaryDistances(shape, half, gaze, checkedSteps(steps));
    const PolarSums s = integrate(radii, f, breaks, measure);
    return {s.full, std::max(std::abs(s.full - s.half), std::abs(s.full - s.quarter))};
}

GainResult foveationGain(const DisplayModel& d, const GainOptions& o) {
    checkDisplay(d, o.measure);
    const double c = d.cpd;
    const bool squared = o.density == DetailDensity::Squared;
    auto power = [squared](double v) { return squared ? v * v : v; };
    GainResult r;
    r.cutoffDeg = cutoffOf(c);
    // Pieces end where min(M, cpd) is not smooth: the knee and the cap.
    const std::vector<double> breaks = {kAcuityKneeDegrees, r.cutoffDeg};
    const auto radii =
        boundaryDistances(d.shape, halfFov(d), d.gazeDeg, checkedSteps(o.angularSteps));
    r.maxEccentricityDeg = maxEccentricity(d.shape, halfFov(d), d.gazeDeg, radii);
    // The same nodes and pieces for all three: where min(M, cpd) = cpd at every node (cpd below
    // the acuity at the FOV's edge) `required` equals `full` to the bit and the saving is 0.
    const PolarSums required = integrate(
        radii, [&](double e) { return power(std::min(acuityCpd(e), c)); }, breaks, o.measure);
    const PolarSums full = integrate(
        radii, [&](double) { return power(c); }, breaks, o.measure);
    const PolarSums area = integrate(
        radii, [](double) { return 1.0; }, breaks, o.measure);
    r.required = required.full;
    r.full = full.full;
    r.area = area.full;
    r.relativeSamples = std::clamp(required.full / full.full, 0.0, 1.0);
    r.saving = 1.0 - r.relativeSamples;
    auto savingOf = [](double req, double all) { return 1.0 - std::clamp(req / all, 0.0, 1.0); };
    r.errorEstimate = std::max(std::abs(r.saving - savingOf(required.half, full.half)),
                               std::abs(r.saving - savingOf(required.quarter, full.quarter)));
    return r;
}

EyeImage eyeImageOf(const DisplayModel& d) {
    EyeImage eye;
    eye.width = d.width > 0 ? d.width : nyquistPixels(d.cpd, d.hfovDeg);
    eye.height = d.height > 0 ? d.height : nyquistPixels(d.cpd, d.vfovDeg);
    // x right and y up in degrees; pixels y down.
    eye.gazePx = {eye.width * (0.5 + d.gazeDeg.x / d.hfovDeg),
                  eye.height * (0.5 - d.gazeDeg.y / d.vfovDeg)};
    return eye;
}

PeresCounts peresCounts(const EyeImage& eye, double r0, double r1, double p) {
    if (!std::isfinite(r0) || !std::isfinite(r1) || r0 < 0.0 || r1 < r0)
        throw InputError("Peres radii: expected 0 <= r0 <= r1, got r0 = " + number(r0) +
                         ", r1 = " + number(r1));
    if (!std::isfinite(p) || p < 0.0 || p > 1.0)
        throw InputError("Peres outer probability: expected [0, 1], got " + number(p));
    PeresCounts out;
    out.r0 = r0;
    out.r1 = r1;
    out.outerProbability = p;
    const glm::dvec2 size(eye.width, eye.height);
    const glm::dvec2 half = 0.5 * size;
    const std::vector<double> breaks = {r0, r1};
    const auto radii =
        boundaryDistances(FovShape::Rectangle, half, eye.gazePx - half, kGainAngularSteps);
    auto areaWithin = [&](double radius) {
        return integrate(
                   radii, [radius](double d) { return d <= radius ? 1.0 : 0.0; }, breaks,
                   AreaMeasure::Flat)
            .full;
    };
    const double pixels = size.x * size.y;
    const double inR0 = areaWithin(r0), inR1 = areaWithin(r1);
    out.area[0] = inR0;
    out.area[1] = inR1 - inR0;
    out.area[2] = pixels - inR1;
    // FoveationMask's probability: 1 at r0 falling linearly to p at r1 (seed 000 §3.2).
    const double ramp =
        r1 > r0 ? integrate(
                      radii,
                      [&](double d) {
                          return d > r0 && d <= r1 ? 1.0 + (p - 1.0) * (d - r0) / (r1 - r0) : 0.0;
                      },
                      breaks, AreaMeasure::Flat)
                      .full
                : 0.0;
    out.sampled[0] = out.area[0];
    out.sampled[1] = ramp;
    out.sampled[2] = p * out.area[2];
    for (int l = 0; l < 3; ++l) {
        out.table1Samples += kPeresSpp[l] * out.area[l];
        out.tossedSamples += kPeresSpp[l] * out.sampled[l];
    }
    out.baseSamples = kPeresSpp[0] * pixels;
    return out;
}

namespace {

// Rows j of n (t_j = (j + 0.5) / n, phi = 2 pi t) whose point gaze + r (cos phi, sin phi) lies
// on [0, W) x [0, H): the circle is cut where it crosses the four edges; each arc between two
// cuts is wholly on or off the screen.
uint64_t rowsOnScreen(uint32_t n, double r, glm::dvec2 g, glm::dvec2 screen) {
    auto onScreen = [&](double t) {
        const glm::dvec2 p = g + r * glm::dvec2(std::cos(2.0 * kPi * t), std::sin(2.0 * kPi * t));
        return p.x >= 0.0 && p.x < screen.x && p.y >= 0.0 && p.y < screen.y;
    };
    std::vector<double> cuts = {0.0, 1.0};
    auto addAngle = [&](double phi) {
        double t = phi / (2.0 * kPi);
        t -= std::floor(t);
        cuts.push_back(t);
    };
    for (double v : {-g.x / r, (screen.x - g.x) / r})  // cos phi = v
        if (std::abs(v) < 1.0) {
            addAngle(std::acos(v));
            addAngle(-std::acos(v));
        }
    for (double v : {-g.y / r, (screen.y - g.y) / r})  // sin phi = v
        if (std::abs(v) < 1.0) {
            addAngle(std::asin(v));
            addAngle(kPi - std::asin(v));
        }
    std::sort(cuts.begin(), cuts.end());
    uint64_t count = 0;
    for (size_t k = 1; k < cuts.size(); ++k) {
        const double a = cuts[k - 1], b = cuts[k];
        if (!(b > a) || !onScreen(0.5 * (a + b))) continue;
        // j with a <= (j + 0.5) / n < b.
        const double first = std::clamp(std::ceil(a * n - 0.5), 0.0, double(n));
        const double end = std::clamp(std::ceil(b * n - 0.5), 0.0, double(n));
        if (end > first) count += uint64_t(end - first);
    }
    return count;
}

}  // namespace

VisualPolarCounts visualPolarCounts(const EyeImage& eye, double reduction, double foveaFraction) {
    VisualPolarCounts out;
    out.reduction = reduction;
    out.foveaFraction = foveaFraction;
    // VisualPolarWarp: the side-by-side image (two eyes) scaled by float(s), rounded up, and
    // split between the eyes (warp.comp makeMap).
    const double s = double(float(visualPolarScale(reduction, foveaFraction)));
    const auto total = uint32_t(std::max(std::ceil(2.0 * eye.width * s), 1.0));
    const VisualPolarGrid grid = VisualPolarGrid::make(
        std::max(total / 2, 1u), uint32_t(std::max(std::ceil(eye.height * s), 1.0)), foveaFraction);
    out.gridWidth = grid.width;
    out.gridHeight = grid.height;
    const glm::dvec2 screen(eye.width, eye.height);
    const VisualPolarMapping m = VisualPolarMapping::make(grid, screen, eye.gazePx / screen);
    for (uint32_t i = 0; i < grid.width; ++i) {
        const uint32_t n = grid.rows(i);
        out.validTexels += n;
        out.tracedTexels += rowsOnScreen(n, m.radius((i + 0.5) / grid.width), m.gaze, screen);
    }
    return out;
}

FvCounts fvCounts(const DisplayModel& d, double budget) {
    checkDisplay(d);
    if (!std::isfinite(budget) || budget < 0.0)
        throw InputError("FV budget: expected a number >= 0, got " + number(budget));
    const EyeImage eye = eyeImageOf(d);
    // P4 Eq. 1: m(e) = M(e) / 60, sampled in flat polar coordinates (P4 Eq. 2-6) out to 80.
    auto m = [](double e) { return e <= kFvMaxDegrees ? acuityCpd(e) / kAcuityPeakCpd : 0.0; };
    const std::vector<double> breaks = {kAcuityKneeDegrees, kFvMaxDegrees};
    const double all = integrateAroundGaze(FovShape::Circle, {kFvMaxDegrees, kFvMaxDegrees},
                                           {0.0, 0.0}, m, breaks, AreaMeasure::Flat)
                           .x;
    const double inside =
        integrateAroundGaze(d.shape, halfFov(d), d.gazeDeg, m, breaks, AreaMeasure::Flat).x;
    FvCounts out;
    out.budget = budget;
    out.insideFraction = std::clamp(inside / all, 0.0, 1.0);
    out.samplesInFov = budget * out.insideFraction;
    out.frameFraction = out.samplesInFov / (double(eye.width) * eye.height);
    // Samples per square degree at the gaze: budget m(0) / all; pixels per square degree:
    // (W / hfov) (H / vfov).
    const double pixelsPerDeg2 = (eye.width / d.hfovDeg) * (eye.height / d.vfovDeg);
    out.gazeSpp = budget / all / pixelsPerDeg2;
    return out;
}

}  // namespace fovea::sampling
