// What evaluation needs to know about a pass's configuration (eval/, `fovea reference`, `bench`),
// reported by the pass from its own parameters (Pass::facts). Evaluation reads these instead of a
// parameter by its name, so renaming a parameter or changing its default cannot silently change
// what the bench measures (tests/unit/PassFactsTests.cpp pins each fact to its parameters).
#pragma once
#include <cstdint>
#include <optional>

namespace fovea::graph {

// The layers of seed 000 §3.2 (Peres et al. 2023, Table 1): fovea d <= r0, middle r0 < d <= r1,
// outer d > r1, with d the distance of a pixel centre to its eye's gaze point in pixels of the
// eye image or its eccentricity in degrees.
struct LayerRadii {
    double r0 = 0, r1 = 0;
    bool degrees = false;  // false: pixels
};

struct PassFacts {
    // A path tracer: the samples every pixel gets per frame (a reference graph runs
    // spp / samplesPerFrame frames).
    std::optional<uint32_t> samplesPerFrame;
    // A foveation mask: the layer radii it splits the image by (per-layer errors use the same).
    std::optional<LayerRadii> foveationLayers;
};

}  // namespace fovea::graph
