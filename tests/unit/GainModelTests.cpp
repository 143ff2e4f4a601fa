// P1's foveation gain model (core/sampling/GainModel.h, seed 003 P1 §4): P1's two numbers,
// closed forms and a Cartesian sum against the polar quadrature, the properties a wrong
// integral breaks (monotone in FOV and cpd, 0 below the edge's acuity, the centred gaze as the
// lower bound), and the layouts' counts against seed 000 Table 1 and brute-force counts.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/sampling/GainModel.h"
#include "core/sampling/VisualPolar.h"
#include "core/util/Error.h"

using namespace fovea::sampling;

namespace {

constexpr double kPi = std::numbers::pi;

DisplayModel gainDisplay(double h, double v, FovShape shape, double cpd,
                         glm::dvec2 gaze = {0.0, 0.0}) {
    DisplayModel d;
    d.hfovDeg = h;
    d.vfovDeg = v;
    d.shape = shape;
    d.cpd = cpd;
    d.gazeDeg = gaze;
    return d;
}

// P1 Eq. 2 integrated by hand over a centred disc of radius R (flat measure, samples ~ cpd):
// e M(e) = 449.4 e / (0.3 e + 1)^2 has the antiderivative (449.4 / 0.09) (ln a + 1 / a).
double closedFormSaving(double radius, double cpd) {
    auto tail = [](double e) {
        const double a = 0.3 * e + 1.0;
        return 449.4 / 0.09 * (std::log(a) + 1.0 / a);
    };
    const double ec = cpd >= 59.99 ? 5.79 : (std::sqrt(449.4 / cpd) - 1.0) / 0.3;
    const double flat = std::min(cpd, 60.0);
    double half = 0.0;  // integral over [0, R] of min(M, cpd) e de
    if (radius <= ec) {
        half = flat * radius * radius / 2.0;
    } else {
        half = flat * ec * ec / 2.0 + tail(radius) - tail(ec);
    }
    return 1.0 - half / (cpd * radius * radius / 2.0);
}

// Midpoint sum on an n x n Cartesian grid over the FOV's bounding box (flat, linear).
double cartesianSaving(const DisplayModel& d, int n) {
    const double a = d.hfovDeg / 2.0, b = d.vfovDeg / 2.0;
    double required = 0.0, full = 0.0;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const double x = -a + (i + 0.5) * 2.0 * a / n, y = -b + (j + 0.5) * 2.0 * b / n;
            if (d.shape != FovShape::Rectangle && (x / a) * (x / a) + (y / b) * (y / b) > 1.0)
                continue;
            const double e = std::hypot(x - d.gazeDeg.x, y - d.gazeDeg.y);
            required += std::min(acuityCpd(e), d.cpd);
            full += d.cpd;
        }
    return 1.0 - required / full;
}

}  // namespace

// P1 §4: "94 % of the details are unresolvable" (perfect HMD) and "at least 70 %" (Vive). P1
// gives whole percents, so the tolerance is half a percent; the exact values are pinned too.
TEST(GainModel, ReproducesP1sNumbers) {
    const GainResult perfect = foveationGain(findDisplayPreset("perfect-hmd")->display);
    EXPECT_NEAR(perfect.saving, 0.94, 0.005);
    EXPECT_NEAR(perfect.saving, 0.938141, 1e-6);
    const GainResult vive = foveationGain(findDisplayPreset("vive")->display);
    EXPECT_NEAR(vive.saving, 0.70, 0.005);
    EXPECT_NEAR(vive.saving, 0.702810, 1e-6);
    EXPECT_NEAR(vive.cutoffDeg, 14.732, 1e-3);  // 449.4 / (0.3 e + 1)^2 = 15.3
    // The reading: a 110-degree *radius* would save 89 %, not P1's 70 %.
    EXPECT_NEAR(foveationGain(gainDisplay(220, 220, FovShape::Circle, 15.3)).saving, 0.891, 1e-3);
    // Solid angle instead of flat polar degrees gives 93.3 % and 69.3 %: it does not round to
    // P1's numbers, which is why flat is the default.
    GainOptions solid;
    solid.measure = AreaMeasure::Solid;
    EXPECT_NEAR(foveationGain(findDisplayPreset("perfect-hmd")->display, solid).saving, 0.9328,
                1e-4);
    EXPECT_NEAR(foveationGain(findDisplayPreset("vive")->display, solid).saving, 0.6929, 1e-4);
}

