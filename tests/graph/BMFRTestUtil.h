// Test harness shared by the BMFR tests: a no-op "Feed" pass whose persistent outputs the test
// fills from the host (noisy radiance, G-buffer), wired into one BMFR pass "bmfr".
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/graph/RenderGraph.h"
#include "passes/BMFR/BMFRPass.h"

namespace fovea::testbmfr {

struct BMFRInputs {
    int width = 0, height = 0;
    // RGBA floats per pixel.
    std::vector<float> color, position, normal, albedo, emission, motion;
    void resize(int w, int h);
};

struct BMFREdges {
    bool albedo = false, emission = false, motion = true;
};

class BMFRHarness {
public:
    BMFRHarness(gpu::Context& ctx, const BMFRInputs& in, const std::string& params,
                BMFREdges edges = {});
    ~BMFRHarness();
    // Uploads the parts of `in` (all of them, or only the colour).
    void upload(const BMFRInputs& in, bool colorOnly = false);
    void runFrame();
    std::vector<float> read(const std::string& field) const;  // "bmfr.<field>"
    std::vector<uint32_t> stats() const;
    // Normals as the pass reads them (rgba16f rounding), for oracles.
    std::vector<float> normalsUsed() const;
    graph::RenderGraph& graph() { return *mGraph; }
    passes::BMFRPass& pass();

private:
    gpu::Context& mCtx;
    BMFREdges mEdges;
    std::unique_ptr<graph::RenderGraph> mGraph;
};

bool allFinite(const std::vector<float>& v);

}  // namespace fovea::testbmfr
