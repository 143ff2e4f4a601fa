// GPU tests of the FoveationMask pass (passes/FoveationMask/, seed 000 §3.2 / Table 1): per-layer
// pixel and sample counts at FHD stereo against the model computed on the CPU and Table 1's
// areas, the mask against a CPU twin of the shader (pixels and degrees), determinism per seed,
// per-eye gaze, caching, layout = mask, and a PathTrace fed by the layout tracing exactly the
// mask's pixels with their spp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "core/graph/GraphDesc.h"
#include "core/graph/PassRegistry.h"
#include "core/graph/RenderGraph.h"
#include "core/sampling/SampleLayout.h"
#include "core/scene/BuiltinScenes.h"
#include "core/scene/Camera.h"
#include "core/scene/CameraGpu.h"
#include "core/scene/SceneGpu.h"
#include "core/vk/Resources.h"
#include "passes/RegisterPasses.h"
#include "tests/graph/GpuTestFixture.h"

using namespace fovea;
using namespace fovea::graph;
using sampling::SampleLayout;

namespace {

constexpr uint64_t kGraphSeed = 7;

// The model of docs/passes/FoveationMask.md, evaluated on the CPU with the camera block the shader
// sees (packCamera): distance to the eye's gaze (pixels or eccentricity degrees), layer,
// probability, and the same per-pixel toss.
struct Model {
    float r0 = 144.0f, r1 = 288.0f, outer = 0.5f;
    bool degrees = false;
    uint32_t spp[3] = {4, 3, 2};
    uint32_t seed = 0;  // the shader's 32-bit seed

    float distance(const scene::layout::CameraInfo& c, uint32_t x, uint32_t y) const {
        uint32_t eye = std::min(x / std::max(c.size.x, 1u), c.size.z - 1u);
        glm::vec2 eyeSize(c.size.x, c.size.y);
        glm::vec2 local = glm::vec2(x, y) + 0.5f - glm::vec2(c.eyes[eye].position.w, 0.0f);
        glm::vec2 gaze = glm::vec2(c.eyes[eye].gaze) * eyeSize;
        if (!degrees) return glm::length(local - gaze);
        auto dir = [&](glm::vec2 l) {
            glm::vec2 ndc(2.0f * l.x / eyeSize.x - 1.0f, 1.0f - 2.0f * l.y / eyeSize.y);
            return glm::vec3(ndc.x * c.jitter.z * c.jitter.w, ndc.y * c.jitter.z, -1.0f);
        };
        glm::vec3 a = dir(local), b = dir(gaze);
        return glm::degrees(std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b)));
    }
    uint32_t layer(float d) const { return d <= r0 ? 0u : (d <= r1 ? 1u : 2u); }
    float probability(float d, uint32_t l) const {
        if (l == 0) return 1.0f;
        if (l == 2) return outer;
        float t = std::clamp((d - r0) / std::max(r1 - r0, 1e-20f), 0.0f, 1.0f);
        return 1.0f * (1.0f - t) + outer * t;  // GLSL mix
    }
    // The mask word the shader writes.
    uint32_t word(const scene::layout::CameraInfo& c, uint32_t x, uint32_t y,
                  uint32_t width) const {
        float d = distance(c, x, y);
        uint32_t l = layer(d);
        uint32_t h = sampling::sampleListHash(y * width + x, seed);
        bool sampled = float(h >> 8) * (1.0f / 16777216.0f) < probability(d, l);
        return sampled ? (1u | (l << 1) | (spp[l] << 16)) : (l << 1);
    }
};

class FoveationMaskTest : public GpuTest {
protected:
    static void SetUpTestSuite() { registerBuiltinPasses(); }

    // The pass declares kSceneGeometry (for its cache key, see the pass header): a tiny scene.
    static const scene::SceneGpu& planeGpu() {
        static const scene::Scene s = scene::loadBuiltinScene("builtin:plane");
        static const auto g = std::make_unique<scene::SceneGpu>(ctx(), s);
        return *g;
    }
    static scene::CameraDesc planeCamera() {
        static const scene::Scene s = scene::loadBuiltinScene("builtin:plane");
        return s.cameras.empty() ? s.defaultCamera() : s.cameras.front();
    }

    static scene::FrameCamera camera(uint32_t width, uint32_t height, bool stereo,
                                     glm::vec2 left = glm::vec2(0.5f),
                                     glm::vec2 right = glm::vec2(0.5f)) {
        scene::CameraRigOptions rig;
        rig.stereo = stereo;
        const glm::vec2 gaze[scene::kMaxEyes] = {left, right};
        return scene::makeFrameCamera(planeCamera(), width, height, rig, 0, nullptr, gaze);
    }

