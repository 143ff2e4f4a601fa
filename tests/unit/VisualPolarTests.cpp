// The Visual-Polar mapping (core/sampling/VisualPolar.h, seed 003 P5 §3.2): constants of Eq. 2-3,
// the fit's error against the exact inverse, round trips, the sample budget and the screen-space
// sample density against the acuity model per eccentricity band.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "core/sampling/BlockGrid.h"
#include "core/sampling/VisualPolar.h"

using namespace fovea::sampling;

namespace {

VisualPolarMapping mappingFor(uint32_t screenW, uint32_t screenH, double reduction,
                              glm::dvec2 gaze01) {
    double s = visualPolarScale(reduction, kVisualPolarFoveaFraction);
    auto grid = VisualPolarGrid::make(uint32_t(std::ceil(screenW * s)),
                                      uint32_t(std::ceil(screenH * s)), kVisualPolarFoveaFraction);
    return VisualPolarMapping::make(grid, {screenW, screenH}, gaze01);
}

// The normalized acuity m(e) of P4 Eq. 1: 1 up to 5.79 degrees, 7.49 / (0.3 e + 1)^2 beyond.
double acuity(double e) {
    return e <= 5.79 ? 1.0 : 7.49 / ((0.3 * e + 1) * (0.3 * e + 1));
}

}  // namespace

TEST(VisualPolar, Eq2ConstantsAndContinuity) {
    EXPECT_NEAR(acuityCdfRaw(80.0), 1091.31, 0.01);
    EXPECT_NEAR(acuityCdfRaw(5.79), std::numbers::pi * 5.79 * 5.79, 1e-9);
    // Finding: the branches do NOT meet exactly at 5.79 degrees (denoiser-specs §3 says they
    // do): Eq. 2's tail gives 105.046 there, pi 5.79^2 = 105.319, a 0.26 % step down. The mapping
    // never evaluates the flat branch (rho_f >= 0.1, i.e. the fovea edge lies beyond 9.5
    // degrees), so the step cannot break its monotonicity; this pins the number.
    EXPECT_NEAR(acuityCdfRaw(5.79) - acuityCdfRaw(5.79 + 1e-9), 0.2728, 1e-3);
    EXPECT_GE(VisualPolarGrid::make(8, 8, 0.01).foveaFraction, kVisualPolarMinFoveaFraction);
    EXPECT_GT(VisualPolarGrid::make(8, 8, kVisualPolarMinFoveaFraction).foveaDegrees, 5.79);
    EXPECT_NEAR(acuityCdf(5.79), 0.09651, 1e-5);
    EXPECT_DOUBLE_EQ(acuityCdf(80.0), 1.0);
    // The derivative is the radial pdf 2 pi e m(e) / h(80) (Eq. 2's 166.4 pi 0.09 = 2 pi 7.488
    // against P4's 7.49: 2.7e-4 apart).
    for (double e : {1.0, 5.0, 7.0, 20.0, 60.0}) {
        double h = 1e-6;
        double numeric = (acuityCdf(e + h) - acuityCdf(e - h)) / (2 * h);
        EXPECT_NEAR(acuityCdfDerivative(e), numeric, 1e-7) << e;
        EXPECT_NEAR(acuityCdfDerivative(e), 2 * std::numbers::pi * e * acuity(e) / 1091.3132,
                    5e-4 * acuityCdfDerivative(e))
            << e;
    }
}

// P5 Eq. 3 against the exact inverse of Eq. 2 on its domain u in [f(5.79), 1] (output 5.79..80
// normalized degrees). Measured: max 0.030 degrees absolute (at u = 1), 0.31 % relative (near
// u = 0.15); its derivative (the sample density) is up to 2.4 % off, which is why the mapping
// refines it with Newton steps (docs/visual-polar.md).
TEST(VisualPolar, Eq3FitErrorAgainstExactInverse) {
    double u0 = acuityCdf(5.79), maxAbs = 0, maxRel = 0, maxSlope = 0;
    for (int k = 0; k <= 2000; ++k) {
        double u = u0 + (1 - u0) * k / 2000.0;
        double exact = acuityInverse(u);
        EXPECT_NEAR(acuityCdf(exact), u, 1e-12);
        double err = std::abs(acuityInversePolynomial(u) - exact);
        maxAbs = std::max(maxAbs, err);
        maxRel = std::max(maxRel, err / exact);
        if (k > 0 && k < 2000) {
            double h = 1e-5;
            double dP = (acuityInversePolynomial(u + h) - acuityInversePolynomial(u - h)) / (2 * h);
            double dE = 1.0 / acuityCdfDerivative(exact);
            maxSlope = std::max(maxSlope, std::abs(dP / dE - 1));
        }
    }
    EXPECT_NEAR(acuityInversePolynomial(0.0965), 5.795, 1e-3);
    EXPECT_NEAR(acuityInversePolynomial(1.0), 79.97, 1e-9);
    EXPECT_LT(maxAbs, 0.031);
    EXPECT_GT(maxAbs, 0.025);  // the fit is not exact: this test would notice a silent swap
    EXPECT_LT(maxRel, 0.0035);
    EXPECT_GT(maxSlope, 0.015);
    EXPECT_LT(maxSlope, 0.03);
    // Below the flat part the inverse is closed form.
    EXPECT_NEAR(acuityInverse(acuityCdf(3.0)), 3.0, 1e-12);
    EXPECT_DOUBLE_EQ(acuityInverse(0.0), 0.0);
}