TEST(GainModel, AcuityIsP1Eq2) {
    EXPECT_EQ(acuityCpd(0.0), 60.0);
    EXPECT_EQ(acuityCpd(5.79), 60.0);
    EXPECT_NEAR(acuityCpd(5.8), 449.4 / (2.74 * 2.74), 1e-12);
    EXPECT_NEAR(acuityCpd(30.0), 449.4 / 100.0, 1e-12);
    // P4 Eq. 1 is the same curve divided by 60: 7.49 = 449.4 / 60.
    EXPECT_NEAR(acuityCpd(40.0) / 60.0, 7.49 / (13.0 * 13.0), 1e-12);
}

TEST(GainModel, CentredCircleMatchesClosedForm) {
    for (double diameter : {8.0, 30.0, 110.0, 220.0, 360.0})
        for (double cpd : {2.0, 15.3, 40.0, 60.0, 120.0}) {
            const GainResult r =
                foveationGain(gainDisplay(diameter, diameter, FovShape::Circle, cpd));
            EXPECT_NEAR(r.saving, closedFormSaving(diameter / 2.0, cpd), 1e-12)
                << diameter << " deg at " << cpd << " c/deg";
            EXPECT_NEAR(r.area, kPi * diameter * diameter / 4.0, 1e-9 * diameter * diameter);
        }
}

// Rectangles and an off-centre gaze have corners and kinks in the angular integrand: the
// quadrature must still agree with a plain Cartesian sum, and its error estimate must cover the
// difference to a 16x finer rule.
TEST(GainModel, PolarQuadratureMatchesCartesianSum) {
    const DisplayModel cases[] = {
        gainDisplay(100, 80, FovShape::Rectangle, 20, {10, -5}),
        gainDisplay(100, 100, FovShape::Rectangle, 8),
        gainDisplay(90, 90, FovShape::Rectangle, 25, {40, -40}),
        gainDisplay(160, 135, FovShape::Oval, 30, {30, 20}),
    };
    for (const auto& d : cases) {
        const GainResult r = foveationGain(d);
        EXPECT_NEAR(r.saving, cartesianSaving(d, 2000), 2e-6) << d.hfovDeg << "x" << d.vfovDeg;
        EXPECT_LT(r.errorEstimate, 1e-6);
        GainOptions fine;
        fine.angularSteps = 16 * kGainAngularSteps;
        EXPECT_LE(std::abs(r.saving - foveationGain(d, fine).saving), r.errorEstimate + 1e-12);
    }
}

// A display showing less than the fovea's 60 c/deg saves more the wider its FOV; nothing while
// the whole FOV lies inside the cap's eccentricity.
TEST(GainModel, WiderFovSavesMore) {
    for (FovShape shape : {FovShape::Circle, FovShape::Oval, FovShape::Rectangle}) {
        double previous = -1.0;
        for (double fov = 10.0; fov <= 360.0; fov += 10.0) {
            const double s =
                foveationGain(
                    gainDisplay(fov, fov * (shape == FovShape::Circle ? 1.0 : 0.8), shape, 15.3))
                    .saving;
            EXPECT_GE(s, previous) << toString(shape) << " " << fov;
            if (fov >= 40.0) {
                EXPECT_GT(s, previous + 1e-3) << toString(shape) << " " << fov;
            }
            previous = s;
        }
    }
}

