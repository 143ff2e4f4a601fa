// Temporal reprojection on a Visual-Polar image (seed 003 P5 §3.3): TAA with the `vp` block
// fetches its history at each column's own phi height and wraps on phi, so a smooth image moved
// by a known screen translation is found again everywhere: in the fovea (whose columns have
// different phi heights, the triangular clip) and across the phi = 0 seam. The control (`vp`
// open: screen addressing of the VP image) misses both. BMFR's and SVGF's temporal accumulation
// (their `vp` inputs) keep the history of every texel and fetch it at the right place.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "core/graph/GraphDesc.h"
#include "core/graph/PassRegistry.h"
#include "core/graph/RenderGraph.h"
#include "core/sampling/BlockGrid.h"
#include "core/sampling/VisualPolar.h"
#include "core/scene/BuiltinScenes.h"
#include "core/scene/Camera.h"
#include "core/vk/Resources.h"
#include "passes/BMFR/BMFRPass.h"
#include "passes/SVGF/SVGFPass.h"
#include "passes/TAA/TAAPass.h"
#include "passes/VisualPolarWarp/VisualPolarWarpPass.h"
#include "tests/graph/GpuTestFixture.h"

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
        r.output("position", vk::Format::eR32G32B32A32Sfloat).sameAs("coords").persistent();
        r.output("normal", vk::Format::eR32G32B32A32Sfloat).sameAs("coords").persistent();
        r.output("depth", vk::Format::eR32G32B32A32Sfloat).sameAs("coords").persistent();
    }
    void execute(ExecuteContext&) override {}
};

const PassRegistry& registry() {
    static PassRegistry reg = [] {
        PassRegistry r;
        r.add({"VisualPolarWarp", "",
               [] { return std::make_unique<passes::VisualPolarWarpPass>(); }});
        r.add({"TAA", "", [] { return std::make_unique<passes::TAAPass>(); }});
        r.add({"BMFR", "", [] { return std::make_unique<passes::BMFRPass>(); }});
        r.add({"SVGF", "", [] { return std::make_unique<passes::SVGFPass>(); }});
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
    VpTaaRig(gpu::Context& gpu, uint32_t w, uint32_t h, bool connectVp, bool denoisers = false,
             const std::string& warpParams = "{}", const std::string& bmfrParams = "{}",
             const std::string& taaFilter = "bilinear")
        : mGpu(gpu), mGraph(gpu, registry()) {
        // alpha 0 and no clip: the result is the reprojected history alone.
        std::string text =
            R"({ "version": 1, "name": "vp_taa", "passes": [)"
            R"( { "name": "warp", "type": "VisualPolarWarp", "params": )" +
            warpParams +
            R"( },)"
            R"( { "name": "feed", "type": "VpTemporalFeed" },)"
            R"( { "name": "taa", "type": "TAA", "params": { "alpha": 0, "clip": "none",)"
            R"( "historyFilter": ")" +
            taaFilter + R"(" } })";
        if (denoisers)
            text += R"(, { "name": "bmfr", "type": "BMFR", "params": )" + bmfrParams +
                    R"( }, { "name": "svgf", "type": "SVGF",)"
                    R"( "params": { "feedbackTap": 0 } })";
        text += R"( ], "edges": [ { "from": "warp.coords", "to": "feed.coords" },)"
                R"( { "from": "feed.color", "to": "taa.color" },)"
                R"( { "from": "feed.motion", "to": "taa.motion" })";
        if (connectVp) text += R"(, { "from": "warp.vp", "to": "taa.vp" })";
        std::string outputs = R"("taa.result", "warp.coords")";
        if (denoisers) {
            for (const char* pass : {"bmfr", "svgf"}) {
                const std::string d = pass;
                for (const char* field : {"color", "position", "normal", "motion"})
                    text += R"(, { "from": "feed.)" + std::string(field) + R"(", "to": ")" + d +
                            "." + field + R"(" })";
                if (connectVp) text += R"(, { "from": "warp.vp", "to": ")" + d + R"(.vp" })";
                outputs += R"(, ")" + d + R"(.accumulated")";
                if (d == "svgf") outputs += R"(, "svgf.illumination")";
                if (d == "bmfr") outputs += R"(, "bmfr.fitted")";
            }
            text += R"(, { "from": "feed.depth", "to": "svgf.depth" })";
        }
        text += R"( ], "outputs": [ )" + outputs + " ] }";
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
        return frame(cam, {{"color", color}, {"motion", motion}}, "taa.result");
    }
    Image frame(const scene::FrameCamera& cam,
                const std::vector<std::pair<std::string, Image>>& inputs, const std::string& out) {
        mGraph.setCamera(cam);
        for (const auto& [name, img] : inputs)
            const_cast<gpu::Image&>(mGraph.image("feed." + name)).uploadRGBA32F(mGpu, img);
        mGraph.runFrame();
        return output(out);
    }
    // An output of the last frame.
    Image output(const std::string& name) { return mGraph.image(name).downloadRGBA32F(mGpu); }