TEST(VisualPolar, RoundTripScreenToVpToScreenEveryPixel) {
    const uint32_t w = 160, h = 180;
    std::vector<glm::dvec2> gazes = {{0.5, 0.5}, {0.1, 0.8}, {0, 0},     {1, 1},
                                     {1, 0},     {0.5, 0},   {0.97, 0.5}};
    for (glm::dvec2 g : gazes) {
        auto m = mappingFor(w, h, 0.61, g);
        double worst = 0;
        auto check = [&](glm::dvec2 p) {
            glm::dvec2 vp = m.toVisualPolar(p);
            ASSERT_TRUE(std::isfinite(vp.x) && std::isfinite(vp.y));
            ASSERT_LE(vp.x, 1.0 + 1e-12);
            ASSERT_GE(vp.y, 0.0);
            ASSERT_LT(vp.y, 1.0);
            glm::dvec2 back = m.toScreen(vp.x, vp.y);
            worst = std::max(worst, glm::length(back - p));
        };
        for (uint32_t y = 0; y < h; ++y)
            for (uint32_t x = 0; x < w; ++x) check({x + 0.5, y + 0.5});
        for (glm::dvec2 c :
             {glm::dvec2(0, 0), glm::dvec2(w, 0), glm::dvec2(0, h), glm::dvec2(w, h)})
            check(c);
        check(m.gaze);  // rho = 0 singularity
        check(m.gaze + glm::dvec2(1e-7, 0));
        EXPECT_LT(worst, 1e-3) << "gaze " << g.x << "," << g.y;
        EXPECT_EQ(m.toVisualPolar(m.gaze), glm::dvec2(0, 0));
        // The farthest corner is at rho = 1.
        double far = 0;
        for (glm::dvec2 c :
             {glm::dvec2(0, 0), glm::dvec2(w, 0), glm::dvec2(0, h), glm::dvec2(w, h)})
            far = std::max(far, m.toVisualPolar(c).x);
        EXPECT_NEAR(far, 1.0, 1e-9);
    }
}

TEST(VisualPolar, RoundTripTexelToScreenToVp) {
    auto m = mappingFor(128, 96, 0.61, {0.3, 0.6});
    for (uint32_t i = 0; i < m.grid.width; ++i)
        for (uint32_t j = 0; j < m.grid.rows(i); ++j) {
            glm::dvec2 p = m.texelToScreen(i, j);
            glm::dvec2 vp = m.toVisualPolar(p);
            EXPECT_NEAR(vp.x, (i + 0.5) / m.grid.width, 1e-9);
            EXPECT_NEAR(vp.y, (j + 0.5) / m.grid.rows(i), 1e-9);
        }
}

// P5 §3.2 / §4.2: 1280x1440 -> 853x960 (2/3 per axis), clip 12 %, 61 % fewer samples.
TEST(VisualPolar, SampleBudget) {
    auto grid = VisualPolarGrid::make(853, 960, kVisualPolarFoveaFraction);
    EXPECT_EQ(grid.rows(0), 3u);  // ceil(960 (0.5 / 853) / 0.24), never 0
    EXPECT_EQ(grid.rows(852), 960u);
    EXPECT_EQ(grid.validTexels(), 720717u);
    EXPECT_NEAR(double(grid.validTexels()) / (1280.0 * 1440.0), 0.391, 0.002);
    EXPECT_NEAR(visualPolarScale(0.61, 0.24), 2.0 / 3.0, 2e-3);
    // Every allowed reduction: valid texels = (1 - reduction) x pixels within 0.5 % of the
    // pixels (ceil of the size and of the fovea rows).
    for (double reduction : {0.5, 0.61, 0.75, 0.88}) {
        for (glm::uvec2 size : {glm::uvec2(1280, 1440), glm::uvec2(256, 256)}) {
            double s = visualPolarScale(reduction, 0.24);
            auto g = VisualPolarGrid::make(uint32_t(std::ceil(size.x * s)),
                                           uint32_t(std::ceil(size.y * s)), 0.24);
            double pixels = double(size.x) * size.y;
            EXPECT_NEAR(g.validTexels() / pixels, 1 - reduction, 0.005 + 2.0 * size.y * s / pixels)
                << reduction << " at " << size.x;
        }
    }
}