// Where the display's cpd is at most the acuity at the farthest FOV point, min(M, cpd) = cpd
// everywhere: nothing is unresolvable, the saving is exactly 0. Just above, it is positive.
TEST(GainModel, NoSavingBelowTheEdgesAcuity) {
    // Circle of radius 10: M(10) = 449.4 / 16 = 28.09 c/deg.
    EXPECT_EQ(foveationGain(gainDisplay(20, 20, FovShape::Circle, 28.0)).saving, 0.0);
    EXPECT_GT(foveationGain(gainDisplay(20, 20, FovShape::Circle, 28.2)).saving, 0.0);
    // Rectangle 40 x 30: the corner is 25 degrees away, M(25) = 6.22 c/deg.
    const GainResult r = foveationGain(gainDisplay(40, 30, FovShape::Rectangle, 6.0));
    EXPECT_EQ(r.saving, 0.0);
    EXPECT_NEAR(r.maxEccentricityDeg, 25.0, 1e-9);
    EXPECT_GT(foveationGain(gainDisplay(40, 30, FovShape::Rectangle, 6.5)).saving, 0.0);
    // Inside the flat 5.79 degrees nothing can be saved at any cpd up to 60.
    EXPECT_EQ(foveationGain(gainDisplay(11, 11, FovShape::Circle, 60.0)).saving, 0.0);
}

// More cpd saves more (min(M, c) / c falls with c); above 60 c/deg the required detail is the
// eye's, so the relative count halves when the cpd doubles.
TEST(GainModel, MoreCpdSavesMore) {
    double previous = -1.0;
    for (double cpd = 1.0; cpd <= 120.0; cpd *= 1.25) {
        const double s = foveationGain(gainDisplay(160, 135, FovShape::Oval, cpd)).saving;
        EXPECT_GE(s, previous) << cpd;
        previous = s;
    }
    const GainResult at60 = foveationGain(gainDisplay(160, 135, FovShape::Oval, 60));
    const GainResult at120 = foveationGain(gainDisplay(160, 135, FovShape::Oval, 120));
    EXPECT_NEAR(at120.relativeSamples, at60.relativeSamples / 2.0, 1e-12);
    EXPECT_NEAR(at120.required, at60.required, 1e-9 * at60.required);
}

// P1: the gaze at the FOV centre needs the most detail, so it gives the lower bound (Anderson's
// theorem: a symmetric convex FOV, an acuity falling with eccentricity).
TEST(GainModel, CentredGazeIsTheLowerBound) {
    for (FovShape shape : {FovShape::Circle, FovShape::Oval, FovShape::Rectangle}) {
        const double v = shape == FovShape::Circle ? 110.0 : 90.0;
        const double centred = foveationGain(gainDisplay(110, v, shape, 15.3)).saving;
        for (glm::dvec2 gaze : {glm::dvec2(10, 0), glm::dvec2(0, -20), glm::dvec2(30, 25)})
            EXPECT_GT(foveationGain(gainDisplay(110, v, shape, 15.3, gaze)).saving, centred)
                << toString(shape) << " " << gaze.x << "," << gaze.y;
    }
}

// Samples ~ cpd^2 saves more than ~ cpd; solid angle weighs the (cheaper) periphery less than
// flat degrees, so it saves less.
TEST(GainModel, DensityAndMeasureOptionsOrder) {
    GainOptions squared, solid;
    squared.density = DetailDensity::Squared;
    solid.measure = AreaMeasure::Solid;
    for (const auto& p : displayPresets()) {
        const double linear = foveationGain(p.display).saving;
        EXPECT_GT(foveationGain(p.display, squared).saving, linear) << p.name;
        EXPECT_LT(foveationGain(p.display, solid).saving, linear) << p.name;
    }
    // The solid area of a 180-degree-radius disc is the whole sphere: 4 pi sr in square degrees.
    const double sphere = 4.0 * kPi * (180.0 / kPi) * (180.0 / kPi);
    EXPECT_NEAR(foveationGain(gainDisplay(360, 360, FovShape::Circle, 10), solid).area, sphere,
                1e-9 * sphere);
}

