#include "core/sampling/VisualPolar.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace fovea::sampling {

namespace {
constexpr double kPi = std::numbers::pi;
// P5 Eq. 2 beyond the flat part: (1 / (0.3 d + 1) + ln(0.3 d + 1)) 166.4 pi - 612.3.
double cdfTail(double e) {
    double a = 0.3 * e + 1.0;  // >= 1 for e >= 0
    return (1.0 / a + std::log(a)) * 166.4 * kPi - 612.3;
}
double cdfTotal() {
    return cdfTail(kAcuityMaxDegrees);
}  // h(80) = 1091.31
}  // namespace

double acuityCdfRaw(double e) {
    e = std::clamp(e, 0.0, kAcuityMaxDegrees);
    // h(5.79) = pi 5.79^2 = 105.32 on both branches: continuous.
    return e <= kAcuityFlatDegrees ? kPi * e * e : cdfTail(e);
}

double acuityCdf(double e) {
    return acuityCdfRaw(e) / cdfTotal();
}

double acuityCdfDerivative(double e) {
    e = std::clamp(e, 0.0, kAcuityMaxDegrees);
    // m(e) = 1 (flat) or 7.49 / (0.3 e + 1)^2; 166.4 pi 0.09 = 2 pi 7.488.
    double a = 0.3 * e + 1.0;
    double raw = e <= kAcuityFlatDegrees ? 2.0 * kPi * e : 166.4 * kPi * 0.09 * e / (a * a);
    return raw / cdfTotal();
}

double acuityInversePolynomial(double u) {
    return (((25.09 * u + 0.1680) * u + 27.61) * u + 23.87) * u + 3.232;
}

double acuityInverse(double u) {
    u = std::clamp(u, 0.0, 1.0);
    double uFlat = acuityCdf(kAcuityFlatDegrees);
    if (u <= uFlat) return std::sqrt(u * cdfTotal() / kPi);  // h = pi e^2
    double e = std::clamp(acuityInversePolynomial(u), kAcuityFlatDegrees, kAcuityMaxDegrees);
    // Newton on f(e) - u: f is increasing and concave here (f' > 0 for e > 0); from Eq. 3's
    // start (<= 0.03 degrees off) four steps reach double precision.
    for (int k = 0; k < 4; ++k) {
        double d = acuityCdfDerivative(e);  // > 0 for e >= 5.79
        e = std::clamp(e - (acuityCdf(e) - u) / d, kAcuityFlatDegrees, kAcuityMaxDegrees);
    }
    return e;
}

VisualPolarGrid VisualPolarGrid::make(uint32_t width, uint32_t height, double foveaFraction) {
    VisualPolarGrid g;
    g.width = std::max(width, 1u);
    g.height = std::max(height, 1u);
    g.foveaFraction = std::clamp(foveaFraction, kVisualPolarMinFoveaFraction, 1.0);
    g.foveaDegrees = acuityInverse(g.foveaFraction);
    return g;
}

uint32_t VisualPolarGrid::rows(uint32_t column) const {
    if (stairBlock > 0)  // the last column of the block column (visual_polar.glsl vpRows)
        column =
            std::min(column + (stairBlock - 1) - (column + stairPhase) % stairBlock, width - 1);
    double rho = (column + 0.5) / width;
    if (rho >= foveaFraction) return height;
    // ceil(H rho / rho_f), at least 1 (column 0 of 853x960: 3 rows); an integer up to rounding
    // stays that integer on both twins (kVisualPolarRowsSlack).
    double n = height * rho / foveaFraction;  // foveaFraction >= 0.1
    return std::clamp(uint32_t(std::ceil(n * (1.0 - kVisualPolarRowsSlack))), 1u, height);
}

uint64_t VisualPolarGrid::validTexels() const {
    uint64_t n = 0;
    for (uint32_t i = 0; i < width; ++i) n += rows(i);
    return n;
}

double VisualPolarGrid::eccentricity(double rho) const {
    if (rho < foveaFraction) return std::max(rho, 0.0) * foveaDegrees / foveaFraction;
    return acuityInverse(rho);
}

double VisualPolarGrid::rhoOfEccentricity(double e) const {
    if (e < foveaDegrees) return std::max(e, 0.0) * foveaFraction / foveaDegrees;
    return acuityCdf(e);
}

double visualPolarScale(double reduction, double foveaFraction) {
    double clipped = std::clamp(foveaFraction, 0.0, 1.0) / 2.0;  // the triangle's share
    return std::sqrt(std::max(1.0 - reduction, 0.0) / (1.0 - clipped));
}

VisualPolarMapping VisualPolarMapping::make(const VisualPolarGrid& grid, glm::dvec2 screenSize,
                                            glm::dvec2 gaze01) {
    VisualPolarMapping m;
    m.grid = grid;
    m.screen = glm::max(screenSize, glm::dvec2(1.0));
    m.gaze = glm::clamp(gaze01, 0.0, 1.0) * m.screen;
    double dx = std::max(m.gaze.x, m.screen.x - m.gaze.x);
    double dy = std::max(m.gaze.y, m.screen.y - m.gaze.y);
    m.dMax = std::max(std::sqrt(dx * dx + dy * dy), 0.5);
    return m;
}

double VisualPolarMapping::radius(double rho) const {
    return dMax * grid.eccentricity(rho) / kAcuityMaxDegrees;
}

double VisualPolarMapping::rhoOfRadius(double r) const {
    return grid.rhoOfEccentricity(r * kAcuityMaxDegrees / dMax);  // dMax >= 0.5
}

glm::dvec2 VisualPolarMapping::toScreen(double rho, double t) const {
    double r = radius(rho), phi = 2.0 * kPi * t;
    return gaze + r * glm::dvec2(std::cos(phi), std::sin(phi));
}

glm::dvec2 VisualPolarMapping::toVisualPolar(glm::dvec2 p) const {
    glm::dvec2 d = p - gaze;
    double r = std::sqrt(d.x * d.x + d.y * d.y);
    double t = r > 0.0 ? std::atan2(d.y, d.x) / (2.0 * kPi) : 0.0;
    if (t < 0.0) t += 1.0;
    if (t >= 1.0) t = 0.0;
    return {rhoOfRadius(r), t};
}

glm::dvec2 VisualPolarMapping::texelToScreen(uint32_t column, uint32_t row,
                                             glm::dvec2 jitter) const {
    double rho = (column + 0.5 + jitter.x) / grid.width;
    double t = (row + 0.5 + jitter.y) / grid.rows(column);
    return toScreen(rho, t);
}

glm::ivec2 visualPolarNeighbour(const VisualPolarGrid& grid, glm::ivec2 texel, glm::ivec2 step) {
    int i0 = glm::clamp(texel.x, 0, int(grid.width) - 1);
    int i1 = glm::clamp(i0 + step.x, 0, int(grid.width) - 1);
    double n0 = grid.rows(uint32_t(i0)), n1 = grid.rows(uint32_t(i1));
    double t = (texel.y + step.y + 0.5) / n0;  // phi / 2 pi, unwrapped
    int j = int(std::floor((t - std::floor(t)) * n1));
    return {i1, glm::clamp(j, 0, int(n1) - 1)};
}

}  // namespace fovea::sampling
