// Temporal reprojection on a Visual-Polar image (seed 003 P5 §3.3): TAA with the `vp` block
// fetches its history at each column's own phi height and wraps on phi, so a smooth image moved
// by a known screen translation is found again everywhere: in the fovea (whose columns have
// different phi heights, the triangular clip) and across the phi = 0 seam. The control (`vp`
// open: screen addressing of the VP image) misses both.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "core/graph/GraphDesc.h"
#include "core/graph/PassRegistry.h"
#include "core/graph/RenderGraph.h"
#include "core/sampling/VisualPolar.h"
#include "core/scene/BuiltinScenes.h"
#include "core/scene/Camera.h"
#include "core/vk/Resources.h"
#include "passes/TAA/TAAPass.h"
#include "passes/VisualPolarWarp/VisualPolarWarpPass.h"
#include "tests/unit/GpuTestFixture.h"

using namespace fovea;
using namespace fovea::graph;
using sampling::VisualPolarGrid;
using sampling::VisualPolarMapping;
using Image = std::vector<float>;  // rgba32f, row-major

namespace {

// Test-only source: colour and motion images the size of the warp's coords, filled from the host.
class VpTemporalFeedPass : public Pass {
public:
    void reflect(Reflection& r) const override {
        r.input("coords").doc("sets the size");
        r.output("color", vk::Format::eR32G32B32A32Sfloat).sameAs("coords").persistent();
        r.output("motion", vk::Format::eR32G32B32A32Sfloat).sameAs("coords").persistent();
    }
    void execute(ExecuteContext&) override {}
};

const PassRegistry& registry() {
    static PassRegistry reg = [] {
        PassRegistry r;
        r.add({"VisualPolarWarp", "",
               [] { return std::make_unique<passes::VisualPolarWarpPass>(); }});
        r.add({"TAA", "", [] { return std::make_unique<passes::TAAPass>(); }});
        r.add({"VpTemporalFeed", "", [] { return std::make_unique<VpTemporalFeedPass>(); }});
        return r;
    }();
    return reg;
}

scene::FrameCamera camera(uint32_t w, uint32_t h, glm::vec2 gaze) {
    static const scene::Scene s = scene::loadBuiltinScene("builtin:plane");
    const glm::vec2 gazes[scene::kMaxEyes] = {gaze, gaze};
    return scene::makeFrameCamera(s.cameras.empty() ? s.defaultCamera() : s.cameras.front(), w, h,
                                  {}, 0, nullptr, gazes);
}

class VpTaaRig {
public:
    VpTaaRig(gpu::Context& gpu, uint32_t w, uint32_t h, bool connectVp)
        : mGpu(gpu), mGraph(gpu, registry()) {
        // alpha 0 and no clip: the result is the reprojected history alone.
        std::string text =
            R"({ "version": 1, "name": "vp_taa", "passes": [)"
            R"( { "name": "warp", "type": "VisualPolarWarp" },)"
            R"( { "name": "feed", "type": "VpTemporalFeed" },)"
            R"( { "name": "taa", "type": "TAA", "params": { "alpha": 0, "clip": "none" } } ],)"
            R"( "edges": [ { "from": "warp.coords", "to": "feed.coords" },)"
            R"( { "from": "feed.color", "to": "taa.color" },)"
            R"( { "from": "feed.motion", "to": "taa.motion" })";
        if (connectVp) text += R"(, { "from": "warp.vp", "to": "taa.vp" })";
        text += R"( ], "outputs": [ "taa.result" ] })";
        CompileOptions o;
        o.width = w;
        o.height = h;
        o.sceneFeatures = kSceneStereo;
        mGraph.build(parseGraphText(text, "vp_taa"), o);
    }
    glm::uvec2 vpSize() const {
        const auto& img = mGraph.image("feed.color");
        return {img.width(), img.height()};
    }
    Image frame(const scene::FrameCamera& cam, const Image& color, const Image& motion) {
        mGraph.setCamera(cam);
        const_cast<gpu::Image&>(mGraph.image("feed.color")).uploadRGBA32F(mGpu, color);
        const_cast<gpu::Image&>(mGraph.image("feed.motion")).uploadRGBA32F(mGpu, motion);
        mGraph.runFrame();
        return mGraph.image("taa.result").downloadRGBA32F(mGpu);
    }

private:
    gpu::Context& mGpu;
    RenderGraph mGraph;
};

class VisualPolarTemporalTest : public GpuTest {};

}  // namespace