TEST(GainModel, RejectsDisplaysItCannotEvaluate) {
    EXPECT_THROW(checkDisplay(gainDisplay(0, 100, FovShape::Oval, 10)), fovea::InputError);
    EXPECT_THROW(checkDisplay(gainDisplay(400, 100, FovShape::Oval, 10)), fovea::InputError);
    EXPECT_THROW(checkDisplay(gainDisplay(100, NAN, FovShape::Oval, 10)), fovea::InputError);
    EXPECT_THROW(checkDisplay(gainDisplay(100, 90, FovShape::Circle, 10)), fovea::InputError);
    EXPECT_THROW(checkDisplay(gainDisplay(100, 100, FovShape::Oval, 0)), fovea::InputError);
    EXPECT_THROW(checkDisplay(gainDisplay(100, 100, FovShape::Oval, 2000)), fovea::InputError);
    EXPECT_THROW(checkDisplay(gainDisplay(100, 100, FovShape::Oval, 10, {40, 40})),
                 fovea::InputError);  // outside the oval, inside its bounding box
    EXPECT_NO_THROW(checkDisplay(gainDisplay(100, 100, FovShape::Rectangle, 10, {40, 40})));
    EXPECT_THROW(checkDisplay(gainDisplay(360, 360, FovShape::Rectangle, 10), AreaMeasure::Solid),
                 fovea::InputError);  // corners 254 degrees from the gaze
    EXPECT_EQ(findDisplayPreset("quest2"), nullptr);
}

TEST(GainModel, NyquistResolution) {
    EXPECT_NEAR(nyquistCpd(1080, 110.0), 4.909, 1e-3);
    EXPECT_EQ(nyquistPixels(60.0, 160.0), 19200u);
    EXPECT_EQ(nyquistPixels(60.0, 135.0), 16200u);
    const EyeImage eye = eyeImageOf(gainDisplay(100, 50, FovShape::Rectangle, 10, {25, 10}));
    EXPECT_EQ(eye.width, 2000u);
    EXPECT_EQ(eye.height, 1000u);
    EXPECT_NEAR(eye.gazePx.x, 1500.0, 1e-9);
    EXPECT_NEAR(eye.gazePx.y, 300.0, 1e-9);  // y up in degrees, down in pixels
}

// Seed 000 Table 1's areas are pi r^2 and the rest of the eye image, exactly what the continuous
// count gives (FHD 960 x 1080 and Quest 2 1832 x 1920, centred gaze).
TEST(GainModel, PeresCountsReproduceTable1) {
    const PeresCounts fhd = peresCounts({960, 1080, {480, 540}}, 144, 288, 0.5);
    EXPECT_NEAR(fhd.area[0], 65144, 0.5);
    EXPECT_NEAR(fhd.area[1], 195432, 0.5);
    EXPECT_NEAR(fhd.area[2], 776224, 0.5);
    EXPECT_NEAR(fhd.table1Samples, 260576 + 586296 + 1552448, 2.0);
    EXPECT_NEAR(fhd.table1Samples / fhd.baseSamples, 0.579, 5e-4);  // docs/pipelines.md
    const PeresCounts quest = peresCounts({1832, 1920, {916, 960}}, 265, 530, 0.5);
    EXPECT_NEAR(quest.area[0], 220618, 0.5);
    EXPECT_NEAR(quest.area[1], 661855, 0.5);
    EXPECT_NEAR(quest.area[2], 2634967, 0.5);
}