    static std::string maskGraph(const std::string& params, const std::string& extraPasses = "",
                                 const std::string& edges = "",
                                 const std::string& outputs = R"("fm.layout", "fm.mask")") {
        return R"({ "version": 1, "name": "foveation_test", "passes": [ { "name": "fm", )"
               R"("type": "FoveationMask", "params": )" +
               params + " }" + extraPasses + R"( ], "edges": [ )" + edges + R"( ], "outputs": [ )" +
               outputs + " ] }";
    }

    static std::unique_ptr<RenderGraph> makeGraph(uint32_t width, uint32_t height,
                                                  const std::string& text) {
        CompileOptions o;
        o.width = width;
        o.height = height;
        o.sceneFeatures = planeGpu().features() | kSceneStereo;
        auto g = std::make_unique<RenderGraph>(ctx(), passRegistry());
        g->setScene(&planeGpu());
        g->setSeed(kGraphSeed);
        g->build(parseGraphText(text, "foveation_test"), o);
        return g;
    }

    static std::vector<uint32_t> mask(const RenderGraph& g) {
        auto bytes = g.image("fm.mask").download(ctx());
        std::vector<uint32_t> m(bytes.size() / 4);
        std::memcpy(m.data(), bytes.data(), m.size() * 4);
        return m;
    }
    static SampleLayout layout(const RenderGraph& g) {
        return SampleLayout::parse(
            g.bufferFor(g.plan().findNode("fm"), sampling::kSampleLayoutField).download(ctx()));
    }
    static PassStatus status(const RenderGraph& g) {
        return g.records()[g.plan().findNode("fm")].status;
    }

    // The layout lists exactly the mask's sampled pixels, row-major, each with the mask's spp.
    static void expectLayoutMatchesMask(const SampleLayout& l, const std::vector<uint32_t>& m,
                                        uint32_t width, uint32_t height) {
        EXPECT_TRUE(sampling::validateSampleLayout(l, width, height).empty());
        size_t k = 0;
        for (uint32_t i = 0; i < m.size(); ++i) {
            if (!(m[i] & 1u)) continue;
            ASSERT_LT(k, l.entries.size()) << "layout shorter than the mask's sampled pixels";
            ASSERT_EQ(l.entries[k].pixel, sampling::packSamplePixel(i % width, i / width))
                << "entry " << k;
            ASSERT_EQ(l.entries[k].samples, m[i] >> 16) << "entry " << k;
            ++k;
        }
        EXPECT_EQ(k, l.entries.size()) << "layout longer than the mask's sampled pixels";
    }

    // Pixels where the GPU mask differs from the CPU twin (float rounding right at a radius or
    // at the toss threshold may flip a handful).
    static size_t mismatches(const std::vector<uint32_t>& m, const Model& model,
                             const scene::FrameCamera& cam, uint32_t width, uint32_t height) {
        const auto info = scene::layout::packCamera(cam, 0, 0);
        size_t bad = 0;
        for (uint32_t y = 0; y < height; ++y)
            for (uint32_t x = 0; x < width; ++x)
                bad += m[size_t(y) * width + x] != model.word(info, x, y, width);
        return bad;
    }
};