private:
    gpu::Context& mGpu;
    RenderGraph mGraph;
};

// Per valid texel of a mono VP image: fn(texel's screen position) in rgba.
template <class Fn>
Image texelImage(const VisualPolarMapping& m, glm::uvec2 vs, Fn&& fn) {
    Image img(size_t(vs.x) * vs.y * 4, 0.0f);
    for (uint32_t i = 0; i < m.grid.width; ++i)
        for (uint32_t j = 0; j < m.grid.rows(i); ++j) {
            glm::dvec4 v = fn(m.texelToScreen(i, j));
            for (int c = 0; c < 4; ++c) img[(size_t(j) * vs.x + i) * 4 + c] = float(v[c]);
        }
    return img;
}

// GBuffer's Visual-Polar motion (gbuffer.comp: previous texel - current texel, rows of the
// texel's column, phi wrapped the short way) of a screen translation: last frame, texel (i, j)
// showed the screen point texelToScreen(i, j) + d.
Image translationMotion(const VisualPolarMapping& m, glm::uvec2 vs, glm::dvec2 d) {
    Image motion(size_t(vs.x) * vs.y * 4, 0.0f);
    for (uint32_t i = 0; i < m.grid.width; ++i)
        for (uint32_t j = 0; j < m.grid.rows(i); ++j) {
            glm::dvec2 rt = m.toVisualPolar(m.texelToScreen(i, j) + d);
            double n = m.grid.rows(i);
            double dRow = rt.y * n - 0.5 - j;
            dRow -= n * std::round(dRow / n);
            motion[(size_t(j) * vs.x + i) * 4] = float(rt.x * m.grid.width - 0.5 - i);
            motion[(size_t(j) * vs.x + i) * 4 + 1] = float(dRow);
        }
    return motion;
}

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
    // connect 0: `vp` open (the control), 1: bilinear, 2: Catmull-Rom with per-column row sets.
    double worst[3] = {}, worstSeam[3] = {}, worstFovea[3] = {};
    size_t checked = 0;
    for (int connect = 0; connect < 3; ++connect) {
        VpTaaRig rig(ctx(), w, h, connect > 0, false, "{}", "{}",
                     connect == 2 ? "catmull-rom" : "bilinear");
        const glm::uvec2 vs = rig.vpSize();
        auto grid = VisualPolarGrid::make(vs.x, vs.y, 0.24);
        auto m = VisualPolarMapping::make(grid, glm::dvec2(w, h), glm::dvec2(gaze));
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
                checked += connect == 1;
            }
    }
    std::printf(
        "worst |error|: vp %.4f (seam %.4f, fovea %.4f); Catmull-Rom %.4f (seam %.4f, fovea "
        "%.4f); screen addressing %.4f (seam %.4f, fovea %.4f)\n",
        worst[1], worstSeam[1], worstFovea[1], worst[2], worstSeam[2], worstFovea[2], worst[0],
        worstSeam[0], worstFovea[0]);
    ASSERT_GT(checked, size_t(1000));
    for (int k = 1; k < 3; ++k) {
        EXPECT_LT(worst[k], 0.02) << k << ": seam " << worstSeam[k] << ", fovea " << worstFovea[k];
        EXPECT_LT(worstSeam[k], 0.02) << k;
    }
    // Control: screen addressing of the VP image reads the wrong phi in the fovea and drops the
    // history at the seam (the result then is the current frame, 0).
    EXPECT_GT(worstFovea[0], 0.1);
    EXPECT_GT(worstSeam[0], 0.1);
}