// The expected count of §3.2's toss against the sum over pixel centres of FoveationMask's
// probability (off-centre gaze, the rings cut by the image's edges).
TEST(GainModel, PeresTossedCountMatchesPixelSum) {
    const uint32_t w = 240, h = 270;
    const glm::dvec2 gaze(70.0, 200.0);
    const double r0 = 36, r1 = 72, p = 0.5;
    double expected = 0.0;
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            const double d = std::hypot(x + 0.5 - gaze.x, y + 0.5 - gaze.y);
            expected += d <= r0   ? 4.0
                        : d <= r1 ? 3.0 * (1.0 + (p - 1.0) * (d - r0) / (r1 - r0))
                                  : 2.0 * p;
        }
    const PeresCounts c = peresCounts({w, h, gaze}, r0, r1, p);
    EXPECT_NEAR(c.tossedSamples, expected, 1e-3 * expected);
    EXPECT_NEAR(c.area[0] + c.area[1] + c.area[2], double(w) * h, 1e-6);
    EXPECT_THROW(peresCounts({w, h, gaze}, 50, 40, p), fovea::InputError);
}

// Visual-Polar: the grid VisualPolarWarp builds for a stereo render and, exactly, the texels
// whose centre VisualPolarMapping puts on the screen.
TEST(GainModel, VisualPolarCountsMatchTheMapping) {
    struct Case {
        uint32_t w, h;
        glm::dvec2 gaze01;
        double reduction, foveaFraction;
    };
    for (const Case& c :
         {Case{128, 96, {0.3, 0.6}, 0.61, 0.24}, Case{1080, 1200, {0.5, 0.5}, 0.61, 0.24},
          Case{333, 201, {0.9, 0.05}, 0.75, 0.1}}) {
        const glm::dvec2 screen(c.w, c.h);
        const VisualPolarCounts v =
            visualPolarCounts({c.w, c.h, c.gaze01 * screen}, c.reduction, c.foveaFraction);
        const double s = double(float(visualPolarScale(c.reduction, c.foveaFraction)));
        EXPECT_EQ(v.gridWidth, uint32_t(std::ceil(2.0 * c.w * s)) / 2);
        EXPECT_EQ(v.gridHeight, uint32_t(std::ceil(c.h * s)));
        const auto grid = VisualPolarGrid::make(v.gridWidth, v.gridHeight, c.foveaFraction);
        const auto m = VisualPolarMapping::make(grid, screen, c.gaze01);
        uint64_t traced = 0;
        for (uint32_t i = 0; i < grid.width; ++i)
            for (uint32_t j = 0; j < grid.rows(i); ++j) {
                const glm::dvec2 p = m.texelToScreen(i, j);
                traced += p.x >= 0 && p.x < c.w && p.y >= 0 && p.y < c.h;
            }
        EXPECT_EQ(v.validTexels, grid.validTexels()) << c.w;
        EXPECT_EQ(v.tracedTexels, traced) << c.w;
        EXPECT_LT(v.tracedTexels, v.validTexels) << c.w;
    }
}

// P4's FV: all of its budget lands inside an 80-degree disc around the gaze; the normalization
// is P4 Eq. 5's h(80) = 1091.31 up to Eq. 2's 0.26 % step at 5.79 degrees (0.05 % overall).
TEST(GainModel, FvCountsFollowP4) {
    DisplayModel wide = gainDisplay(160, 160, FovShape::Circle, 10);
    wide.width = wide.height = 1600;
    const FvCounts all = fvCounts(wide, 100000);
    EXPECT_NEAR(all.insideFraction, 1.0, 1e-12);
    EXPECT_NEAR(all.frameFraction, 100000.0 / (1600.0 * 1600.0), 1e-12);
    // 10 x 10 pixels per square degree; density at the gaze budget / h(80) per square degree.
    EXPECT_NEAR(all.gazeSpp, 100000.0 / acuityCdfRaw(80.0) / 100.0, 1e-3 * all.gazeSpp);
    const FvCounts vive = fvCounts(findDisplayPreset("vive")->display, 100000);
    EXPECT_GT(vive.insideFraction, 0.8);
    EXPECT_LT(vive.insideFraction, 0.9);
}
