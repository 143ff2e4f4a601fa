// Seed 003 P3/P4's foveated preview sampling on the CPU: the published inverse of the acuity CDF
// (P4 Eq. 7, fitted) next to the exact one (VisualPolar.h acuityInverse, the same CDF as P5), and
// how far apart they are. shaders/preview_samples/generate.comp uses both (PreviewSamples'
// `inverse`); tests/graph/PreviewTests.cpp checks the GPU samples against acuityCdf.
#pragma once

namespace fovea::sampling {

// P4 Eq. 7 (P3 Eq. 6 times 80): 18.64 sqrt(u) for u <= 0.0965, else the fourth-order polynomial
// 25.09u^4 + 0.1680u^3 + 27.61u^2 + 23.87u + 3.232; eccentricity in degrees for u in [0, 1].
double acuityInversePublished(double u);

// The published inverse against the exact one over u in (0, 1] (`steps` points).
struct InverseError {
    double maxRelative = 0;       // max |published - exact| / exact
    double atU = 0;               // where
    double maxDegrees = 0;        // max |published - exact|, degrees
    double integralRelative = 0;  // ∫|published - exact| du / ∫exact du (P4: "less than 0.04 %")
    // The density the published inverse generates, 1 / (d published / du), against the exact
    // density, max relative difference over the polynomial branch (where P4's error matters).
    double maxDensityRelative = 0;
};
InverseError publishedInverseError(int steps = 100000);

}  // namespace fovea::sampling