// BMFR phase I and SVGF's temporal accumulation on a VP image: a static scene whose world
// position is a function of the screen point (1 unit per pixel, 100 units deep: the discard tests
// accept ~2 px), seen moved by d. Frame 0: colour f; frame 1: colour 0 and the VP motion of d.
// (SVGF with feedbackTap 0: its colour history is the accumulation, not the filtered level 1.)
// Each pass then holds 2 samples, half of them f(p + d) from its history, at every texel whose
// previous position lies in the grid; screen addressing (the control) loses or misplaces the
// history of the fovea's texels.
TEST_F(VisualPolarTemporalTest, BMFRAndSVGFHistoryFollowColumnHeights) {
    const uint32_t w = 96, h = 80;
    const glm::vec2 gaze(0.45f, 0.55f);
    const glm::dvec2 d(1.3, -0.9);
    auto cam = camera(w, h, gaze);
    const glm::dvec3 eye(cam.eyes[0].position);
    auto f = [&](glm::dvec2 p) { return 0.2 + 0.5 * p.x / w + 0.3 * p.y / h; };
    auto world = [&](glm::dvec2 p) { return eye + glm::dvec3(p.x - w / 2.0, p.y - h / 2.0, -100); };
    size_t lost[2][2] = {}, checked = 0;  // [connect][bmfr, svgf]
    double worst[2][2] = {};
    for (int connect = 0; connect < 2; ++connect) {
        VpTaaRig rig(ctx(), w, h, connect == 1, true);
        const glm::uvec2 vs = rig.vpSize();
        auto grid = VisualPolarGrid::make(vs.x, vs.y, 0.24);
        auto m = VisualPolarMapping::make(grid, glm::dvec2(w, h), glm::dvec2(gaze));
        auto normal = texelImage(m, vs, [](glm::dvec2) { return glm::dvec4(0, 0, 1, 1); });
        auto depth = texelImage(m, vs, [](glm::dvec2) { return glm::dvec4(100, 0, 0, 1); });
        auto color0 =
            texelImage(m, vs, [&](glm::dvec2 p) { return glm::dvec4(f(p), f(p), f(p), 1); });
        auto zero = texelImage(m, vs, [](glm::dvec2) { return glm::dvec4(0, 0, 0, 1); });
        auto pos0 = texelImage(m, vs, [&](glm::dvec2 p) { return glm::dvec4(world(p), 1); });
        auto pos1 = texelImage(m, vs, [&](glm::dvec2 p) { return glm::dvec4(world(p + d), 1); });
        Image still(color0.size(), 0.0f);
        rig.frame(cam,
                  {{"color", color0},
                   {"position", pos0},
                   {"normal", normal},
                   {"depth", depth},
                   {"motion", still}},
                  "bmfr.accumulated");
        const Image bmfr = rig.frame(
            cam, {{"color", zero}, {"position", pos1}, {"motion", translationMotion(m, vs, d)}},
            "bmfr.accumulated");
        const Image svgf = rig.output("svgf.accumulated");
        for (int k = 0; k < 2; ++k) {
            const Image& acc = k == 0 ? bmfr : svgf;
            for (uint32_t i = 0; i < grid.width; ++i)
                for (uint32_t j = 0; j < grid.rows(i); ++j) {
                    glm::dvec2 p = m.texelToScreen(i, j);
                    double x = m.toVisualPolar(p + d).x * grid.width;
                    if (x < 0.5 || x > grid.width - 0.5) continue;
                    const float* a = &acc[(size_t(j) * vs.x + i) * 4];
                    if (std::abs(a[3] - 2.0f) > 1e-3f) {
                        ++lost[connect][k];
                        continue;
                    }
                    double e = std::abs(2.0 * a[0] - f(p + d));
                    worst[connect][k] = std::max(worst[connect][k], e);
                    checked += connect == 1 && k == 0;
                }
        }
    }
    std::printf(
        "BMFR: lost %zu, worst %.4f (control: lost %zu, worst %.4f); SVGF: lost %zu, worst "
        "%.4f (control: lost %zu, worst %.4f)\n",
        lost[1][0], worst[1][0], lost[0][0], worst[0][0], lost[1][1], worst[1][1], lost[0][1],
        worst[0][1]);
    ASSERT_GT(checked, size_t(1000));
    for (int k = 0; k < 2; ++k) {
        EXPECT_EQ(lost[1][k], 0u) << (k == 0 ? "BMFR" : "SVGF");
        EXPECT_LT(worst[1][k], 0.02) << (k == 0 ? "BMFR" : "SVGF");
        EXPECT_GT(lost[0][k] + size_t(worst[0][k] > 0.05) * 1000, 20u) << "control " << k;
    }
}

