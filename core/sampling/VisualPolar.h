// The Visual-Polar mapping of seed 003 P5 §3.2 (thesis §4.6.2): the C++ twin of
// shaders/common/visual_polar.glsl, used by the VisualPolarWarp and Unwarp passes and by the
// tests as the oracle. Every pass that reads or writes Visual-Polar images uses the GLSL file;
// this file must stay numerically identical to it (docs/visual-polar.md).
//
// Conventions (per eye):
//  - A Visual-Polar (VP) image is W x H texels: column i <-> rho = (i + 0.5) / W in (0, 1) (rho
//    runs horizontally, P5 Fig. 4), row j <-> phi = 2 pi (j + 0.5) / n(i).
//  - n(i), the phi height of column i: H outside the fovea, ceil(H rho / rho_f) inside it (the
//    triangular clip of P5 §3.2, "reduces 12 %" for rho_f = 0.24; phi still covers 0..2 pi).
//    Rows j >= n(i) are clipped: never traced, never read.
//  - Eccentricity e(rho) in the normalized "degrees" of P5 Eq. 2-3 (0..80): linear rho e_f /
//    rho_f in the fovea, the inverse of the acuity CDF beyond. Screen radius r = dMax e / 80,
//    dMax = the largest distance from the gaze to a screen corner ("maximum rho is equal to
//    it"), so every screen pixel has rho <= 1 wherever the user looks.
//  - Screen positions are in pixels of the eye image (0..width, y down), the gaze at rho = 0.
#pragma once
#include <cmath>
#include <cstdint>
#include <glm/glm.hpp>

namespace fovea::sampling {

// P5 Eq. 1-2 (KIV*18): acuity constant up to 5.79 degrees; CDF normalized at 80 degrees.
inline constexpr double kAcuityFlatDegrees = 5.79;
inline constexpr double kAcuityMaxDegrees = 80.0;
// P5 §3.2: rho_f such that the clipped triangle is 12 % of the space (rho_f / 2 = 0.12).
inline constexpr double kVisualPolarFoveaFraction = 0.24;
// Smallest rho_f: keeps the fovea edge (f^-1(0.1) = 9.5 degrees) beyond the flat part of the
// acuity, where Eq. 2's two branches differ by 0.26 % (a small step down at 5.79 degrees): the
// mapping then only uses the monotone tail of Eq. 2.
inline constexpr double kVisualPolarMinFoveaFraction = 0.1;
// n(i) = ceil(H rho / rho_f) counts a value up to this much (relative) above an integer as that
// integer, here and in visual_polar.glsl vpRows: H rho / rho_f is often an exact integer (every
// fovea column when W = H and rho_f = 0.1) and the GPU's float rounding lifted some by an ulp, a
// whole row more after the ceil (column 4 of 70x70: 46 rows on the GPU, 45 here). Float is at
// most ~6 ulps (7e-7) off; 2e-6 is ~3x that. A value genuinely that close above an integer loses
// its extra row on both twins (P5's 853x959 grid: column 112, x = 527.0003, 527 rows).
inline constexpr double kVisualPolarRowsSlack = 2e-6;
// Bytes of the `vp` parameter block (visual_polar.glsl VisualPolarParams, std430): grid, fovea,
// two eyes, staircase.
inline constexpr uint64_t kVisualPolarParamsBytes = 80;

// Unnormalized CDF h(e) of P5 Eq. 2 (pi e^2 below 5.79 degrees, where the acuity is flat).
double acuityCdfRaw(double e);
// Normalized CDF f(e) = h(e) / h(80) in [0, 1] for e in [0, 80] (clamped outside).
double acuityCdf(double e);
// df/de = 2 pi e m(e) / h(80) (the radial pdf, P4 Eq. 1 normalized).
double acuityCdfDerivative(double e);
// P5 Eq. 3, the fitted inverse polynomial, as published (defined for u in [f(5.79), 1]).
double acuityInversePolynomial(double u);
// The exact inverse f^-1(u), u in [0, 1]: closed form below f(5.79), else Eq. 3 refined by
// Newton steps on Eq. 2 (Eq. 3's derivative is up to 2.4 % off, which would show directly as a
// density error; docs/visual-polar.md).
double acuityInverse(double u);

// The grid shape of one eye: VP size, fovea fraction and the fovea's edge eccentricity.
struct VisualPolarGrid {
    uint32_t width = 1, height = 1;                    // VP texels per eye (>= 1 each)
    double foveaFraction = kVisualPolarFoveaFraction;  // rho_f in (0, 1]
    double foveaDegrees = 0;                           // e_f = f^-1(rho_f)
    // P5 §3.3's staircase clip: 0 = the triangular clip; B > 0 = every column takes the height of
    // the last column of its B-column block column, the block grid shifted so that column i lies
    // in block column floor((i + stairPhase) / B) (phase = (block offset x + eye W) mod B).
    uint32_t stairBlock = 0;
    uint32_t stairPhase = 0;