// Seed 000 Table 1, FHD: 1920x1080 side by side (960x1080 per eye), r0 = 144, r1 = 288, default
// probabilities. Per eye and layer: pixel counts (areas) against the model and Table 1's Area
// column; sampled pixels and samples against the model's expectation (sum of probabilities).
TEST_F(FoveationMaskTest, FhdStereoLayerCountsMatchTheModel) {
    constexpr uint32_t kW = 1920, kH = 1080;
    auto g = makeGraph(kW, kH, maskGraph("{}"));
    const scene::FrameCamera cam = camera(kW, kH, true);
    g->setCamera(cam);
    g->runFrame();
    const std::vector<uint32_t> m = mask(*g);
    ASSERT_EQ(m.size(), size_t(kW) * kH);

    Model model;
    const auto info = scene::layout::packCamera(cam, 0, 0);
    double expectSampled[2][3] = {}, expectSamples[2][3] = {};
    size_t modelArea[2][3] = {}, area[2][3] = {}, sampled[2][3] = {}, samples[2][3] = {};
    for (uint32_t y = 0; y < kH; ++y)
        for (uint32_t x = 0; x < kW; ++x) {
            const uint32_t eye = x / (kW / 2);
            const float d = model.distance(info, x, y);
            const uint32_t l = model.layer(d);
            const double p = model.probability(d, l);
            ++modelArea[eye][l];
            expectSampled[eye][l] += p;
            expectSamples[eye][l] += p * model.spp[l];

            const uint32_t w = m[size_t(y) * kW + x];
            const uint32_t gl = (w >> 1) & 3u;
            ASSERT_LT(gl, 3u) << x << "," << y;
            ++area[eye][gl];
            if (w & 1u) {
                ++sampled[eye][gl];
                samples[eye][gl] += w >> 16;
            }
            if (gl == 0) {
                ASSERT_TRUE(w & 1u) << "fovea pixel " << x << "," << y << " not sampled";
            }
        }
    const double tableArea[3] = {65144, 195432, 776224};  // Table 1, FHD, per screen
    for (int eye = 0; eye < 2; ++eye)
        for (int l = 0; l < 3; ++l) {
            SCOPED_TRACE("eye " + std::to_string(eye) + " layer " + std::to_string(l));
            EXPECT_NEAR(double(area[eye][l]), double(modelArea[eye][l]), 0.001 * modelArea[eye][l]);
            EXPECT_NEAR(double(area[eye][l]), tableArea[l], 0.01 * tableArea[l]);
            EXPECT_NEAR(double(sampled[eye][l]), expectSampled[eye][l],
                        0.01 * expectSampled[eye][l]);
            EXPECT_NEAR(double(samples[eye][l]), expectSamples[eye][l],
                        0.01 * expectSamples[eye][l]);
            std::printf(
                "eye %d layer %d: area %zu (Table 1 %.0f), sampled %zu (model %.1f), "
                "samples %zu (model %.1f)\n",
                eye, l, area[eye][l], tableArea[l], sampled[eye][l], expectSampled[eye][l],
                samples[eye][l], expectSamples[eye][l]);
        }
    // The middle ring really thins out: fewer than all, more than the outer probability.
    EXPECT_LT(double(sampled[0][1]), 0.9 * area[0][1]);
    EXPECT_GT(double(sampled[0][1]), 0.6 * area[0][1]);

    expectLayoutMatchesMask(layout(*g), m, kW, kH);
    uint32_t maxSamples;
    auto bytes =
        g->bufferFor(g->plan().findNode("fm"), sampling::kSampleLayoutField).download(ctx());
    std::memcpy(&maxSamples, bytes.data() + 4, 4);
    EXPECT_EQ(maxSamples, 4u);
}

TEST_F(FoveationMaskTest, MaskMatchesTheCpuModelInPixelsAndDegrees) {
    constexpr uint32_t kW = 64, kH = 32;
    const scene::FrameCamera cam = camera(kW, kH, true, {0.3f, 0.6f}, {0.7f, 0.4f});
    for (bool degrees : {false, true}) {
        SCOPED_TRACE(degrees ? "degrees" : "pixels");
        Model model;
        model.degrees = degrees;
        model.r0 = degrees ? 6.0f : 5.0f;
        model.r1 = degrees ? 15.0f : 11.0f;
        model.outer = 0.25f;
        model.spp[0] = 5;
        model.spp[1] = 2;
        model.spp[2] = 1;
        model.seed = sampling::sampleListSeed(kGraphSeed + 3ull * 0x9E3779B97F4A7C15ull, 0, false);
        const std::string params = std::string(R"({ "r0": )") + std::to_string(model.r0) +
                                   R"(, "r1": )" + std::to_string(model.r1) +
                                   R"(, "radiusUnit": ")" + (degrees ? "degrees" : "pixels") +
                                   R"(", "outerProbability": 0.25, "sppFovea": 5, )"
                                   R"("sppMiddle": 2, "sppOuter": 1, "seed": 3 })";
        auto g = makeGraph(kW, kH, maskGraph(params));
        g->setCamera(cam);
        g->runFrame();
        const auto m = mask(*g);
        EXPECT_LE(mismatches(m, model, cam, kW, kH), size_t(4));
        size_t layers[3] = {};
        for (uint32_t w : m) ++layers[(w >> 1) & 3u];
        EXPECT_GT(layers[0], 20u);
        EXPECT_GT(layers[1], 20u);
        EXPECT_GT(layers[2], 20u);
        expectLayoutMatchesMask(layout(*g), m, kW, kH);
    }
}

