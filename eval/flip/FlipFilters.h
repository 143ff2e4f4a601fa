// The filters of ꟻLIP (Andersson et al. 2020): the contrast sensitivity functions of the colour
// pipeline (a sum of Gaussians per opponent channel, in degrees of visual angle) and the edge and
// point detectors of the feature pipeline (first and second derivatives of a Gaussian). Every
// kernel FLIP defines in 2D is separable, so each is applied as a row pass and a column pass with
// clamp-to-edge borders; tests/unit/FlipTests.cpp checks that against the 2D kernels.
#pragma once
#include <cstdint>
#include <vector>

namespace fovea::eval::flip {

// One float channel, row-major.
struct Plane {
    uint32_t width = 0, height = 0;
    std::vector<float> values;
    Plane() = default;
    Plane(uint32_t w, uint32_t h) : width(w), height(h), values(size_t(w) * h, 0.0f) {}
    float& at(uint32_t x, uint32_t y) { return values[size_t(y) * width + x]; }
    float at(uint32_t x, uint32_t y) const { return values[size_t(y) * width + x]; }
};

// An odd-length 1D kernel, centre at size() / 2.
using Kernel = std::vector<float>;

// Row pass then column pass; samples outside the plane read the nearest edge pixel (FLIP pads by
// replication).
Plane convolveSeparable(const Plane& in, const Kernel& rows, const Kernel& columns);

// The opponent channels the contrast sensitivity functions act on.
enum class CsfChannel { Achromatic, RedGreen, BlueYellow };

// A CSF as separable terms: the 2D filter is the sum over terms of weight · k ⊗ k, each k
// normalized to sum 1 and the weights to sum 1, which equals FLIP's 2D kernel normalized to sum 1.
struct CsfTerm {
    float weight = 0;
    Kernel kernel;
};
// FLIP's CSFs in the spatial domain: a1 √(π/b1) exp(−π² r² / b1) + a2 √(π/b2) exp(−π² r² / b2),
// r in degrees (pixels / ppd), with (a1, b1, a2, b2) = (1, 0.0047, 0, 1e-5) achromatic,
// (1, 0.0053, 0, 1e-5) red-green, (34.1, 0.04, 13.5, 0.025) blue-yellow; all three share the
// radius csfRadius(ppd).
std::vector<CsfTerm> csfTerms(CsfChannel channel, double pixelsPerDegree);
// ⌈3 √(b_max / (2π²)) · ppd⌉ with b_max = 0.04 (the widest Gaussian's three standard deviations).
int csfRadius(double pixelsPerDegree);

// The feature detectors on the achromatic channel: a Gaussian of σ = 0.5 · 0.082° · ppd (0.082°:
// the width FLIP's feature pipeline is tuned to), radius ⌈3σ⌉; `edge` is −x·g(x) and `point`
// (x²/σ² − 1)·g(x), each with its positive weights scaled to sum 1 and its negative ones to −1,
// `smooth` is g normalized to sum 1. The 2D edge detector in x is edge ⊗ smooth (rows, columns).
struct FeatureKernels {
    int radius = 0;
    float sigma = 0;
    Kernel smooth, edge, point;
};
FeatureKernels featureKernels(double pixelsPerDegree);

}  // namespace fovea::eval::flip