// SVGF's a-trous and spatial-variance taps on a VP image (P5 §3.3): a smooth image of the screen
// position filtered in one frame stays that image (the taps sit around the texel in the screen,
// wrapped on phi, at each column's own height); screen addressing of the VP image averages texels
// of other phi in the fovea and loses one side at the phi = 0 seam.
TEST_F(VisualPolarTemporalTest, SVGFSpatialTapsFollowColumnHeightsAndPhiSeam) {
    const uint32_t w = 96, h = 80;
    const glm::vec2 gaze(0.45f, 0.55f);
    auto cam = camera(w, h, gaze);
    const glm::dvec3 eye(cam.eyes[0].position);
    auto f = [&](glm::dvec2 p) { return 0.2 + 0.5 * p.x / w + 0.3 * p.y / h; };
    double worst[2] = {}, worstSeam[2] = {};
    for (int connect = 0; connect < 2; ++connect) {
        VpTaaRig rig(ctx(), w, h, connect == 1, true);
        const glm::uvec2 vs = rig.vpSize();
        auto grid = VisualPolarGrid::make(vs.x, vs.y, 0.24);
        auto m = VisualPolarMapping::make(grid, glm::dvec2(w, h), glm::dvec2(gaze));
        auto img = [&](auto fn) { return texelImage(m, vs, fn); };
        const Image out = rig.frame(
            cam,
            {{"color", img([&](glm::dvec2 p) { return glm::dvec4(f(p), f(p), f(p), 1); })},
             {"position", img([&](glm::dvec2 p) {
                  return glm::dvec4(eye + glm::dvec3(p.x - w / 2.0, p.y - h / 2.0, -100), 1);
              })},
             {"normal", img([](glm::dvec2) { return glm::dvec4(0, 0, 1, 1); })},
             {"depth", img([](glm::dvec2) { return glm::dvec4(100, 0, 0, 1); })},
             {"motion", Image(size_t(vs.x) * vs.y * 4, 0.0f)}},
            "svgf.illumination");
        for (uint32_t i = 1; i + 1 < grid.width; ++i)
            for (uint32_t j = 0; j < grid.rows(i); ++j) {
                glm::dvec2 p = m.texelToScreen(i, j);
                double e = std::abs(double(out[(size_t(j) * vs.x + i) * 4]) - f(p));
                worst[connect] = std::max(worst[connect], e);
                if (j == 0 || j + 1 == grid.rows(i))
                    worstSeam[connect] = std::max(worstSeam[connect], e);
            }
    }
    std::printf("SVGF spatial: worst %.4f (seam %.4f); screen addressing %.4f (seam %.4f)\n",
                worst[1], worstSeam[1], worst[0], worstSeam[0]);
    // Measured: 0.070 (seam 0.041) against 0.131 (seam 0.131). Filtering in (rho, phi) averages
    // a screen ramp over arcs, so even the right taps leave a few percent in the periphery.
    EXPECT_LT(worst[1], 0.09);
    EXPECT_LT(worstSeam[1], 0.06);
    EXPECT_GT(worstSeam[0], 0.1) << "control: screen addressing must show the seam";
    EXPECT_GT(worst[0], 1.5 * worst[1]);
}

namespace {

// P5 §3.3's staircase for frame `frame` of eye `eye` (the warp's P2 §6.1 block grid offsets).
VisualPolarGrid staircaseGrid(glm::uvec2 vs, uint32_t eyes, uint32_t eye, uint64_t frame) {
    auto grid = VisualPolarGrid::make(vs.x / eyes, vs.y, 0.24);
    grid.stairBlock = uint32_t(sampling::kBlockGridSize);
    grid.stairPhase =
        uint32_t(sampling::blockGridOffset(frame)[0] + eye * grid.width) % grid.stairBlock;
    return grid;
}

}  // namespace