TEST_F(FoveationMaskTest, SameSeedSameMaskOtherSeedOtherAndCachedUntilGazeChanges) {
    constexpr uint32_t kW = 64, kH = 32;
    const std::string p = R"({ "r0": 4, "r1": 10 , "seed": )";
    auto a = makeGraph(kW, kH, maskGraph(p + "1 }"));
    auto b = makeGraph(kW, kH, maskGraph(p + "1 }"));
    auto c = makeGraph(kW, kH, maskGraph(p + "2 }"));
    const scene::FrameCamera cam = camera(kW, kH, true);
    for (auto* g : {a.get(), b.get(), c.get()}) {
        g->setCamera(cam);
        g->runFrame();
    }
    const auto ma = mask(*a);
    EXPECT_EQ(ma, mask(*b));
    EXPECT_EQ(layout(*a).bytes(), layout(*b).bytes());
    EXPECT_NE(ma, mask(*c)) << "another seed, another toss";

    // Fixed per gaze (seed 000 §3.2): the next frame is served from the cache, unchanged.
    a->setCamera(cam);
    a->runFrame();
    EXPECT_EQ(status(*a), PassStatus::Cached);
    EXPECT_EQ(mask(*a), ma);
    // A new gaze recomputes.
    a->setCamera(camera(kW, kH, true, {0.2f, 0.5f}, {0.8f, 0.5f}));
    a->runFrame();
    EXPECT_EQ(status(*a), PassStatus::Executed);
    EXPECT_NE(mask(*a), ma);

    // animate: a new toss every frame, never cached.
    auto anim = makeGraph(kW, kH,
                          maskGraph(R"({ "r0": 4, "r1": 10 , )"
                                    R"("animate": true })"));
    anim->setCamera(cam);
    anim->runFrame();
    const auto f0 = mask(*anim);
    anim->setCamera(cam);
    anim->runFrame();
    EXPECT_EQ(status(*anim), PassStatus::Executed);
    EXPECT_NE(mask(*anim), f0);
}

TEST_F(FoveationMaskTest, EachEyeUsesItsOwnGaze) {
    constexpr uint32_t kW = 96, kH = 32;  // 48x32 per eye
    const glm::vec2 gaze[2] = {{0.25f, 0.3f}, {0.7f, 0.75f}};
    auto g = makeGraph(kW, kH, maskGraph(R"({ "r0": 5, "r1": 9 })"));
    g->setCamera(camera(kW, kH, true, gaze[0], gaze[1]));
    g->runFrame();
    const auto m = mask(*g);
    for (uint32_t eye = 0; eye < 2; ++eye) {
        // The fovea's centroid sits on this eye's gaze point.
        glm::dvec2 sum(0.0);
        size_t n = 0;
        for (uint32_t y = 0; y < kH; ++y)
            for (uint32_t x = eye * kW / 2; x < (eye + 1) * kW / 2; ++x)
                if (((m[size_t(y) * kW + x] >> 1) & 3u) == 0u) {
                    EXPECT_TRUE(m[size_t(y) * kW + x] & 1u);
                    sum += glm::dvec2(x - eye * kW / 2 + 0.5, y + 0.5);
                    ++n;
                }
        ASSERT_GT(n, 50u) << "eye " << eye;
        glm::dvec2 c = sum / double(n);
        EXPECT_NEAR(c.x, gaze[eye].x * kW / 2, 0.75) << "eye " << eye;
        EXPECT_NEAR(c.y, gaze[eye].y * kH, 0.75) << "eye " << eye;
    }
}

// The layout drives PathTrace: exactly the mask's sampled pixels are traced, each with its
// layer's spp (radiance alpha = sample count), the others stay invalid (alpha 0).
TEST_F(FoveationMaskTest, PathTraceTracesExactlyTheMaskPixels) {
    constexpr uint32_t kW = 32, kH = 16;
    auto g = makeGraph(
        kW, kH,
        maskGraph(R"({ "r0": 3, "r1": 6, "sppFovea": 3, "sppMiddle": 2, )"
                  R"("sppOuter": 1 })",
                  R"(, { "name": "pt", "type": "PathTrace", "params": { "spp": 7 } })",
                  R"({ "from": "fm.layout", "to": "pt.layout" })", R"("pt.radiance", "fm.mask")"));
    g->setCamera(camera(kW, kH, true, {0.4f, 0.5f}, {0.6f, 0.5f}));
    g->runFrame();
    const auto m = mask(*g);
    const auto rad = g->image("pt.radiance").downloadRGBA32F(ctx());
    size_t traced = 0;
    for (size_t i = 0; i < m.size(); ++i) {
        const float expected = (m[i] & 1u) ? float(m[i] >> 16) : 0.0f;
        ASSERT_EQ(rad[4 * i + 3], expected) << "pixel " << i % kW << "," << i / kW;
        traced += (m[i] & 1u) != 0u;
    }
    EXPECT_GT(traced, 0u);
    EXPECT_LT(traced, m.size());
}