// Frame 0 holds a smooth image f(screen position) on the VP grid; frame 1 says (through GBuffer-
// style VP motion: columns, rows of the texel's column, phi wrapped the short way) that every
// texel showed the screen point p + d last frame. With alpha 0 the result is the history at that
// point, which must be f(p + d) within the bilinear error at every texel, seam and fovea included.
TEST_F(VisualPolarTemporalTest, TaaHistoryFollowsColumnHeightsAndPhiSeam) {
    const uint32_t w = 96, h = 80;
    const glm::vec2 gaze(0.45f, 0.55f);
    const glm::dvec2 d(1.3, -0.9);  // pixels: crosses the phi = 0 ray (right of the gaze)
    auto cam = camera(w, h, gaze);
    double worst[2] = {0, 0}, worstSeam[2] = {0, 0}, worstFovea[2] = {0, 0};
    size_t checked = 0;
    for (int connect = 0; connect < 2; ++connect) {
        VpTaaRig rig(ctx(), w, h, connect == 1);
        const glm::uvec2 vs = rig.vpSize();
        auto grid = VisualPolarGrid::make(vs.x, vs.y, 0.24);
        auto m =
            VisualPolarMapping::make(grid, glm::dvec2(w, h), glm::dvec2(gaze) * glm::dvec2(w, h));
        auto f = [&](glm::dvec2 p) { return 0.2 + 0.5 * p.x / w + 0.3 * p.y / h; };
        Image history(size_t(vs.x) * vs.y * 4, 0.0f), zero(history.size(), 0.0f),
            motion(history.size(), 0.0f);
        for (uint32_t i = 0; i < grid.width; ++i)
            for (uint32_t j = 0; j < grid.rows(i); ++j) {
                size_t k = (size_t(j) * vs.x + i) * 4;
                history[k] = float(f(m.texelToScreen(i, j)));
                history[k + 3] = 1.0f;
                // GBuffer's encoding (gbuffer.comp): previous texel - current texel.
                glm::dvec2 rt = m.toVisualPolar(m.texelToScreen(i, j) + d);
                double n = grid.rows(i);
                double dRow = rt.y * n - 0.5 - j;
                dRow -= n * std::round(dRow / n);
                motion[k] = float(rt.x * grid.width - 0.5 - i);
                motion[k + 1] = float(dRow);
            }
        rig.frame(cam, history, zero);  // first frame: no history, the result is `history`
        Image got = rig.frame(cam, zero, motion);
        for (uint32_t i = 0; i < grid.width; ++i)
            for (uint32_t j = 0; j < grid.rows(i); ++j) {
                glm::dvec2 p = m.texelToScreen(i, j);
                double x = m.toVisualPolar(p + d).x * grid.width;
                if (x < 0.5 || x > grid.width - 0.5) continue;  // rho clamped: not compared
                double e = std::abs(double(got[(size_t(j) * vs.x + i) * 4]) - f(p + d));
                worst[connect] = std::max(worst[connect], e);
                double t = (j + 0.5) / grid.rows(i);
                if (std::min(t, 1.0 - t) * grid.rows(i) < 2.0)
                    worstSeam[connect] = std::max(worstSeam[connect], e);
                if ((i + 0.5) / grid.width < grid.foveaFraction)
                    worstFovea[connect] = std::max(worstFovea[connect], e);
                checked += connect;
            }
    }
    std::printf(
        "worst |error|: vp %.4f (seam %.4f, fovea %.4f); screen addressing %.4f (seam %.4f, "
        "fovea %.4f)\n",
        worst[1], worstSeam[1], worstFovea[1], worst[0], worstSeam[0], worstFovea[0]);
    ASSERT_GT(checked, size_t(1000));
    EXPECT_LT(worst[1], 0.02) << "seam " << worstSeam[1] << ", fovea " << worstFovea[1];
    EXPECT_LT(worstSeam[1], 0.02);
    // Control: screen addressing of the VP image reads the wrong phi in the fovea and drops the
    // history at the seam (the result then is the current frame, 0).
    EXPECT_GT(worstFovea[0], 0.1);
    EXPECT_GT(worstSeam[0], 0.1);
}