// The warp with `staircase` (P5 §3.3): every frame, the clipped texels are exactly those of the
// C++ staircase for that frame's block offset (eye 1 of a stereo pair shifted by its first
// column), each 32-column block column of the side-by-side image has one phi height, and no
// column is thinner than the triangular clip.
TEST_F(VisualPolarTemporalTest, WarpStaircaseFollowsTheMovingBlockGrid) {
    const uint32_t w = 512, h = 192;  // stereo: 256x192 per eye, VP 171x128 per eye
    VpTaaRig rig(ctx(), w, h, true, false, R"({ "staircase": true })");
    const glm::uvec2 vs = rig.vpSize();
    static const scene::Scene s = scene::loadBuiltinScene("builtin:plane");
    scene::CameraRigOptions stereo;
    stereo.stereo = true;
    const glm::vec2 gazes[scene::kMaxEyes] = {{0.5f, 0.5f}, {0.3f, 0.6f}};
    auto cam = scene::makeFrameCamera(s.cameras.empty() ? s.defaultCamera() : s.cameras.front(), w,
                                      h, stereo, 0, nullptr, gazes);
    const Image zero(size_t(vs.x) * vs.y * 4, 0.0f);
    const auto triangle = VisualPolarGrid::make(vs.x / 2, vs.y, 0.24);
    size_t mismatched = 0, thinner = 0, clipped = 0;
    std::vector<uint32_t> firstHeights;
    for (uint64_t frame = 0; frame < 6; ++frame) {
        rig.frame(cam, zero, zero);
        const Image coords = rig.output("warp.coords");
        const int ox = sampling::blockGridOffset(frame)[0];
        std::vector<uint32_t> height(vs.x, 0);  // per column of the side-by-side image
        for (uint32_t eye = 0; eye < 2; ++eye) {
            auto grid = staircaseGrid(vs, 2, eye, frame);
            for (uint32_t i = 0; i < grid.width; ++i) {
                const uint32_t x = eye * grid.width + i;
                height[x] = grid.rows(i);
                thinner += grid.rows(i) < triangle.rows(i);
                for (uint32_t j = 0; j < vs.y; ++j) {
                    bool off = coords[(size_t(j) * vs.x + x) * 4] == -1.0f;
                    mismatched += off != (j >= grid.rows(i));
                    clipped += off;
                }
            }
        }
        // One height per block column [b 32 - ox, b 32 - ox + 32) within each eye.
        const uint32_t eyeWidth = vs.x / 2;  // an odd width leaves a spare last column
        for (uint32_t x = 1; x < 2 * eyeWidth; ++x) {
            bool sameBlock = (x + ox) % 32 != 0 && x != eyeWidth;
            if (sameBlock) {
                EXPECT_EQ(height[x], height[x - 1]) << "frame " << frame << " x " << x;
            }
        }
        if (frame == 0) firstHeights = height;
        if (frame == 1) {
            EXPECT_NE(height, firstHeights) << "the staircase must move";
        }
    }
    EXPECT_EQ(mismatched, 0u);
    EXPECT_EQ(thinner, 0u);
    EXPECT_GT(clipped, 0u) << "the staircase must still clip the fovea";
}

// A still camera and gaze with the staircase: the phi heights change every frame, so the same
// texel index names another phi than last frame. TAA (alpha 0: the history alone) must return the
// image of the previous frame at every texel's own screen point (taps at the PREVIOUS heights,
// vpPrevious), and BMFR must keep every texel's history. The check is not vacuous: at many texels
// the previous frame's texel with the same index showed a clearly different value.
TEST_F(VisualPolarTemporalTest, StaircaseHistoryUsesThePreviousHeights) {
    const uint32_t w = 256, h = 192;
    const glm::vec2 gaze(0.5f, 0.5f);
    auto cam = camera(w, h, gaze);
    const glm::dvec3 eye(cam.eyes[0].position);
    VpTaaRig rig(ctx(), w, h, true, true, R"({ "staircase": true })");
    const glm::uvec2 vs = rig.vpSize();
    // A function of the angle around the gaze: the same row index at another phi height is
    // another angle, hence clearly another value.
    const glm::dvec2 g = glm::dvec2(gaze) * glm::dvec2(w, h);
    auto f = [&](glm::dvec2 p) { return 0.5 + 0.3 * std::cos(std::atan2(p.y - g.y, p.x - g.x)); };
    auto world = [&](glm::dvec2 p) { return eye + glm::dvec3(p.x - w / 2.0, p.y - h / 2.0, -100); };
    const Image still(size_t(vs.x) * vs.y * 4, 0.0f);
    double worst = 0;
    size_t checked = 0, lost = 0, sameIndexWrong = 0;
    VisualPolarMapping before{};
    for (uint64_t frame = 0; frame < 3; ++frame) {
        auto m = VisualPolarMapping::make(staircaseGrid(vs, 1, 0, frame), glm::dvec2(w, h),
                                          glm::dvec2(gaze));
        auto img = [&](auto fn) { return texelImage(m, vs, fn); };
        auto color = img([&](glm::dvec2 p) {
            double v = frame == 0 ? f(p) : 0.0;
            return glm::dvec4(v, v, v, 1);
        });
        const Image taa =
            rig.frame(cam,
                      {{"color", color},
                       {"position", img([&](glm::dvec2 p) { return glm::dvec4(world(p), 1); })},
                       {"normal", img([](glm::dvec2) { return glm::dvec4(0, 0, 1, 1); })},
                       {"depth", img([](glm::dvec2) { return glm::dvec4(100, 0, 0, 1); })},
                       {"motion", still}},
                      "taa.result");
        if (frame == 1) {
            const Image bmfr = rig.output("bmfr.accumulated");
            for (uint32_t i = 1; i + 1 < m.grid.width; ++i)
                for (uint32_t j = 0; j < m.grid.rows(i); ++j) {
                    const size_t k = (size_t(j) * vs.x + i) * 4;
                    const glm::dvec2 p = m.texelToScreen(i, j);
                    lost += std::abs(bmfr[k + 3] - 2.0f) > 1e-3f;
                    // Bilinear in phi of a cosine: ~0.04 (2 pi / n)^2 off; compared where the
                    // previous column had >= 24 rows (<= 0.003).
                    if (before.grid.rows(i) < 24) continue;
                    worst = std::max(worst, std::abs(double(taa[k]) - f(p)));
                    ++checked;
                    if (j < before.grid.rows(i))
                        sameIndexWrong += std::abs(f(before.texelToScreen(i, j)) - f(p)) > 0.05;
                }
        }
        before = m;
    }
    std::printf(
        "staircase history: worst %.4f over %zu texels, BMFR lost %zu, %zu texels whose "
        "same-index texel was > 0.05 off\n",
        worst, checked, lost, sameIndexWrong);
    ASSERT_GT(checked, size_t(10000));
    EXPECT_GT(sameIndexWrong, size_t(100));
    EXPECT_LT(worst, 0.02);
    EXPECT_EQ(lost, 0u);
}