TEST_F(FoveationMaskTest, BadParametersAreClearErrors) {
    auto expectError = [&](const std::string& params, const std::string& word) {
        try {
            makeGraph(32, 16, maskGraph(params));
            ADD_FAILURE() << "expected an error for " << params;
        } catch (const std::exception& e) {
            EXPECT_NE(std::string(e.what()).find(word), std::string::npos) << e.what();
        }
    };
    expectError(R"({ "r0": 10, "r1": 5 })", "params.r1");
    expectError(R"({ "radiusUnit": "degrees", "r0": 10, "r1": 200 })", "params.r1");
}

// Issue 15 §1: graphs/peres_nh2ld.json and peres_nh3ld.json follow seed 000 Table 1 (every pixel
// of every layer traced, 4/3/2 spp: 58 % of Base's samples); the *_sparse graphs follow §3.2's
// random sub-sampling. Each graph's own mask parameters at Table 1's size (FHD stereo, 960x1080
// per eye; the graphs' radii are for their 960x540 default, so r0/r1 = 144/288 here): per eye and
// layer, the pixels and samples the layout hands PathTrace against Table 1's Area and Samples.
TEST_F(FoveationMaskTest, PeresGraphsTraceTable1sCounts) {
    constexpr uint32_t kW = 1920, kH = 1080;
    const double tableArea[3] = {65144, 195432, 776224};       // Table 1, FHD, per screen
    const double tableSamples[3] = {260576, 586296, 1552448};  // Area x 4 / 3 / 2 spp
    const double baseSamples = 4.0 * (kW / 2) * kH;            // Base: 4 spp everywhere
    const std::string graphs = std::string(FOVEA_TEST_DIR) + "/../graphs/";
    auto maskParams = [&](const std::string& file) {
        for (const auto& pass : parseGraphFile(graphs + file).passes)
            if (pass.type == "FoveationMask") return pass.params;
        ADD_FAILURE() << file << " has no FoveationMask pass";
        return nlohmann::json::object();
    };
    EXPECT_EQ(maskParams("peres_nh2ld.json"), maskParams("peres_nh3ld.json"));
    EXPECT_EQ(maskParams("peres_nh2ld_sparse.json"), maskParams("peres_nh3ld_sparse.json"));
    for (const bool table1 : {true, false}) {
        const std::string file = table1 ? "peres_nh3ld.json" : "peres_nh3ld_sparse.json";
        SCOPED_TRACE(file);
        nlohmann::json params = maskParams(file);
        params["r0"] = 144;
        params["r1"] = 288;
        auto g = makeGraph(kW, kH, maskGraph(params.dump()));
        g->setCamera(camera(kW, kH, true));
        g->runFrame();
        const std::vector<uint32_t> m = mask(*g);
        double area[2][3] = {}, traced[2][3] = {}, samples[2][3] = {};
        for (size_t i = 0; i < m.size(); ++i) ++area[(i % kW) / (kW / 2)][(m[i] >> 1) & 3u];
        for (const auto& e : layout(*g).entries) {
            const glm::uvec2 px = sampling::unpackSamplePixel(e.pixel);
            const uint32_t l = (m[size_t(px.y) * kW + px.x] >> 1) & 3u;
            ++traced[px.x / (kW / 2)][l];
            samples[px.x / (kW / 2)][l] += e.samples;
        }
        for (int eye = 0; eye < 2; ++eye) {
            double total = 0;
            for (int l = 0; l < 3; ++l) {
                SCOPED_TRACE("eye " + std::to_string(eye) + " layer " + std::to_string(l));
                EXPECT_NEAR(area[eye][l], tableArea[l], 0.01 * tableArea[l]);
                if (table1) {
                    EXPECT_EQ(traced[eye][l], area[eye][l]);
                    EXPECT_EQ(samples[eye][l], area[eye][l] * double(4 - l));
                    EXPECT_NEAR(samples[eye][l], tableSamples[l], 0.01 * tableSamples[l]);
                }
                total += samples[eye][l];
            }
            std::printf("%s eye %d: %.0f samples = %.1f %% of Base\n", file.c_str(), eye, total,
                        100.0 * total / baseSamples);
            if (table1)
                EXPECT_NEAR(total / baseSamples, 0.579, 0.006);  // Table 1: 2,399,320 / 4,147,200
            else
                EXPECT_LT(total / baseSamples, 0.45);  // §3.2's sub-sampling traces fewer
        }
    }
}

}  // namespace
