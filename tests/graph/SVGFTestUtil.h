// Test harness shared by the SVGF tests: a no-op "Feed" pass whose persistent outputs the test
// fills from the host (noisy radiance, G-buffer), wired into one SVGF pass "svgf"; and a random
// static G-buffer for the oracle comparisons.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/graph/RenderGraph.h"

namespace fovea::testsvgf {

struct SVGFInputs {
    int width = 0, height = 0;
    // RGBA floats per pixel (depth: x only).
    std::vector<float> color, position, normal, depth, albedo, emission, motion;
    void resize(int w, int h);
    size_t at(int x, int y) const { return (size_t(y) * size_t(width) + size_t(x)) * 4; }
};

struct SVGFEdges {
    bool albedo = true, emission = true, motion = true;
};

class SVGFHarness {
public:
    SVGFHarness(gpu::Context& ctx, const SVGFInputs& in, const std::string& params,
                SVGFEdges edges = {});
    ~SVGFHarness();
    void upload(const SVGFInputs& in, bool colorOnly = false);
    void runFrame();
    std::vector<float> read(const std::string& field) const;  // "svgf.<field>" (RGBA floats)
    std::vector<uint32_t> stats() const;
    // Inputs as the pass reads them (normal: rgba16f rounding, motion: rg16f), for oracles.
    std::vector<float> readFeed(const std::string& field) const;
    graph::RenderGraph& graph() { return *mGraph; }

private:
    gpu::Context& mCtx;
    std::unique_ptr<graph::RenderGraph> mGraph;
};

// A static scene of `w` x `h` pixels: two tilted planes with a depth step, a sphere-ish bump in
// the normals, a few misses, random albedo; colour = noise around a smooth signal (seeded).
SVGFInputs randomScene(int w, int h, uint32_t seed);
// New noisy colours for the same scene.
void recolor(SVGFInputs& in, uint32_t seed);

bool allFinite(const std::vector<float>& v);

}  // namespace fovea::testsvgf