// BMFR on a Visual-Polar image with the staircase follows the warp's block columns even with its
// own offsets off: with constant features the fit is one value per block, so the fitted image
// steps exactly where the block columns start ((x + ox) mod 32 = 0, ox = this frame's offset);
// without the staircase BMFR keeps its own grid (x mod 32 = 0).
TEST_F(VisualPolarTemporalTest, BMFRBlockColumnsFollowTheStaircase) {
    const uint32_t w = 256, h = 192;
    const glm::vec2 gaze(0.5f, 0.5f);
    auto cam = camera(w, h, gaze);
    for (int staircase = 0; staircase < 2; ++staircase) {
        VpTaaRig rig(ctx(), w, h, true, true, staircase ? R"({ "staircase": true })" : "{}",
                     R"({ "blockOffsets": false })");
        const glm::uvec2 vs = rig.vpSize();
        std::mt19937 rng(7);
        std::uniform_real_distribution<double> u(0.0, 1.0);
        for (uint64_t frame = 0; frame < 2; ++frame) {
            auto grid = staircase ? staircaseGrid(vs, 1, 0, frame)
                                  : VisualPolarGrid::make(vs.x, vs.y, 0.24);
            auto m = VisualPolarMapping::make(grid, glm::dvec2(w, h), glm::dvec2(gaze));
            auto img = [&](auto fn) { return texelImage(m, vs, fn); };
            const Image fitted =
                rig.frame(cam,
                          {{"color", img([&](glm::dvec2) {
                                double v = u(rng);
                                return glm::dvec4(v, v, v, 1);
                            })},
                           {"position", img([](glm::dvec2) { return glm::dvec4(1, 2, 3, 1); })},
                           {"normal", img([](glm::dvec2) { return glm::dvec4(0, 0, 1, 1); })},
                           {"depth", img([](glm::dvec2) { return glm::dvec4(100, 0, 0, 1); })},
                           {"motion", Image(size_t(vs.x) * vs.y * 4, 0.0f)}},
                          "bmfr.fitted");
            const int ox = staircase ? sampling::blockGridOffset(frame)[0] : 0;
            size_t wrong = 0;
            for (uint32_t x = 1; x < grid.width; ++x) {
                bool steps = fitted[size_t(x) * 4] != fitted[size_t(x - 1) * 4];  // row 0
                wrong += steps != ((x + ox) % 32 == 0);
            }
            EXPECT_EQ(wrong, 0u) << "staircase " << staircase << " frame " << frame;
        }
    }
}