// n(i) = ceil(H rho / rho_f) with kVisualPolarRowsSlack: an exact integer stays that integer (a
// 70x70 grid at rho_f 0.1 has one in every fovea column: 10 i + 5; the shader's float had given
// column 4 46 rows), and so does a value less than the slack above one (column 112 of 1280x1440's
// 853x959 grid: 527.0003), on both twins alike.
TEST(VisualPolar, RowsOfAnIntegerHeightAreThatInteger) {
    auto square = VisualPolarGrid::make(70, 70, 0.1);
    for (uint32_t i = 0; i < 7; ++i) EXPECT_EQ(square.rows(i), 10 * i + 5) << i;
    EXPECT_EQ(square.rows(7), 70u);
    auto p5 = VisualPolarGrid::make(853, 959, kVisualPolarFoveaFraction);
    EXPECT_NEAR(959 * (112.5 / 853) / kVisualPolarFoveaFraction, 527.0003, 1e-4);
    EXPECT_EQ(p5.rows(112), 527u);
    EXPECT_EQ(p5.rows(113), 532u);  // ceil(531.69)
}

// Screen-space density of the VP grid: count texel centres per annulus, divide by its area, and
// compare with the model: uniform W H 80^2 rho_f / (2 pi dMax^2 e_f^2) in the fovea, and
// W H 80^2 f'(e) / (2 pi e dMax^2) (prop. to m(e), Eq. 2's derivative) beyond.
TEST(VisualPolar, DensityFollowsAcuityPerEccentricityBand) {
    auto m = mappingFor(1280, 1440, 0.61, {0.5, 0.5});
    const auto& g = m.grid;
    std::vector<double> columnRadius(g.width);
    for (uint32_t i = 0; i < g.width; ++i) columnRadius[i] = m.radius((i + 0.5) / g.width);
    double rf = m.radius(g.foveaFraction);
    EXPECT_NEAR(rf, 128.1, 0.5);  // denoiser-specs §3: fovea radius at a centre gaze
    auto measured = [&](double r0, double r1) {
        double count = 0;
        for (uint32_t i = 0; i < g.width; ++i)
            if (columnRadius[i] >= r0 && columnRadius[i] < r1) count += g.rows(i);
        return count / (std::numbers::pi * (r1 * r1 - r0 * r0));
    };
    double W = g.width, H = g.height, d2 = m.dMax * m.dMax;
    double fovea = W * H * 80 * 80 * g.foveaFraction /
                   (2 * std::numbers::pi * d2 * g.foveaDegrees * g.foveaDegrees);
    auto model = [&](double r) {
        if (r < rf) return fovea;
        double e = r * 80 / m.dMax;
        return W * H * 80 * 80 * acuityCdfDerivative(e) / (2 * std::numbers::pi * e * d2);
    };
    // Fovea band (0..rf): uniform (the ceil of the row count adds < 3 % beyond 0.3 rf).
    EXPECT_NEAR(measured(0.3 * rf, 0.98 * rf) / fovea, 1.0, 0.03);
    EXPECT_GT(fovea, 1.0);  // P5: "more than 1 spp" in the fovea
    EXPECT_NEAR(fovea, 1.91, 0.03);
    // Periphery bands: density / model within 3 %, and proportional to m(e).
    for (double r : {200.0, 300.0, 500.0, 900.0}) {
        double a = measured(r * 0.95, r * 1.05), b = model(r);
        EXPECT_NEAR(a / b, 1.0, 0.03) << "r = " << r;
        double e = r * 80 / m.dMax, e0 = 200 * 80 / m.dMax;
        EXPECT_NEAR(b / model(200.0), acuity(e) / acuity(e0), 0.01 * acuity(e) / acuity(e0));
    }
    EXPECT_NEAR(model(300.0), 0.54, 0.02);
    EXPECT_NEAR(model(900.0), 0.071, 0.003);
}