    static VisualPolarGrid make(uint32_t width, uint32_t height, double foveaFraction);
    // n(i): rows of column i, in [1, height] (the staircase's when stairBlock > 0).
    uint32_t rows(uint32_t column) const;
    // Valid (unclipped) texels of the whole grid.
    uint64_t validTexels() const;
    // Normalized eccentricity (0..80) of rho, and its inverse.
    double eccentricity(double rho) const;
    double rhoOfEccentricity(double e) const;
};

// VP size per eye for a `reduction` of the samples (P5 §4.2: 61 %): both axes scaled by
// s = sqrt((1 - reduction) / (1 - rho_f / 2)), so valid texels ~ (1 - reduction) x pixels.
double visualPolarScale(double reduction, double foveaFraction);

// One eye's mapping: the grid plus the gaze and the scale dMax of the screen it maps to.
struct VisualPolarMapping {
    VisualPolarGrid grid;
    glm::dvec2 screen{1, 1};    // eye image size in pixels
    glm::dvec2 gaze{0.5, 0.5};  // pixels, clamped onto the screen (an off-screen gaze is clamped)
    double dMax = 1;            // >= 0.5 px (largest gaze-to-corner distance)

    // gaze01 in [0, 1]^2 of the eye image (the camera's gaze).
    static VisualPolarMapping make(const VisualPolarGrid& grid, glm::dvec2 screenSize,
                                   glm::dvec2 gaze01);
    double radius(double rho) const;     // pixels from the gaze
    double rhoOfRadius(double r) const;  // inverse of radius
    // VP -> screen: rho in [0, 1], t = phi / 2 pi (any real: wraps).
    glm::dvec2 toScreen(double rho, double t) const;
    // Screen -> VP: (rho, t) with t in [0, 1). The gaze itself maps to (0, 0).
    glm::dvec2 toVisualPolar(glm::dvec2 screenPos) const;
    // The screen position of texel (i, j)'s centre, jitter (texels) added in VP space.
    glm::dvec2 texelToScreen(uint32_t column, uint32_t row, glm::dvec2 jitter = {0, 0}) const;
    // Continuous texel coordinates of a screen position: x = rho W - 0.5 (column space), y =
    // t n(i) - 0.5 in column i's own row space (not wrapped).
    double columnCoordinate(double rho) const { return rho * grid.width - 0.5; }
};

// Neighbour addressing (P5 §3.3): a step of (dx, dy) texels from (i, j) lands on column
// clamp(i + dx) (clamp on rho) and, in that column, on the row at the same phi moved by dy rows
// of column i, wrapped modulo the column's own height n (the phi heights of two columns can
// differ inside the fovea).
glm::ivec2 visualPolarNeighbour(const VisualPolarGrid& grid, glm::ivec2 texel, glm::ivec2 step);

// Bilinear fetch at (rho, t) from level `level` of a phi-only mip chain (level 0 = the image):
// level k of column i has ceil(n(i) / 2^k) rows. Bilinear in rho between two columns (clamped),
// in each column bilinear in phi at its own height, wrapped. `texel(i, j, level)` returns a
// value (any type with + and scalar *).
template <class Fetch>
auto visualPolarBilinear(const VisualPolarGrid& grid, double rho, double t, uint32_t level,
                         Fetch&& texel) {
    double x = rho * grid.width - 0.5;
    int i0 = int(std::floor(x));
    double fx = x - i0;
    auto clampColumn = [&](int i) { return uint32_t(glm::clamp(i, 0, int(grid.width) - 1)); };
    auto column = [&](uint32_t i) {
        uint32_t n = (grid.rows(i) + (1u << level) - 1u) >> level;  // ceil(n / 2^level) >= 1
        double y = (t - std::floor(t)) * n - 0.5;
        int j0 = int(std::floor(y));
        double fy = y - j0;
        auto wrap = [&](int j) { return uint32_t(((j % int(n)) + int(n)) % int(n)); };
        return texel(i, wrap(j0), level) * (1.0 - fy) + texel(i, wrap(j0 + 1), level) * fy;
    };
    return column(clampColumn(i0)) * (1.0 - fx) + column(clampColumn(i0 + 1)) * fx;
}

}  // namespace fovea::sampling