TEST(VisualPolar, NeighbourWrapsPhiAndClampsRho) {
    auto g = VisualPolarGrid::make(40, 30, 0.24);
    uint32_t inner = 2, outer = 20;
    ASSERT_LT(g.rows(inner), g.height);
    EXPECT_EQ(visualPolarNeighbour(g, {outer, 29}, {0, 1}), glm::ivec2(outer, 0));
    EXPECT_EQ(visualPolarNeighbour(g, {outer, 0}, {0, -1}), glm::ivec2(outer, 29));
    EXPECT_EQ(visualPolarNeighbour(g, {0, 1}, {-1, 0}), glm::ivec2(0, 1));
    EXPECT_EQ(visualPolarNeighbour(g, {39, 5}, {3, 0}).x, 39);
    int n = int(g.rows(inner));
    EXPECT_EQ(visualPolarNeighbour(g, {int(inner), n - 1}, {0, 1}), glm::ivec2(inner, 0));
    // Across columns of different heights phi is kept: row 0 of the inner column (phi =
    // pi / n) lands on the outer-column row containing that phi.
    glm::ivec2 across = visualPolarNeighbour(g, {int(inner) + 1, 0}, {-1, 0});
    EXPECT_EQ(across.x, int(inner));
    double t = 0.5 / g.rows(inner + 1);
    EXPECT_EQ(across.y, int(std::floor(t * n)));
}

TEST(VisualPolar, BilinearReproducesConstantAndWrapsPhi) {
    auto g = VisualPolarGrid::make(24, 20, 0.24);
    auto constant = [](uint32_t, uint32_t, uint32_t) { return 0.75; };
    for (double rho : {0.0, 0.01, 0.2, 0.5, 1.0})
        for (double t : {0.0, 0.001, 0.5, 0.999})
            EXPECT_NEAR(visualPolarBilinear(g, rho, t, 0, constant), 0.75, 1e-12);
    // A function of phi only (cos phi at each texel centre): continuous across t = 0.
    auto cosPhi = [&](uint32_t i, uint32_t j, uint32_t level) {
        uint32_t n = (g.rows(i) + (1u << level) - 1) >> level;
        return std::cos(2 * std::numbers::pi * (j + 0.5) / n);
    };
    double below = visualPolarBilinear(g, 0.7, 1.0 - 1e-9, 0, cosPhi);
    double above = visualPolarBilinear(g, 0.7, 1e-9, 0, cosPhi);
    EXPECT_NEAR(below, above, 1e-6);
}

// P5 §3.3's staircase: for each of the 16 block offsets, every 32-column block column has one phi
// height (its last column's), no column is thinner than the triangular clip, columns outside the
// fovea's block columns are untouched, and stairBlock = 0 is the triangular clip. Prints how many
// more texels it traces (the price of a fovea that is never thinner) at P5's 853x960 and at a
// 256x256 screen's 171x171.
TEST(VisualPolar, StaircaseHasOneHeightPerBlockColumn) {
    for (auto [w, h] : {std::pair<uint32_t, uint32_t>{853, 960}, {171, 171}}) {
        const auto triangle = VisualPolarGrid::make(w, h, 0.24);
        uint64_t least = ~0ull, most = 0;
        for (int k = 0; k < fovea::sampling::kBlockGridOffsetCount; ++k) {
            auto g = triangle;
            g.stairBlock = fovea::sampling::kBlockGridSize;
            g.stairPhase = uint32_t(fovea::sampling::blockGridOffset(k)[0]);
            for (uint32_t i = 0; i < w; ++i) {
                ASSERT_GE(g.rows(i), triangle.rows(i)) << i;
                if ((i + g.stairPhase) % g.stairBlock != 0 && i > 0) {
                    ASSERT_EQ(g.rows(i), g.rows(i - 1)) << "offset " << k << " column " << i;
                }
                // The last column of a block column keeps its own height.
                if ((i + 1 + g.stairPhase) % g.stairBlock == 0 || i + 1 == w) {
                    ASSERT_EQ(g.rows(i), triangle.rows(i)) << i;
                }
            }
            least = std::min(least, g.validTexels());
            most = std::max(most, g.validTexels());
            g.stairBlock = 0;
            for (uint32_t i = 0; i < w; ++i) ASSERT_EQ(g.rows(i), triangle.rows(i));
        }
        double t = double(triangle.validTexels());
        std::printf("%ux%u: triangle %.0f texels, staircase %llu..%llu (+%.1f..%.1f %%)\n", w, h, t,
                    (unsigned long long)least, (unsigned long long)most, 100 * (least / t - 1),
                    100 * (most / t - 1));
        EXPECT_GT(least, triangle.validTexels());
        // At most one block column's worth of extra texels per fovea block column.
        EXPECT_LT(double(most), t + double(h) * 32 * (std::ceil(0.24 * w / 32) + 1));
    }
}
